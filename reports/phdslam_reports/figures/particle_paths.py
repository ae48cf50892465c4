"""Fig. 3 analogue: particle trajectories of a run (the paper's figure is without resampling)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from matplotlib.figure import Figure

from ..csv_table import CsvTable
from ..style import TRUTH_COLOUR, new_figure

MAX_PANELS = 4


@dataclass
class ParticlePanel:
    """particles.csv of one run with its run's steps.csv (for the true trajectory), if any."""

    title: str
    particles: CsvTable
    steps: CsvTable | None


def particle_weights(table: CsvTable) -> np.ndarray:
    """The linear weights of particles.csv: exp(log_weight), or the weight column."""
    if table.has("log_weight"):
        return np.exp(table.num("log_weight"))
    return table.num("weight")


def plot_particle_paths(panels: list[ParticlePanel]) -> Figure | None:
    """Each particle's path (line colour by its final weight) with the true trajectory."""
    panels = panels[:MAX_PANELS]
    if not panels:
        return None
    cols = min(2, len(panels))
    rows = (len(panels) + cols - 1) // cols
    fig, axes = new_figure(6.5 * cols, 5.5 * rows, rows, cols)
    for index, panel in enumerate(panels):
        ax = axes[index // cols][index % cols]
        table = panel.particles
        step = table.num("step")
        ids = table.num("particle")
        weight = particle_weights(table)
        last_step = np.nanmax(step) if step.size else 0
        final = {int(p): w for p, s, w in zip(ids, step, weight) if s == last_step}
        top = max(final.values(), default=1.0) or 1.0
        for particle in np.unique(ids[np.isfinite(ids)]):
            rows_of = ids == particle
            order = np.argsort(step[rows_of])
            shade = 0.25 + 0.75 * float(final.get(int(particle), 0.0)) / top
            ax.plot(table.num("x")[rows_of][order], table.num("y")[rows_of][order],
                    color=(0.12, 0.35, 0.75, min(max(shade, 0.25), 1.0)), lw=0.8, zorder=3)
        if panel.steps is not None and np.any(np.isfinite(panel.steps.num("x_true"))):
            # under the particles: where they follow the truth closely they stay visible
            ax.plot(panel.steps.num("x_true"), panel.steps.num("y_true"), color=TRUTH_COLOUR,
                    lw=1.8, label="true trajectory", zorder=2)
        ax.plot([], [], color=(0.12, 0.35, 0.75), lw=0.8,
                label="particles (darker = larger final weight)")
        ax.set_title(panel.title)
        ax.set_xlabel("x (m)")
        ax.set_ylabel("y (m)")
        ax.set_aspect("equal", adjustable="datalim")
        ax.legend(loc="best", framealpha=0.85)
    for index in range(len(panels), rows * cols):
        axes[index // cols][index % cols].set_visible(False)
    fig.tight_layout()
    return fig
