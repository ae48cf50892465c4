"""A filter against the graph-optimisation smoothers of the same results folder.

The smoothers (``smoother-*``, the batch ones, and ``window*``, the fixed-lag ones) use every
measurement for every pose, so on the same data they should bound the filters from below: the
estimator with the lower position error is the ceiling. This module picks the filter (the online
estimator with the lowest pooled position RMSE, dead reckoning and the bounds left out), the
first seed the filter and the smoothers share, and draws the position error over time and the
trajectories over the truth (or the GPS fixes of real data without true poses).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np
from matplotlib.figure import Figure

from ..bound_efficiency import BOUNDS
from ..results import Group, ResultsFolder
from ..style import GPS_COLOUR, TRUTH_COLOUR, estimator_colour, new_figure

SMOOTHER_PREFIXES = ("smoother-", "window")
"""Estimator names of the graph-optimisation smoothers."""

FLOOR_ESTIMATORS = ("odometry",)
"""Estimators that are floors, never the filter drawn against the smoothers."""

# The posterior Cramer-Rao bounds hold a bound, not an estimate: neither the filter nor the ceiling.
LEFT_OUT = FLOOR_ESTIMATORS + BOUNDS


def is_smoother(estimator: str) -> bool:
    """True for the graph-optimisation smoothers' estimator names."""
    return estimator.startswith(SMOOTHER_PREFIXES)


@dataclass
class Contender:
    """One group of the comparison: its pooled position RMSE over every run of the folder."""

    group: Group
    pos_rmse_m: float


@dataclass
class CeilingComparison:
    """The filter, the smoothers, the seed drawn and which estimator is the ceiling."""

    filter: Contender
    smoothers: list[Contender]
    seed: int

    @property
    def ceiling(self) -> Contender:
        """The contender with the lowest pooled position RMSE (the filter on a tie)."""
        best = self.filter
        for s in self.smoothers:
            if s.pos_rmse_m < best.pos_rmse_m:
                best = s
        return best


def _pooled_rmse(folder: ResultsFolder, group: Group) -> float:
    row = folder.summary_row(group)
    if row is None:
        return math.nan
    try:
        return float(row.get("pos_rmse_m", math.nan))
    except (TypeError, ValueError):
        return math.nan


def ceiling_comparison(folder: ResultsFolder) -> CeilingComparison | None:
    """The comparison of ``folder``, or None when it lacks a filter, a smoother, a finite position
    RMSE for either, or a seed with steps.csv they share."""
    filters, smoothers = [], []
    for group in folder.groups():
        rmse = _pooled_rmse(folder, group)
        if not math.isfinite(rmse) or group.estimator in LEFT_OUT:
            continue
        (smoothers if is_smoother(group.estimator) else filters).append(Contender(group, rmse))
    if not filters or not smoothers:
        return None
    best_filter = min(filters, key=lambda c: (c.pos_rmse_m, c.group))
    shared = set(folder.seeds(best_filter.group))
    for s in smoothers:
        shared &= set(folder.seeds(s.group))
    if not shared:
        return None
    return CeilingComparison(best_filter, sorted(smoothers, key=lambda c: c.group), min(shared))


def ceiling_sentence(comparison: CeilingComparison, name: Callable[[str], str]) -> str:
    """Which estimator is the ceiling, and every smoother against the filter, in words."""
    f = comparison.filter
    ceiling = comparison.ceiling
    label = f"{name(ceiling.group.estimator)} (N = {ceiling.group.particles})"
    parts = [f"The ceiling is {label}: the lowest pooled position RMSE, "
             f"{ceiling.pos_rmse_m:.3g} m."]
    for s in comparison.smoothers:
        verdict = "below" if s.pos_rmse_m < f.pos_rmse_m else "not below"
        parts.append(f"{name(s.group.estimator)}: {s.pos_rmse_m:.3g} m, {verdict} the filter "
                     f"{name(f.group.estimator)} (N = {f.group.particles}, "
                     f"{f.pos_rmse_m:.3g} m).")
    if ceiling is f:
        parts.append("No smoother bounds the filter here: the smoothers are not a ceiling on "
                     "these data.")
    return " ".join(parts)


def plot_filter_vs_smoothers(folder: ResultsFolder, comparison: CeilingComparison,
                             name: Callable[[str], str] = str) -> Figure:
    """Position error over the steps (left) and the trajectories over the truth or the GPS
    fixes (right), for the comparison's seed."""
    contenders = [comparison.filter] + comparison.smoothers
    known = [c.group.estimator for c in contenders]
    fig, axes = new_figure(13.0, 4.6, 1, 2)
    error_ax, path_ax = axes[0][0], axes[0][1]
    truth_drawn = False
    for index, c in enumerate(contenders):
        steps = folder.steps(c.group, comparison.seed)
        colour = estimator_colour(c.group.estimator, known)
        style = "-" if index == 0 else "--"
        label = f"{name(c.group.estimator)} (N = {c.group.particles})"
        error_ax.plot(steps.num("step"), steps.num("pos_err_m"), style, color=colour, label=label)
        if not truth_drawn:
            xt, yt = steps.num("x_true"), steps.num("y_true")
            if np.any(np.isfinite(xt) & np.isfinite(yt)):
                path_ax.plot(xt, yt, "-", color=TRUTH_COLOUR, linewidth=2.2, label="truth")
            else:
                gps = folder.gps(comparison.seed)
                if gps is not None:
                    path_ax.plot(gps.num("x"), gps.num("y"), ".", color=GPS_COLOUR, markersize=2,
                                 label="GPS")
            truth_drawn = True
        path_ax.plot(steps.num("x"), steps.num("y"), style, color=colour, label=label)
    folder.forget_steps()
    error_ax.set_xlabel("step")
    error_ax.set_ylabel("position error (m)")
    error_ax.set_title(f"Position error, seed {comparison.seed}")
    error_ax.legend(fontsize=8)
    path_ax.set_xlabel("x (m)")
    path_ax.set_ylabel("y (m)")
    path_ax.set_aspect("equal", adjustable="datalim")
    path_ax.set_title("Trajectories")
    path_ax.legend(fontsize=8)
    return fig
