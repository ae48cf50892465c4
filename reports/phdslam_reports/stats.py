"""Monte Carlo statistics for the report: standard errors, paper comparisons, bands and fits."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Sequence

import numpy as np
from scipy import stats as scipy_stats

FLAG_TOLERANCE = 0.15
"""Relative difference to the paper above which a cell is flagged (15 %)."""


def standard_error_from_std(std: float, runs: float) -> float:
    """std / sqrt(runs): the standard error of a mean over ``runs`` runs (NaN if undefined)."""
    if runs is None or std is None or not math.isfinite(std) or not runs or runs < 2:
        return math.nan
    return float(std) / math.sqrt(float(runs))


def standard_error_of_values(values: Sequence[float]) -> float:
    """Sample std (n - 1) of the finite ``values`` divided by sqrt(n); NaN for n < 2.

    For a pooled RMSE this is the Monte Carlo spread of the per-run RMSEs over sqrt(runs).
    """
    finite = np.asarray([v for v in values if v is not None and math.isfinite(v)], dtype=float)
    if finite.size < 2:
        return math.nan
    return float(np.std(finite, ddof=1) / math.sqrt(finite.size))


def relative_difference(ours: float, paper: float) -> float:
    """(ours - paper) / |paper|; NaN when either is missing or the paper's value is 0."""
    if ours is None or paper is None or not math.isfinite(ours) or not math.isfinite(paper):
        return math.nan
    if paper == 0:
        return math.nan
    return (ours - paper) / abs(paper)


def is_flagged(ours: float, paper: float, tolerance: float = FLAG_TOLERANCE,
               only_above: bool = False) -> bool:
    """True when ours is more than ``tolerance`` (relative) away from the paper's value.

    With ``only_above`` only a value above the paper's counts (a time per step: being faster is
    not a deviation). A paper value of 0 (e.g. 0 % resampling) has no relative scale: any
    non-zero value of ours (any positive one with ``only_above``) is then flagged. Missing values
    are never flagged.
    """
    if ours is None or paper is None or not math.isfinite(ours) or not math.isfinite(paper):
        return False
    if paper == 0:
        return ours > 1e-12 if only_above else abs(ours) > 1e-12
    relative = relative_difference(ours, paper)
    return relative > tolerance if only_above else abs(relative) > tolerance


@dataclass(frozen=True)
class Band:
    """Per-step mean and percentile band over runs."""

    mean: np.ndarray
    low: np.ndarray
    high: np.ndarray
    count: np.ndarray  # runs with a finite value at each step


def band_over_runs(matrix: np.ndarray, low_pct: float = 5.0, high_pct: float = 95.0) -> Band:
    """Mean and [low_pct, high_pct] percentiles over the rows (runs) of a runs x steps matrix.

    NaN entries (missing steps or values) are ignored; steps without any value give NaN.
    """
    matrix = np.asarray(matrix, dtype=float)
    finite = np.isfinite(matrix)
    count = np.sum(finite, axis=0)
    total = np.where(finite, matrix, 0.0).sum(axis=0)
    with np.errstate(invalid="ignore", divide="ignore"):
        mean = np.where(count > 0, total / np.maximum(count, 1), np.nan)
    return Band(mean=mean, low=column_percentile(matrix, low_pct),
                high=column_percentile(matrix, high_pct), count=count)


def column_percentile(matrix: np.ndarray, pct: float) -> np.ndarray:
    """Percentile of the finite values of each column (linear interpolation, as numpy's default).

    Vectorised over columns: sorting puts NaN last, so each column's finite values come first.
    Columns without a finite value give NaN.
    """
    matrix = np.where(np.isfinite(matrix), matrix, np.nan)
    ordered = np.sort(matrix, axis=0)
    count = np.sum(np.isfinite(matrix), axis=0)
    position = (np.maximum(count, 1) - 1) * pct / 100.0
    below = np.floor(position).astype(int)
    above = np.minimum(below + 1, np.maximum(count - 1, 0))
    fraction = position - below
    columns = np.arange(matrix.shape[1])
    lower = ordered[below, columns] if matrix.shape[0] else np.full(matrix.shape[1], np.nan)
    upper = ordered[above, columns] if matrix.shape[0] else np.full(matrix.shape[1], np.nan)
    result = lower + fraction * (upper - lower)
    return np.where(count > 0, result, np.nan)


def nan_mean(values: np.ndarray) -> float:
    """Mean of the values that are not NaN, as numpy's nanmean (an infinite value stays in it), but
    NaN without nanmean's empty-slice warning when every value is NaN or there is none."""
    values = np.asarray(values, dtype=float)
    present = values[~np.isnan(values)]
    return float(present.mean()) if present.size else math.nan


def stack_ragged(series: Sequence[np.ndarray]) -> np.ndarray:
    """Rows of unequal length as one matrix padded with NaN."""
    width = max((len(s) for s in series), default=0)
    matrix = np.full((len(series), width), np.nan)
    for i, s in enumerate(series):
        matrix[i, : len(s)] = s
    return matrix


def nees_bounds(runs: int, dof: int = 3, confidence: float = 0.95) -> tuple[float, float]:
    """Two-sided chi-square bounds of a NEES averaged over ``runs`` runs of ``dof`` dimensions.

    The sum over runs of NEES values is chi-square with dof x runs degrees of freedom, so the
    bounds of the average are chi2.ppf((1 -/+ confidence) / 2, dof x runs) / runs.
    """
    if runs < 1:
        raise ValueError("nees_bounds: runs must be at least 1")
    tail = (1.0 - confidence) / 2.0
    total = dof * runs
    return (
        float(scipy_stats.chi2.ppf(tail, total) / runs),
        float(scipy_stats.chi2.ppf(1.0 - tail, total) / runs),
    )


def fraction_inside(values: np.ndarray, low: float, high: float) -> float:
    """Fraction of the finite ``values`` within [low, high] (NaN when there are none)."""
    values = np.asarray(values, dtype=float)
    finite = values[np.isfinite(values)]
    if finite.size == 0:
        return math.nan
    return float(np.mean((finite >= low) & (finite <= high)))


@dataclass(frozen=True)
class PowerLaw:
    """y = coefficient * x ** exponent, fitted in log-log space."""

    exponent: float
    coefficient: float
    points: int


def fit_power_law(x: Sequence[float], y: Sequence[float]) -> PowerLaw | None:
    """Least-squares line through (log x, log y) over the positive pairs; None with < 2 x values."""
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    keep = np.isfinite(x) & np.isfinite(y) & (x > 0) & (y > 0)
    if np.unique(x[keep]).size < 2:
        return None
    slope, intercept = np.polyfit(np.log(x[keep]), np.log(y[keep]), 1)
    return PowerLaw(exponent=float(slope), coefficient=float(math.exp(intercept)),
                    points=int(np.sum(keep)))
