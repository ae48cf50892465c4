"""Fig. 2 analogue: per-step metrics pooled over seeds (mean and 5-95 % band)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np
from matplotlib.figure import Figure

from ..bound_efficiency import BOUNDS
from ..results import Group, ResultsFolder
from ..stats import Band, band_over_runs, stack_ragged
from ..style import estimator_colour, new_figure, particle_line_style

PANELS = (
    ("pos_err_m", "Position error (m)"),
    ("heading_err_deg", "Heading error (deg)"),
    ("ess_ratio", "ESS / N"),
    ("map_components", "Map size (GM-PHD components)"),
)

MAP_OSPA_PANEL = ("map_ospa_m", "Map OSPA (m; p = 1, c = {c:g} m, landmarks detected so far)")
"""Drawn as a fifth panel when steps.csv has the opt-in column (phdslam run --map-ospa); {c} is
the cut-off of the runs (config.json metrics.map_ospa_c, default 5 m)."""


@dataclass
class GroupSeries:
    """Per-step bands of one group for each panel metric."""

    group: Group
    runs: int
    bands: dict[str, Band]


def collect_series(results: ResultsFolder, group: Group) -> GroupSeries | None:
    """Reads every run of ``group`` and pools its per-step metrics over seeds."""
    seeds = results.seeds(group)
    if not seeds:
        return None
    columns: dict[str, list[np.ndarray]] = {name: [] for name, _ in PANELS}
    for seed in seeds:
        steps = results.steps(group, seed)
        if steps.has(MAP_OSPA_PANEL[0]):
            columns.setdefault(MAP_OSPA_PANEL[0], []).append(steps.num(MAP_OSPA_PANEL[0]))
        columns["pos_err_m"].append(steps.num("pos_err_m"))
        columns["heading_err_deg"].append(steps.num("heading_err_deg"))
        columns["ess_ratio"].append(steps.num("ess") / float(group.particles))
        columns["map_components"].append(steps.num("map_components"))
    results.forget_steps()
    bands = {name: band_over_runs(stack_ragged(series)) for name, series in columns.items()}
    return GroupSeries(group=group, runs=len(seeds), bands=bands)


def needs_log_scale(means: list[np.ndarray], ratio: float = 20.0) -> bool:
    """True when the typical levels of the curves differ by more than ``ratio``.

    The level of a curve is the median of its positive values; a linear axis would flatten the
    curves of the accurate estimators next to, e.g., dead reckoning.
    """
    levels = []
    for mean in means:
        positive = mean[np.isfinite(mean) & (mean > 0)]
        if positive.size:
            levels.append(float(np.median(positive)))
    return len(levels) >= 2 and max(levels) > ratio * min(levels)


# The posterior Cramer-Rao bounds: rows that hold a bound where the others hold an error.
BOUND_ESTIMATORS = BOUNDS


def plot_metrics_over_time(
    series: list[GroupSeries], display_name: Callable[[str], str] = str,
    map_ospa_cutoff: float = 5.0,
) -> Figure | None:
    """Four panels (position error, heading error, ESS/N, map size) over the step index, and the
    map OSPA as a fifth when the runs have it."""
    series = [s for s in series if s is not None]
    if not series:
        return None
    estimators = [s.group.estimator for s in series]
    # line styles tell the estimators' particle counts apart; a bound's N (1) is none of them
    particles = [s.group.particles for s in series if s.group.estimator not in BOUND_ESTIMATORS]
    with_ospa = any(MAP_OSPA_PANEL[0] in s.bands for s in series)
    ospa_panel = (MAP_OSPA_PANEL[0], MAP_OSPA_PANEL[1].format(c=map_ospa_cutoff))
    panels = PANELS + (ospa_panel,) if with_ospa else PANELS
    fig, axes = new_figure(13.0, 12.0, 3, 2) if with_ospa else new_figure(13.0, 8.0, 2, 2)
    if with_ospa:
        axes.flat[-1].set_visible(False)
    for (name, label), ax in zip(panels, axes.flat):
        drawn = False
        for s in series:
            if name not in s.bands:
                continue
            band = s.bands[name]
            if not np.any(np.isfinite(band.mean)):
                continue
            k = np.arange(band.mean.size)
            colour = estimator_colour(s.group.estimator, estimators)
            if s.group.estimator in BOUND_ESTIMATORS:
                # a bound (docs/algorithms/pcrb.md): a limit drawn over the estimators, no band
                ax.plot(k, band.mean, color=colour, ls="-", lw=2.2, zorder=5,
                        label=f"{display_name(s.group.estimator)} (bound, {s.runs} seeds)")
                drawn = True
                continue
            style = particle_line_style(s.group.particles, particles)
            ax.plot(k, band.mean, color=colour, ls=style,
                    label=f"{display_name(s.group.estimator)}, N = {s.group.particles} "
                          f"({s.runs} runs)")
            if s.runs > 1:
                ax.fill_between(k, band.low, band.high, color=colour, alpha=0.15, linewidth=0)
            drawn = True
        ax.set_xlabel("step k")
        ax.set_ylabel(label)
        if name in ("pos_err_m", "heading_err_deg") and drawn and needs_log_scale(
                [s.bands[name].mean for s in series]):
            ax.set_yscale("log", nonpositive="mask")
        if not drawn:
            ax.text(0.5, 0.5, "not available for these runs", transform=ax.transAxes,
                    ha="center", va="center", color="#777")
        elif name == "pos_err_m":
            ax.legend(loc="upper left", framealpha=0.85)
    fig.suptitle("Mean over runs (line) and 5\u201395 % band over runs (shaded)")
    fig.tight_layout()
    return fig
