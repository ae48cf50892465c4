"""Scaling: time per call against the landmarks in view, log-log, with fitted exponents."""

from __future__ import annotations

from typing import Callable

import numpy as np
from matplotlib.figure import Figure
from matplotlib.ticker import ScalarFormatter

from ..csv_table import CsvTable
from ..stats import PowerLaw, fit_power_law
from ..style import estimator_colour, new_figure


def scaling_fits(table: CsvTable) -> dict[str, PowerLaw | None]:
    """The fitted power law of us_per_call against landmarks_in_fov, per estimator."""
    names = table.str("estimator")
    x, y = table.num("landmarks_in_fov"), table.num("us_per_call")
    fits = {}
    for estimator in sorted(set(names)):
        rows = np.array([n == estimator for n in names])
        fits[estimator] = fit_power_law(x[rows], y[rows])
    return fits


def plot_scaling(table: CsvTable, display_name: Callable[[str], str] = str) -> Figure | None:
    """Log-log points per estimator with the fitted line and its exponent in the legend."""
    if table.rows == 0:
        return None
    names = table.str("estimator")
    x, y = table.num("landmarks_in_fov"), table.num("us_per_call")
    fits = scaling_fits(table)
    estimators = sorted(set(names))
    fig, axes = new_figure(7.5, 5.0)
    ax = axes[0][0]
    for estimator in estimators:
        rows = np.array([n == estimator for n in names]) & (x > 0) & (y > 0)
        colour = estimator_colour(estimator, estimators)
        fit = fits[estimator]
        label = display_name(estimator)
        if fit is not None:
            label += f": $\\propto n^{{{fit.exponent:.2f}}}$"
        ax.loglog(x[rows], y[rows], "o", color=colour, ms=4, label=label)
        if fit is not None:
            grid = np.geomspace(np.min(x[rows]), np.max(x[rows]), 50)
            ax.loglog(grid, fit.coefficient * grid ** fit.exponent, color=colour, lw=1.0)
    ax.xaxis.set_major_formatter(ScalarFormatter())
    ax.xaxis.set_minor_formatter(ScalarFormatter())
    ax.grid(True, which="both", alpha=0.25)
    ax.set_xlabel("landmarks in the field of view")
    ax.set_ylabel("time per call (\u00b5s)")
    ax.legend(loc="best", framealpha=0.85)
    fig.tight_layout()
    return fig
