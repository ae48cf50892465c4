"""Normalised innovation squared (NIS) pooled over runs at each step, with its 95 % bounds.

At step k the runs' NIS sums and measurement counts are pooled: NIS_k = sum_r nis_sum / sum_r
nis_count, the NIS per measurement. For a consistent filter sum_r nis_sum is chi-square with
2 C_k degrees of freedom (C_k = sum_r nis_count), so the two-sided bounds of NIS_k are
chi2.ppf(0.025 and 0.975, 2 C_k) / C_k: they narrow where many measurements are pooled. This is
the computation of summary.csv's nis_mean / nis_median / nis_fraction_inside
(validation/runner/results/summary.cc), drawn per step.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np
from matplotlib.figure import Figure
from scipy import stats as scipy_stats

from ..style import estimator_colour, panel_grid

MEASUREMENT_DOF = 2


@dataclass
class NisSeries:
    """Pooled NIS per measurement of one group at each step (NaN where no run had any)."""

    estimator: str
    particles: int
    runs: int
    nis: np.ndarray
    low: np.ndarray
    high: np.ndarray
    pooled_mean: float

    @property
    def median(self) -> float:
        """Median over the steps with measurements of the pooled NIS."""
        used = self.nis[np.isfinite(self.nis)]
        return float(np.median(used)) if used.size else float("nan")

    @property
    def inside(self) -> float:
        """Fraction of the steps with measurements whose pooled NIS is within its bounds."""
        used = np.isfinite(self.nis)
        if not np.any(used):
            return float("nan")
        ok = (self.nis[used] >= self.low[used]) & (self.nis[used] <= self.high[used])
        return float(np.mean(ok))


def nis_series(estimator: str, particles: int, sums: np.ndarray,
               counts: np.ndarray) -> NisSeries | None:
    """Pools runs x steps matrices of nis_sum and nis_count (NaN or missing read as 0)."""
    sums = np.nan_to_num(np.asarray(sums, dtype=float), nan=0.0)
    counts = np.nan_to_num(np.asarray(counts, dtype=float), nan=0.0)
    if sums.shape != counts.shape:
        raise ValueError(f"nis_series: nis_sum {sums.shape} and nis_count {counts.shape} differ")
    if sums.size == 0:
        return None
    pooled_sum = sums.sum(axis=0)
    pooled_count = counts.sum(axis=0)
    used = pooled_count > 0
    if not np.any(used):
        return None
    nis = np.full(pooled_count.shape, np.nan)
    low = np.full(pooled_count.shape, np.nan)
    high = np.full(pooled_count.shape, np.nan)
    c = pooled_count[used]
    nis[used] = pooled_sum[used] / c
    low[used] = scipy_stats.chi2.ppf(0.025, MEASUREMENT_DOF * c) / c
    high[used] = scipy_stats.chi2.ppf(0.975, MEASUREMENT_DOF * c) / c
    pooled_mean = float(pooled_sum[used].sum() / c.sum())
    return NisSeries(estimator, particles, sums.shape[0], nis, low, high, pooled_mean)


def plot_nis(series: list[NisSeries], display_name: Callable[[str], str] = str) -> Figure | None:
    """One panel per group: pooled NIS over steps on a log axis, its bounds as a band."""
    if not series:
        return None
    fig, axes = panel_grid(len(series))
    estimators = [s.estimator for s in series]
    for ax, s in zip(axes, series):
        k = np.arange(s.nis.size)
        ax.fill_between(k, s.low, s.high, color="#bbb", alpha=0.6, lw=0,
                        label="95 % chi-square bounds")
        ax.plot(k, s.nis, color=estimator_colour(s.estimator, estimators), lw=0.8,
                label=f"NIS per measurement, {s.runs} runs pooled")
        ax.axhline(MEASUREMENT_DOF, color="#333", ls=":", lw=1.0,
                   label=f"expected ({MEASUREMENT_DOF})")
        ax.set_yscale("log")
        ax.set_title(f"{display_name(s.estimator)}, N = {s.particles}: "
                     f"{100 * s.inside:.1f} % of steps inside")
        ax.set_xlabel("step k")
        ax.set_ylabel("NIS per measurement (2 dof)")
        ax.legend(loc="best", framealpha=0.85)
    fig.tight_layout()
    return fig
