"""The delta-GLMB-SLAM paper's figures from glmb-sim results: RMSE in x, y and heading over time
per clutter rate (its Figs. 2-4), OSPA and time per step mean +- std per clutter rate (Figs. 5
and 6)."""

from __future__ import annotations

from typing import Callable, Sequence

import numpy as np
from matplotlib.figure import Figure

from ..glmb_paper import ClutterPoint, MeanStd
from ..style import estimator_colour, new_figure, particle_line_style

RMSE_ROWS = (("x", "RMSE x (m)"), ("y", "RMSE y (m)"), ("heading_deg", "RMSE heading (deg)"))


def _rates(points: Sequence[ClutterPoint]) -> list[float]:
    return sorted({p.clutter_rate for p in points})


def plot_rmse_over_time(points: Sequence[ClutterPoint],
                        display_name: Callable[[str], str] = str) -> Figure | None:
    """Rows x, y, heading; one column per clutter rate; one line per estimator and N."""
    if not points:
        return None
    rates = _rates(points)
    known = sorted({p.group.estimator for p in points})
    all_n = {p.group.particles for p in points}
    fig, axes = new_figure(3.6 * len(rates), 2.6 * len(RMSE_ROWS), len(RMSE_ROWS), len(rates),
                           sharex=True, sharey="row")
    for col, rate in enumerate(rates):
        for point in (p for p in points if p.clutter_rate == rate):
            for row, (attribute, _) in enumerate(RMSE_ROWS):
                values = getattr(point.rmse, attribute)
                label = f"{display_name(point.group.estimator)}, N = {point.group.particles}"
                axes[row][col].plot(np.arange(values.size), values, label=label,
                                    color=estimator_colour(point.group.estimator, known),
                                    ls=particle_line_style(point.group.particles, all_n))
        axes[0][col].set_title(f"clutter rate {rate:g}")
        axes[-1][col].set_xlabel("step")
    for row, (_, label) in enumerate(RMSE_ROWS):
        axes[row][0].set_ylabel(label)
    handles, labels = axes[0][0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=min(5, max(1, len(labels))),
               frameon=False, bbox_to_anchor=(0.5, -0.02))
    fig.tight_layout(rect=(0, 0.05, 1, 1))
    return fig


def plot_mean_std_per_rate(points: Sequence[ClutterPoint],
                           display_name: Callable[[str], str] = str,
                           ospa_cutoff: float | None = None) -> Figure | None:
    """Left: map OSPA (mean over steps per run) mean +- std over runs; right: time per step mean
    +- std; both against the clutter rate, one offset marker series per estimator and N."""
    if not points:
        return None
    known = sorted({p.group.estimator for p in points})
    groups = sorted({p.group for p in points})
    all_n = {g.particles for g in groups}
    fig, axes = new_figure(11.0, 4.0, 1, 2)
    rates = _rates(points)
    spacing = min(np.diff(rates)) if len(rates) > 1 else 1.0
    width = 0.6 * spacing / max(1, len(groups))
    panels: tuple[tuple[str, Callable[[ClutterPoint], MeanStd]], ...] = (
        ("ospa", lambda p: p.ospa), ("step_ms", lambda p: p.step_ms))
    for ax, (_, value) in zip(axes[0], panels):
        for index, group in enumerate(groups):
            mine = [p for p in points if p.group == group and value(p).count > 0]
            if not mine:
                continue
            offset = (index - (len(groups) - 1) / 2.0) * width
            x = np.array([p.clutter_rate for p in mine]) + offset
            mean = np.array([value(p).mean for p in mine])
            std = np.nan_to_num(np.array([value(p).std for p in mine]))
            ax.errorbar(x, mean, yerr=std, fmt="o", ms=4, capsize=3,
                        ls=particle_line_style(group.particles, all_n),
                        color=estimator_colour(group.estimator, known),
                        label=f"{display_name(group.estimator)}, N = {group.particles}")
        ax.set_xticks(rates)
        ax.set_xlabel("clutter rate (mean clutter points per scan)")
    cutoff = f"c = {ospa_cutoff:g} m, " if ospa_cutoff is not None else ""
    axes[0][0].set_ylabel(f"map OSPA (m; {cutoff}p = 1)")
    axes[0][0].set_title("Map OSPA, mean \u00b1 std over runs")
    axes[0][1].set_ylabel("time per step (ms)")
    axes[0][1].set_title("Time per step, mean \u00b1 std")
    axes[0][1].set_yscale("log")
    axes[0][0].legend(loc="best", frameon=False)
    fig.tight_layout()
    return fig
