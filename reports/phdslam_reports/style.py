"""One look for every figure: Agg backend, sizes, fonts, a fixed colour per estimator."""

from __future__ import annotations

import io
from pathlib import Path
from typing import Iterable

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (the backend must be chosen first)
from matplotlib.figure import Figure  # noqa: E402

ESTIMATOR_COLOURS = {
    "phd1": "#1f77b4",
    "phd2a": "#ff7f0e",
    "phd2b": "#2ca02c",
    "phd3": "#d62728",
    "oracle": "#9467bd",
    "odometry": "#7f7f7f",
    # the posterior Cramer-Rao bounds (docs/algorithms/pcrb.md): dark, so that they read as limits
    "pcrb": "#111111",
    "pcrb-smoother": "#555555",
}
_SPARE_COLOURS = ("#8c564b", "#e377c2", "#bcbd22", "#17becf", "#393b79", "#637939")
LINE_STYLES = ("-", "--", ":", "-.")
TRUTH_COLOUR = "#000000"
GPS_COLOUR = "#a6a6a6"  # lighter than the odometry grey, drawn as dots
FIGURE_DPI = 110


def apply_style() -> None:
    """Sets the matplotlib defaults shared by every figure."""
    plt.rcParams.update({
        "figure.dpi": 100,
        "savefig.dpi": FIGURE_DPI,
        "font.size": 10,
        "axes.titlesize": 11,
        "axes.labelsize": 10,
        "legend.fontsize": 8.5,
        "axes.grid": True,
        "grid.alpha": 0.3,
        "axes.spines.top": False,
        "axes.spines.right": False,
        "lines.linewidth": 1.4,
        "svg.hashsalt": "phdslam",
    })


def estimator_colour(estimator: str, known: Iterable[str] = ()) -> str:
    """The colour of an estimator: fixed for the paper's filters, else by its rank in ``known``."""
    if estimator in ESTIMATOR_COLOURS:
        return ESTIMATOR_COLOURS[estimator]
    others = sorted({e for e in known if e not in ESTIMATOR_COLOURS} | {estimator})
    return _SPARE_COLOURS[others.index(estimator) % len(_SPARE_COLOURS)]


def particle_line_style(particles: int, all_particles: Iterable[int]) -> str:
    """Line style by the rank of a particle count among those plotted."""
    ranks = sorted(set(all_particles) | {particles})
    return LINE_STYLES[ranks.index(particles) % len(LINE_STYLES)]


def new_figure(width: float, height: float, rows: int = 1, cols: int = 1, **kwargs):
    """A figure of ``width`` x ``height`` inches with a grid of axes (squeeze off)."""
    apply_style()
    fig, axes = plt.subplots(rows, cols, figsize=(width, height), squeeze=False, **kwargs)
    return fig, axes


def panel_grid(count: int, width: float = 6.5, height: float = 3.8, max_cols: int = 2):
    """A figure with one panel per item, ``max_cols`` per row, and the panels in reading order;
    the grid's unused panels are hidden. Returns (figure, list of ``count`` axes)."""
    cols = min(max_cols, count)
    rows = (count + cols - 1) // cols
    fig, axes = new_figure(width * cols, height * rows, rows, cols)
    flat = [axes[i // cols][i % cols] for i in range(rows * cols)]
    for ax in flat[count:]:
        ax.set_visible(False)
    return fig, flat[:count]


def save_figure(fig: Figure, path: Path) -> bytes:
    """Writes ``fig`` as PNG to ``path``, closes it and returns the PNG bytes."""
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", bbox_inches="tight", metadata={"Software": None})
    plt.close(fig)
    data = buffer.getvalue()
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(data)
    return data
