"""Cost against map size: time per step and map bytes against landmarks, one line per N."""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

from ..csv_table import CsvTable
from ..style import new_figure


def map_scaling_ratios(table: CsvTable) -> dict[int, float]:
    """Per particle count with at least two map sizes: time per step at the largest map over the
    time per step at the smallest."""
    landmarks, particles = table.num("landmarks"), table.num("particles")
    ms = table.num("ms_per_step")
    ratios = {}
    for n in sorted(set(particles.astype(int))):
        rows = particles == n
        if np.count_nonzero(rows) < 2:
            continue
        order = np.argsort(landmarks[rows])
        times = ms[rows][order]
        if times[0] > 0:
            ratios[n] = float(times[-1] / times[0])
    return ratios


def plot_map_scaling(table: CsvTable) -> Figure | None:
    """Two log-log panels against the number of landmarks: ms per step and MB of all particles'
    maps (shared storage counted once), one line per particle count."""
    if table.rows == 0:
        return None
    landmarks, particles = table.num("landmarks"), table.num("particles")
    ms, mb = table.num("ms_per_step"), table.num("map_bytes") / 1e6
    fig, axes = new_figure(11.0, 4.5, cols=2)
    time_ax, bytes_ax = axes[0][0], axes[0][1]
    for n in sorted(set(particles.astype(int))):
        rows = particles == n
        order = np.argsort(landmarks[rows])
        x = landmarks[rows][order]
        style = "o-" if np.count_nonzero(rows) > 1 else "s"
        time_ax.loglog(x, ms[rows][order], style, ms=4, label=f"N = {n}")
        bytes_ax.loglog(x, mb[rows][order], style, ms=4, label=f"N = {n}")
    time_ax.set_ylabel("time per step (ms)")
    bytes_ax.set_ylabel("bytes of all particles' maps (MB)")
    for ax in (time_ax, bytes_ax):
        ax.set_xlabel("landmarks in the map")
        ax.grid(True, which="both", alpha=0.25)
        ax.legend(loc="best", framealpha=0.85)
    fig.tight_layout()
    return fig
