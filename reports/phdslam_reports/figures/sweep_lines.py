"""A one-dimensional sweep over any parameter: final-map GOSPA and position RMSE against the
swept value, one line per (estimator, N)."""

from __future__ import annotations

import math
from typing import Callable

import numpy as np
from matplotlib.figure import Figure

from ..bound_efficiency import BOUNDS
from ..style import estimator_colour, new_figure, particle_line_style
from ..sweep_table import SweepTable
from .bound_line import plot_bound_line

METRICS = (("gospa_mean_m", "gospa_sem_m", "GOSPA (m)"),
           ("pos_rmse_m", "", "Position RMSE (m)"))


def _positions(values: tuple[str, ...]) -> tuple[np.ndarray, bool]:
    """Numeric x positions of the values when they are all numbers, else their ranks."""
    try:
        return np.array([float(v) for v in values]), True
    except ValueError:
        return np.arange(len(values), dtype=float), False


def _group_key(table: SweepTable, row) -> tuple[str, int | None]:
    """(estimator, N), without N when the particle count is the swept parameter."""
    return (row.estimator, None if "particles" in table.parameters else row.particles)


def plot_sweep_lines(table: SweepTable,
                     display_name: Callable[[str], str] = str) -> Figure | None:
    """GOSPA and position RMSE (± SE where known) against the one swept parameter."""
    if len(table.parameters) != 1:
        return None
    values = table.values[0]
    x_all, numeric = _positions(values)
    estimators = sorted({r.estimator for r in table.rows})
    # line styles tell the estimators' particle counts apart; a bound's N (1) is none of them
    particle_counts = sorted({r.particles for r in table.rows if r.estimator not in BOUNDS})
    particle_counts = particle_counts or [1]
    fig, axes = new_figure(12.0, 4.3, 1, 2)
    for col, (metric, se, label) in enumerate(METRICS):
        ax = axes[0][col]
        groups: dict[tuple, dict[str, tuple[float, float]]] = {}
        for r in table.rows:
            err = r.values.get(se, math.nan) if se else math.nan
            groups.setdefault(_group_key(table, r), {})[r.point[0]] = (
                r.values.get(metric, math.nan), err)
        for (estimator, n), by_value in sorted(groups.items(), key=lambda g: str(g[0])):
            index = [i for i, v in enumerate(values) if v in by_value]
            if not index:
                continue
            y = np.array([by_value[values[i]][0] for i in index])
            err = np.array([by_value[values[i]][1] for i in index])
            name = display_name(estimator) + (f", N = {n}" if n is not None else "")
            if estimator in BOUNDS:
                if metric == "pos_rmse_m":
                    plot_bound_line(ax, x_all[index], y, estimator, display_name)
                continue
            ax.errorbar(x_all[index], y, yerr=np.where(np.isfinite(err), err, 0.0), marker="o",
                        ms=4, capsize=3, color=estimator_colour(estimator, estimators),
                        ls=particle_line_style(n if n is not None else particle_counts[0],
                                               particle_counts), label=name)
        if not numeric:
            ax.set_xticks(x_all, values)
        ax.set_xlabel(table.parameters[0])
        ax.set_ylabel(label)
        ax.set_title(f"{label.split(' (')[0]} vs {table.parameters[0]}")
        ax.legend(loc="best", framealpha=0.85)
    fig.tight_layout()
    return fig
