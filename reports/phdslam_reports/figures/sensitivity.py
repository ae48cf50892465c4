"""Fig. 5 analogue: GOSPA and position RMSE against the detection probability and clutter rate."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable, Iterable

import numpy as np
from matplotlib.figure import Figure

from ..bound_efficiency import BOUNDS
from ..csv_table import CsvTable
from ..style import estimator_colour, new_figure, particle_line_style
from .bound_line import plot_bound_line

PD_COLUMNS = ("pd", "detection_probability", "detection_probability_nominal")
CLUTTER_COLUMNS = ("clutter_rate",)
OTHER_SYMBOL = {"pd": "\u03bb", "clutter_rate": "pD"}


@dataclass(frozen=True)
class SweepPoint:
    """One (estimator, N) result at one (pD, clutter rate) setting."""

    estimator: str
    particles: int
    pd: float
    clutter_rate: float
    pos_rmse_m: float
    pos_rmse_se: float
    gospa_m: float
    gospa_se: float


def first_column(table: CsvTable, names: Iterable[str]) -> str | None:
    """The first of ``names`` that the table has, or None."""
    return next((n for n in names if table.has(n)), None)


def points_from_table(
    table: CsvTable, default_pd: float, default_clutter: float
) -> list[SweepPoint]:
    """Points from a summary.csv or sweep.csv whose rows carry pd and/or clutter_rate columns."""
    pd_column = first_column(table, PD_COLUMNS)
    clutter_column = first_column(table, CLUTTER_COLUMNS)
    points = []
    for row in table.records():
        runs = float(row.get("runs", math.nan))
        gospa_std = float(row.get("gospa_std_m", math.nan))
        gospa_se = float(row.get("gospa_sem_m", math.nan))
        if not math.isfinite(gospa_se) and math.isfinite(gospa_std) and runs > 1:
            gospa_se = gospa_std / math.sqrt(runs)
        points.append(SweepPoint(
            estimator=str(row["estimator"]),
            particles=int(row["particles"]),
            pd=float(row[pd_column]) if pd_column else default_pd,
            clutter_rate=float(row[clutter_column]) if clutter_column else default_clutter,
            pos_rmse_m=float(row.get("pos_rmse_m", math.nan)),
            pos_rmse_se=float(row.get("pos_rmse_sem_m", math.nan)),
            gospa_m=float(row.get("gospa_mean_m", math.nan)),
            gospa_se=gospa_se,
        ))
    return points


def swept(points: list[SweepPoint], attribute: str) -> bool:
    """True when ``attribute`` takes at least two values for some (estimator, N, other setting)."""
    other = "clutter_rate" if attribute == "pd" else "pd"
    seen: dict[tuple, set[float]] = {}
    for p in points:
        key = (p.estimator, p.particles, getattr(p, other))
        seen.setdefault(key, set()).add(getattr(p, attribute))
    return any(len(values) >= 2 for values in seen.values())


def plot_sensitivity(
    points: list[SweepPoint], display_name: Callable[[str], str] = str
) -> Figure | None:
    """GOSPA and position RMSE vs pD (top row) and vs clutter rate (bottom row)."""
    sweeps = [a for a in ("pd", "clutter_rate") if swept(points, a)]
    if not sweeps:
        return None
    estimators = sorted({p.estimator for p in points})
    # line styles tell the estimators' particle counts apart; a bound's N (1) is none of them
    particle_counts = sorted({p.particles for p in points if p.estimator not in BOUNDS})
    fig, axes = new_figure(12.0, 4.3 * len(sweeps), len(sweeps), 2)
    x_labels = {"pd": "detection probability pD", "clutter_rate": "clutter rate \u03bb (per scan)"}
    for row, attribute in enumerate(sweeps):
        other = "clutter_rate" if attribute == "pd" else "pd"
        lines: dict[tuple, list[SweepPoint]] = {}
        for p in points:
            lines.setdefault((p.estimator, p.particles, getattr(p, other)), []).append(p)
        others_per_line = {key[:2]: set() for key in lines}
        for key in lines:
            others_per_line[key[:2]].add(key[2])
        for col, (metric, se, label) in enumerate((
            ("gospa_m", "gospa_se", "GOSPA (m)"),
            ("pos_rmse_m", "pos_rmse_se", "Position RMSE (m)"),
        )):
            ax = axes[row][col]
            for (estimator, n, fixed), members in sorted(lines.items()):
                if len({getattr(m, attribute) for m in members}) < 2:
                    continue
                members = sorted(members, key=lambda m: getattr(m, attribute))
                x = np.array([getattr(m, attribute) for m in members])
                y = np.array([getattr(m, metric) for m in members])
                err = np.array([getattr(m, se) for m in members])
                name = f"{display_name(estimator)}, N = {n}"
                if len(others_per_line[(estimator, n)]) > 1:
                    name += f" ({OTHER_SYMBOL[attribute]} = {fixed:g})"
                if estimator in BOUNDS:
                    if metric == "pos_rmse_m":
                        plot_bound_line(ax, x, y, estimator, display_name)
                    continue
                ax.errorbar(x, y, yerr=np.where(np.isfinite(err), err, 0.0), marker="o", ms=4,
                            capsize=3, color=estimator_colour(estimator, estimators),
                            ls=particle_line_style(n, particle_counts), label=name)
            ax.set_xlabel(x_labels[attribute])
            ax.set_ylabel(label)
            ax.set_title(f"{label.split(' (')[0]} vs {x_labels[attribute].split(' (')[0]}")
            ax.legend(loc="best", framealpha=0.85)
    fig.tight_layout()
    return fig
