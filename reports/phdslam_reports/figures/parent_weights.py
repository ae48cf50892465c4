"""Single-cluster vs RB-PHD-SLAM parent weighting (Lee, Clark & Salvi 2012, Fig. 4 analogue).

One predicted state, many parent poses drawn from its pose Gaussian, one scan: the normalised
weight of every parent under the single-cluster likelihood (with the missed-detection term
exp(-sum pD w)) and under the RB-PHD-SLAM weighting (46), from ``phdslam parent-weights``.

A few parents usually dominate both weightings, so their normalised weights look alike: the
parents are coloured by their normalised log-weight (sc_log_weight, rb_log_weight; log of the
plain weights in older files) and, when parent_weights.csv has missed_mass, a third panel shows
the missed-detection mass sum pD w of each parent: the single-cluster log-weight is the RB-PHD
one minus it, up to a constant.
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
    ("sc_weight", "sc_log_weight", "single-cluster (with exp(-\u03a3 pD w))"),
    ("rb_weight", "rb_log_weight", "RB-PHD-SLAM weighting (46)"),
)
"""(weight column, log-weight column, panel title) of the two weightings, in panel order."""

OPTIONAL_WEIGHTINGS = (
    ("sf_weight", "sf_log_weight", "single-feature RB-PHD-SLAM (Mullane et al.)"),
)
"""Weightings drawn after those when parent_weights.csv has their columns (newer files)."""

MISSED_MASS_COLUMN = "missed_mass"
MISSED_MASS_TITLE = "missed-detection mass \u03a3 pD w\n(the single-cluster penalty)"
LOG_WEIGHT_LABEL = "normalised log weight (nats)"
LOG_WEIGHT_RANGE = 20.0
"""The log-weight colour scale spans [max - LOG_WEIGHT_RANGE, max] nats; lower values clipped."""

COLOUR_MAP = "viridis"
MISSED_MASS_COLOUR_MAP = "plasma"
PREDICTED_COLOUR = "#d62728"
MEAN_COLOUR = "#ff7f0e"
PREVIOUS_COLOUR = "#7f7f7f"
MAX_EQUAL_ASPECT = 3.0
"""x and y are drawn to the same scale unless the drawn extent is more elongated than this."""

Pose = tuple[float, float, float]


@dataclass
class WeightingSummary:
    """One weighting: its column, title, weights, log-weights, ESS and weighted means."""

    column: str
    title: str
    weights: np.ndarray
    log_weights: np.ndarray  # from the file, or log of ``weights`` (-inf where they are 0)
    ess: float
    mean: Pose
    mean_missed_mass: float | None = None  # the weighted mean of missed_mass, when known


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
    missed_mass: np.ndarray | None = None
    log_weights_in_file: bool = False
    spread: float | None = None

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


def log_of_weights(weights: np.ndarray) -> np.ndarray:
    """Natural log of weights, -inf where a weight is 0."""
    with np.errstate(divide="ignore"):
        return np.log(weights)


def parent_weights_data(table: CsvTable, meta: dict[str, Any] | None) -> ParentWeightsData:
    """The figure's data from a validated parent_weights.csv and parent_weights.json."""
    x, y, theta = table.num("x"), table.num("y"), table.num("theta")
    missed = table.num(MISSED_MASS_COLUMN) if table.has(MISSED_MASS_COLUMN) else None
    in_file = all(table.has(log_column) for _, log_column, _ in WEIGHTINGS)
    present = WEIGHTINGS + tuple(o for o in OPTIONAL_WEIGHTINGS if table.has(o[0]) and
                                 table.has(o[1]))
    weightings = []
    for column, log_column, title in present:
        w = table.num(column)
        log_w = table.num(log_column) if in_file else log_of_weights(w)
        weightings.append(WeightingSummary(
            column, title, w, log_w, effective_sample_size(w),
            weighted_mean_pose(x, y, theta, w),
            float(np.sum(w * missed) / np.sum(w)) if missed is not None else None))
    meta = meta or {}
    spread = meta.get("spread")
    return ParentWeightsData(x=x, y=y, theta=theta, weightings=weightings,
                             predicted_mean=_pose(meta.get("predicted_mean")),
                             previous_pose=_pose(meta.get("previous_pose")),
                             true_pose=_pose(meta.get("true_pose")),
                             missed_mass=missed, log_weights_in_file=in_file,
                             spread=None if spread is None else float(spread))


def log_weight_norm(data: ParentWeightsData) -> Normalize:
    """The colour scale shared by the weighting panels: [top - LOG_WEIGHT_RANGE, top] nats."""
    finite = [float(np.max(w.log_weights[np.isfinite(w.log_weights)]))
              for w in data.weightings if np.any(np.isfinite(w.log_weights))]
    top = max(finite) if finite else 0.0
    return Normalize(vmin=top - LOG_WEIGHT_RANGE, vmax=top)


