"""A two-dimensional sweep (a grid over two parameters): heat maps of the final-map GOSPA and of
the position RMSE, one row of panels per (estimator, N), every cell labelled with its value."""

from __future__ import annotations

import math
from typing import Callable

import numpy as np
from matplotlib.figure import Figure

from ..style import new_figure
from ..sweep_table import SweepTable

METRICS = (("gospa_mean_m", "GOSPA (m)", "viridis"), ("pos_rmse_m", "Position RMSE (m)", "magma"))


def heat_map_grids(table: SweepTable) -> dict[tuple[str, int | None], dict[str, np.ndarray]]:
    """Per (estimator, N) group (N is None when it is swept), per metric, the grid of values:
    rows follow the first parameter's values, columns the second's; NaN where no row exists."""
    first, second = table.values
    grids: dict[tuple[str, int | None], dict[str, np.ndarray]] = {}
    for r in table.rows:
        key = (r.estimator, None if "particles" in table.parameters else r.particles)
        group = grids.setdefault(key, {m: np.full((len(first), len(second)), math.nan)
                                       for m, _, _ in METRICS})
        if r.point[0] in first and r.point[1] in second:
            i, j = first.index(r.point[0]), second.index(r.point[1])
            for metric, _, _ in METRICS:
                group[metric][i, j] = r.values.get(metric, math.nan)
    return grids


def plot_sweep_heat_maps(table: SweepTable,
                         display_name: Callable[[str], str] = str) -> Figure | None:
    """The heat maps of a two-parameter sweep, or None for any other sweep."""
    if len(table.parameters) != 2 or not table.rows:
        return None
    grids = heat_map_grids(table)
    first, second = table.values
    keys = sorted(grids, key=lambda k: (k[0], k[1] or 0))
    width = max(5.0, 0.9 * len(second) + 2.5)
    height = max(3.2, 0.55 * len(first) + 1.8)
    fig, axes = new_figure(2 * width, height * len(keys), len(keys), 2)
    for row, key in enumerate(keys):
        estimator, n = key
        for col, (metric, label, cmap) in enumerate(METRICS):
            ax = axes[row][col]
            grid = grids[key][metric]
            ax.grid(False)
            image = ax.imshow(np.ma.masked_invalid(grid), cmap=cmap, aspect="auto",
                              origin="lower")
            finite = grid[np.isfinite(grid)]
            middle = float(np.mean([finite.min(), finite.max()])) if finite.size else math.nan
            for i in range(grid.shape[0]):
                for j in range(grid.shape[1]):
                    text = "n/a" if not math.isfinite(grid[i, j]) else f"{grid[i, j]:.3g}"
                    dark = math.isfinite(grid[i, j]) and grid[i, j] < middle
                    ax.text(j, i, text, ha="center", va="center", fontsize=8,
                            color="white" if dark else "black")
            ax.set_xticks(range(len(second)), second)
            ax.set_yticks(range(len(first)), first)
            ax.set_xlabel(table.parameters[1])
            ax.set_ylabel(table.parameters[0])
            name = display_name(estimator) + (f", N = {n}" if n is not None else "")
            ax.set_title(f"{label.split(' (')[0]}: {name}")
            fig.colorbar(image, ax=ax, label=label)
    fig.tight_layout()
    return fig
