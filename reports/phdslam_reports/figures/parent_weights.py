"""Single-cluster vs RB-PHD-SLAM parent weighting (Lee, Clark & Salvi 2012, Fig. 4 analogue).

One predicted state, many parent poses drawn from its pose Gaussian, one scan: the normalised
weight of every parent under the single-cluster likelihood (with the missed-detection term
exp(-sum pD w)) and under the RB-PHD-SLAM weighting (46), from ``phdslam parent-weights``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from matplotlib import colormaps
from matplotlib.cm import ScalarMappable
from matplotlib.colors import Normalize
from matplotlib.figure import Figure

from ..csv_table import CsvTable
from ..style import TRUTH_COLOUR, new_figure

WEIGHTINGS = (
    ("sc_weight", "single-cluster (with exp(-\u03a3 pD w))"),
    ("rb_weight", "RB-PHD-SLAM weighting (46)"),
)
"""(parent_weights.csv column, panel title) of the two weightings, in panel order."""

COLOUR_MAP = "viridis"
PREDICTED_COLOUR = "#d62728"
MEAN_COLOUR = "#ff7f0e"
PREVIOUS_COLOUR = "#7f7f7f"
MAX_EQUAL_ASPECT = 3.0
"""x and y are drawn to the same scale unless the drawn extent is more elongated than this."""

Pose = tuple[float, float, float]


@dataclass
class WeightingSummary:
    """One weighting: its column, title, ESS and weighted-mean pose."""

    column: str
    title: str
    weights: np.ndarray
    ess: float
    mean: Pose


@dataclass
class ParentWeightsData:
    """parent_weights.csv with the facts of parent_weights.json (None when that file is absent)."""

    x: np.ndarray
    y: np.ndarray
    theta: np.ndarray
    weightings: list[WeightingSummary]
    predicted_mean: Pose | None
    previous_pose: Pose | None
    true_pose: Pose | None

    @property
    def parents(self) -> int:
        """The number of parent poses."""
        return int(self.x.size)


def effective_sample_size(weights: np.ndarray) -> float:
    """1 / sum w^2 of normalised weights."""
    total = float(np.sum(np.square(weights)))
    return 1.0 / total if total > 0 else math.nan


def weighted_mean_pose(x: np.ndarray, y: np.ndarray, theta: np.ndarray,
                       weights: np.ndarray) -> Pose:
    """The weighted mean position and the weighted circular mean heading."""
    total = float(np.sum(weights))
    w = weights / total
    heading = math.atan2(float(np.sum(w * np.sin(theta))), float(np.sum(w * np.cos(theta))))
    return float(np.sum(w * x)), float(np.sum(w * y)), heading


def pose_error(estimate: Pose, truth: Pose) -> tuple[float, float]:
    """Position distance (m) and absolute wrapped heading difference (deg)."""
    distance = math.hypot(estimate[0] - truth[0], estimate[1] - truth[1])
    heading = math.remainder(estimate[2] - truth[2], 2.0 * math.pi)
    return distance, abs(math.degrees(heading))


def _pose(value: Any) -> Pose | None:
    return None if value is None else (float(value[0]), float(value[1]), float(value[2]))


def parent_weights_data(table: CsvTable, meta: dict[str, Any] | None) -> ParentWeightsData:
    """The figure's data from a validated parent_weights.csv and parent_weights.json."""
    x, y, theta = table.num("x"), table.num("y"), table.num("theta")
    weightings = []
    for column, title in WEIGHTINGS:
        w = table.num(column)
        weightings.append(WeightingSummary(column, title, w, effective_sample_size(w),
                                           weighted_mean_pose(x, y, theta, w)))
    meta = meta or {}
    return ParentWeightsData(x=x, y=y, theta=theta, weightings=weightings,
                             predicted_mean=_pose(meta.get("predicted_mean")),
                             previous_pose=_pose(meta.get("previous_pose")),
                             true_pose=_pose(meta.get("true_pose")))


def _extent_ratio(data: ParentWeightsData) -> float:
    """The longer over the shorter side of the box around every drawn point (>= 1)."""
    poses = [p for p in (data.previous_pose, data.predicted_mean, data.true_pose) if p]
    x = np.concatenate([data.x, [p[0] for p in poses]])
    y = np.concatenate([data.y, [p[1] for p in poses]])
    sides = sorted((float(np.ptp(x)), float(np.ptp(y))))
    return sides[1] / sides[0] if sides[0] > 0 else math.inf


def plot_parent_weights(data: ParentWeightsData) -> Figure:
    """Two panels with shared axes: parents sized and coloured by weight (one colour scale)."""
    fig, axes = new_figure(11.5, 5.6, 1, 2, sharex=True, sharey=True, layout="constrained")
    top = max(float(np.max(w.weights)) for w in data.weightings) or 1.0
    norm = Normalize(vmin=0.0, vmax=top)
    cmap = colormaps[COLOUR_MAP]
    to_scale = _extent_ratio(data) <= MAX_EQUAL_ASPECT
    for ax, weighting in zip(axes[0], data.weightings):
        order = np.argsort(weighting.weights, kind="stable")  # heaviest drawn last, on top
        w = weighting.weights[order]
        ax.scatter(data.x[order], data.y[order], c=w, cmap=cmap, norm=norm,
                   s=6.0 + 170.0 * w / top, edgecolors="#333333", linewidths=0.25, zorder=2)
        ax.scatter([], [], s=40, color=cmap(0.5), edgecolors="#333333", linewidths=0.25,
                   label=f"parents ({data.parents})")  # a legend entry of fixed size
        if data.previous_pose is not None:
            ax.scatter([data.previous_pose[0]], [data.previous_pose[1]], marker="s", s=36,
                       color=PREVIOUS_COLOUR, zorder=3, label="previous pose")
        if data.predicted_mean is not None:
            ax.scatter([data.predicted_mean[0]], [data.predicted_mean[1]], marker="x", s=90,
                       linewidths=2.0, color=PREDICTED_COLOUR, zorder=4, label="predicted mean")
        ax.scatter([weighting.mean[0]], [weighting.mean[1]], marker="D", s=60, facecolors="none",
                   edgecolors=MEAN_COLOUR, linewidths=1.8, zorder=4, label="weighted mean")
        if data.true_pose is not None:
            ax.scatter([data.true_pose[0]], [data.true_pose[1]], marker="*", s=190,
                       color=TRUTH_COLOUR, edgecolors="white", linewidths=0.6, zorder=5,
                       label="true pose")
        ax.set_title(f"{weighting.title}\nESS = 1/\u03a3w\u00b2 = {weighting.ess:.1f} of "
                     f"{data.parents}")
        ax.set_xlabel("x (m)")
        if to_scale:
            ax.set_aspect("equal", adjustable="box")
        # below the tick labels and the x label whatever the axes height (offset in font sizes)
        ax.legend(loc="upper center", bbox_to_anchor=(0.5, 0.0), borderaxespad=4.3, ncol=3,
                  frameon=False, markerscale=0.8)
    axes[0][0].set_ylabel("y (m)" if to_scale else "y (m; not to the scale of x)")
    fig.colorbar(ScalarMappable(norm=norm, cmap=cmap), ax=list(axes[0]), shrink=0.85,
                 label="normalised parent weight (area and colour)")
    return fig