def _extent_ratio(data: ParentWeightsData) -> float:
    """The longer over the shorter side of the box around every drawn point (>= 1)."""
    poses = [p for p in (data.previous_pose, data.predicted_mean, data.true_pose) if p]
    x = np.concatenate([data.x, [p[0] for p in poses]])
    y = np.concatenate([data.y, [p[1] for p in poses]])
    sides = sorted((float(np.ptp(x)), float(np.ptp(y))))
    return sides[1] / sides[0] if sides[0] > 0 else math.inf


def _markers(ax, data: ParentWeightsData, weighted_mean: Pose | None, colour: Any) -> None:
    """The fixed-size legend entry of the parents and the previous, predicted, mean, true pose."""
    ax.scatter([], [], s=40, color=colour, edgecolors="#333333", linewidths=0.25,
               label=f"parents ({data.parents})")  # a legend entry of fixed size
    if data.previous_pose is not None:
        ax.scatter([data.previous_pose[0]], [data.previous_pose[1]], marker="s", s=36,
                   color=PREVIOUS_COLOUR, zorder=3, label="previous pose")
    if data.predicted_mean is not None:
        ax.scatter([data.predicted_mean[0]], [data.predicted_mean[1]], marker="x", s=90,
                   linewidths=2.0, color=PREDICTED_COLOUR, zorder=4, label="predicted mean")
    if weighted_mean is not None:
        ax.scatter([weighted_mean[0]], [weighted_mean[1]], marker="D", s=60, facecolors="none",
                   edgecolors=MEAN_COLOUR, linewidths=1.8, zorder=4, label="weighted mean")
    if data.true_pose is not None:
        ax.scatter([data.true_pose[0]], [data.true_pose[1]], marker="*", s=190,
                   color=TRUTH_COLOUR, edgecolors="white", linewidths=0.6, zorder=5,
                   label="true pose")


def plot_parent_weights(data: ParentWeightsData) -> Figure:
    """Parents sized by normalised weight and coloured by log-weight (one scale, shared axes).

    One panel per weighting (single-cluster, RB-PHD (46), and single-feature RB-PHD when the
    data have it); a last one, coloured by missed_mass and sized by the RB-PHD weight, when the
    data have it.
    """
    third = data.missed_mass is not None
    drawn = len(data.weightings)
    panels = drawn + 1 if third else drawn
    fig, axes = new_figure(4.6 * panels + 2.3, 5.8, 1, panels, sharex=True, sharey=True,
                           layout="constrained")
    axes = list(axes[0])
    top = max(float(np.max(w.weights)) for w in data.weightings) or 1.0
    norm = log_weight_norm(data)
    cmap = colormaps[COLOUR_MAP]
    to_scale = _extent_ratio(data) <= MAX_EQUAL_ASPECT
    legend_columns = 2 if third else 3
    for ax, weighting in zip(axes, data.weightings):
        log_w = np.maximum(weighting.log_weights, norm.vmin)  # clipped below (and -inf)
        order = np.lexsort((weighting.weights, log_w))  # heaviest drawn last, on top
        ax.scatter(data.x[order], data.y[order], c=log_w[order], cmap=cmap, norm=norm,
                   s=6.0 + 170.0 * weighting.weights[order] / top, edgecolors="#333333",
                   linewidths=0.25, zorder=2)
        _markers(ax, data, weighting.mean, cmap(0.5))
        ax.set_title(f"{weighting.title}\nESS = 1/\u03a3w\u00b2 = {weighting.ess:.1f} of "
                     f"{data.parents}")
    if third:
        ax = axes[drawn]
        rb = data.weightings[1]
        missed = data.missed_mass
        low, high = float(np.min(missed)), float(np.max(missed))
        missed_norm = Normalize(vmin=low, vmax=high if high > low else low + 1.0)
        missed_cmap = colormaps[MISSED_MASS_COLOUR_MAP]
        order = np.lexsort((rb.weights, rb.log_weights))  # stacked as in the RB-PHD panel
        ax.scatter(data.x[order], data.y[order], c=missed[order], cmap=missed_cmap,
                   norm=missed_norm, s=6.0 + 170.0 * rb.weights[order] / top,
                   edgecolors="#333333", linewidths=0.25, zorder=2)
        _markers(ax, data, None, missed_cmap(0.5))
        ax.set_title(MISSED_MASS_TITLE)
        fig.colorbar(ScalarMappable(norm=missed_norm, cmap=missed_cmap), ax=ax, shrink=0.85,
                     label="\u03a3 pD w (nats; point area = RB-PHD weight)")
    for ax in axes:
        ax.set_xlabel("x (m)")
        if to_scale:
            ax.set_aspect("equal", adjustable="box")
        # below the tick labels and the x label whatever the axes height (offset in font sizes)
        ax.legend(loc="upper center", bbox_to_anchor=(0.5, 0.0), borderaxespad=4.3,
                  ncol=legend_columns, frameon=False, markerscale=0.8)
    axes[0].set_ylabel("y (m)" if to_scale else "y (m; not to the scale of x)")
    fig.colorbar(ScalarMappable(norm=norm, cmap=cmap), ax=axes[:drawn], shrink=0.85, extend="min",
                 label=f"{LOG_WEIGHT_LABEL}; point area = weight")
    return fig
