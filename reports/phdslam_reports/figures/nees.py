"""Pose NEES averaged over runs, with two-sided 95 % chi-square bounds."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np
from matplotlib.figure import Figure

from ..stats import fraction_inside, nees_bounds
from ..style import estimator_colour, panel_grid

POSE_DOF = 3
#: chi2.ppf(0.95, 3): a pose NEES at or below it puts the truth inside the 95 % ellipsoid.
COVERAGE_THRESHOLD = 7.814727903251178
#: Highest run-averaged NEES drawn. A filter whose particles collapse reaches 1e300 (and a mean
#: over runs then overflows to infinity), which a log axis cannot label; such steps are drawn at
#: this ceiling and the legend says so.
DRAW_CEILING = 1e100


@dataclass
class NeesSeries:
    """Run-averaged NEES of one group at each step, with its bounds."""

    estimator: str
    particles: int
    runs: int
    mean: np.ndarray
    low: float
    high: float
    coverage: float = float("nan")

    @property
    def median(self) -> float:
        """Median over the used steps of the run-averaged NEES."""
        used = self.mean[np.isfinite(self.mean)]
        return float(np.median(used)) if used.size else float("nan")

    @property
    def inside(self) -> float:
        """Fraction of steps whose run-averaged NEES is within the bounds."""
        return fraction_inside(self.mean, self.low, self.high)


def nees_series(estimator: str, particles: int, matrix: np.ndarray) -> NeesSeries | None:
    """Averages a runs x steps NEES matrix over runs (steps where every run has a value)."""
    matrix = np.asarray(matrix, dtype=float)
    if matrix.size == 0 or not np.any(np.isfinite(matrix)):
        return None
    runs = matrix.shape[0]
    complete = np.all(np.isfinite(matrix), axis=0)
    mean = np.full(matrix.shape[1], np.nan)
    with np.errstate(over="ignore"):  # a sum beyond the double range is +inf: outside the bounds
        mean[complete] = np.mean(matrix[:, complete], axis=0)
    low, high = nees_bounds(runs, POSE_DOF)
    values = matrix[np.isfinite(matrix)]
    coverage = float(np.mean(values <= COVERAGE_THRESHOLD))
    return NeesSeries(estimator, particles, runs, mean, low, high, coverage)


def plot_nees(series: list[NeesSeries], display_name: Callable[[str], str] = str) -> Figure | None:
    """One panel per group: averaged NEES over steps on a log axis, bounds as dashed lines."""
    if not series:
        return None
    fig, axes = panel_grid(len(series))
    estimators = [s.estimator for s in series]
    for ax, s in zip(axes, series):
        k = np.arange(s.mean.size)
        drawn = np.minimum(s.mean, DRAW_CEILING)  # NaN stays NaN, +inf becomes the ceiling
        clipped = bool(np.any(s.mean > DRAW_CEILING))  # NaN compares false
        ax.plot(k, drawn, color=estimator_colour(s.estimator, estimators), lw=1.0,
                label=f"mean NEES over {s.runs} runs" +
                (f" (above {DRAW_CEILING:.0e} drawn at it)" if clipped else ""))
        ax.axhline(s.low, color="#333", ls="--", lw=1.0, label="95 % chi-square bounds")
        ax.axhline(s.high, color="#333", ls="--", lw=1.0)
        ax.axhline(POSE_DOF, color="#888", ls=":", lw=1.0, label=f"expected ({POSE_DOF})")
        positive = drawn[np.isfinite(drawn) & (drawn > 0)]
        if positive.size and positive.max() / max(positive.min(), 1e-12) > 50:
            ax.set_yscale("log")
        ax.set_title(f"{display_name(s.estimator)}, N = {s.particles}: "
                     f"{100 * s.inside:.1f} % of steps inside")
        ax.set_xlabel("step k")
        ax.set_ylabel("pose NEES (3 dof)")
        ax.legend(loc="best", framealpha=0.85)
    fig.tight_layout()
    return fig
