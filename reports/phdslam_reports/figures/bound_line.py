"""A posterior Cramer-Rao bound (docs/algorithms/pcrb.md) as a line of a sweep figure: dashed,
without error bars, beneath the estimators' curves, labelled as a bound."""

from __future__ import annotations

from typing import Callable

import numpy as np

from ..bound_efficiency import row_name
from ..style import estimator_colour

BOUND_LINE_STYLE = "--"
BOUND_Z_ORDER = 1.5
"""Below matplotlib's default of 2 for lines and error bars: the estimators are drawn over it."""


def plot_bound_line(ax, x: np.ndarray, y: np.ndarray, estimator: str,
                    display_name: Callable[[str], str] = str) -> None:
    """Draws the bound's values ``y`` at the swept values ``x``."""
    ax.plot(x, y, color=estimator_colour(estimator), ls=BOUND_LINE_STYLE, lw=1.8,
            zorder=BOUND_Z_ORDER, label=row_name(display_name(estimator), estimator))
