"""Fig. 1 analogue: true and estimated trajectory, true landmarks and the estimated map.

For real data without true poses but with GPS (Victoria Park) the GPS fixes are drawn under the
estimate instead of a true trajectory, as in the paper's Fig. 4.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np
from matplotlib.collections import PatchCollection
from matplotlib.figure import Figure
from matplotlib.patches import Ellipse

from ..csv_table import CsvTable
from ..style import GPS_COLOUR, TRUTH_COLOUR, estimator_colour, new_figure

SIGMA_SCALE = 3.0


@dataclass
class TrajectoryPanel:
    """The data of one panel: one run of one estimator."""

    title: str
    estimator: str
    steps: CsvTable
    estimated_map: CsvTable | None
    truth_map: CsvTable | None
    gps: CsvTable | None = None  # truth/seed-<s>/gps.csv, given for runs without true poses


def has_true_trajectory(steps: CsvTable) -> bool:
    """True when steps.csv holds at least one true position."""
    return bool(np.any(np.isfinite(steps.num("x_true")) & np.isfinite(steps.num("y_true"))))


def gps_in_span(gps: CsvTable, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The (x, y) of the GPS fixes within the run's time span (every fix when t is unknown)."""
    x, y, stamps = gps.num("x"), gps.num("y"), gps.num("t")
    keep = np.isfinite(x) & np.isfinite(y)
    finite_t = t[np.isfinite(t)]
    if finite_t.size:
        keep &= (stamps >= finite_t.min()) & (stamps <= finite_t.max())
    return x[keep], y[keep]


def covariance_ellipse(
    x: float, y: float, pxx: float, pxy: float, pyy: float, scale: float = SIGMA_SCALE
) -> Ellipse | None:
    """The ``scale``-sigma ellipse of a 2-D Gaussian, or None for a non-finite or non-PSD matrix."""
    cov = np.array([[pxx, pxy], [pxy, pyy]], dtype=float)
    if not np.all(np.isfinite(cov)):
        return None
    eigenvalues, eigenvectors = np.linalg.eigh(cov)
    if eigenvalues[0] < 0:
        return None
    major = eigenvectors[:, 1]
    angle = math.degrees(math.atan2(major[1], major[0]))
    width = 2.0 * scale * math.sqrt(eigenvalues[1])
    height = 2.0 * scale * math.sqrt(eigenvalues[0])
    return Ellipse((x, y), width=width, height=height, angle=angle)


def _map_ellipses(table: CsvTable) -> list[Ellipse]:
    if not all(table.has(c) for c in ("pxx", "pxy", "pyy")):
        return []
    ellipses = []
    for x, y, pxx, pxy, pyy in zip(table.num("x"), table.num("y"), table.num("pxx"),
                                   table.num("pxy"), table.num("pyy")):
        ellipse = covariance_ellipse(x, y, pxx, pxy, pyy)
        if ellipse is not None:
            ellipses.append(ellipse)
    return ellipses


def plot_trajectory_maps(
    panels: list[TrajectoryPanel], known_estimators: list[str],
    display_name: Callable[[str], str] = str,
) -> Figure | None:
    """One panel per run: trajectories, true landmarks, the estimated map with 3-sigma ellipses.

    A panel with ``gps`` draws the GPS fixes of the run's time span (grey dots, label "GPS").
    """
    if not panels:
        return None
    cols = min(3, len(panels))
    rows = math.ceil(len(panels) / cols)
    fig, axes = new_figure(5.2 * cols, 4.8 * rows, rows, cols)
    for index, panel in enumerate(panels):
        ax = axes[index // cols][index % cols]
        colour = estimator_colour(panel.estimator, known_estimators)
        steps = panel.steps
        xt, yt = steps.num("x_true"), steps.num("y_true")
        if np.any(np.isfinite(xt)):
            ax.plot(xt, yt, color=TRUTH_COLOUR, lw=1.2, label="true trajectory")
        if panel.gps is not None:
            gx, gy = gps_in_span(panel.gps, steps.num("t"))
            if gx.size:
                ax.plot(gx, gy, ls="none", marker="o", ms=2.6, mew=0, color=GPS_COLOUR,
                        zorder=1, label="GPS")
        ax.plot(steps.num("x"), steps.num("y"), color=colour, lw=1.2, ls="--",
                label=f"{display_name(panel.estimator)} estimate")
        if panel.truth_map is not None and panel.truth_map.rows:
            ax.scatter(panel.truth_map.num("x"), panel.truth_map.num("y"), marker="+", s=30,
                       color=TRUTH_COLOUR, linewidths=0.9, label="true landmarks", zorder=3)
        if panel.estimated_map is not None and panel.estimated_map.rows:
            m = panel.estimated_map
            ax.scatter(m.num("x"), m.num("y"), marker="o", s=9, facecolors="none",
                       edgecolors=colour, linewidths=0.8, label="estimated map", zorder=4)
            ellipses = _map_ellipses(m)
            if ellipses:
                ax.add_collection(PatchCollection(ellipses, facecolor="none", edgecolor=colour,
                                                  linewidth=0.6, alpha=0.7, zorder=4))
                ax.plot([], [], color=colour, lw=0.6, label="3\u03c3 ellipses")
        ax.set_title(panel.title)
        ax.set_xlabel("x (m)")
        ax.set_ylabel("y (m)")
        ax.set_aspect("equal", adjustable="datalim")
        ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=3, frameon=False)
    for index in range(len(panels), rows * cols):
        axes[index // cols][index % cols].set_visible(False)
    fig.tight_layout()
    return fig
