"""phdslam's PHD-SLAM against the authors' implementation, seed by seed.

A results folder that holds an ingested run of the authors' release (estimator ``authors-<v>``,
reference/authors/) and phdslam's own ``<v>`` (its seeded random draws) or ``<v>-replay`` (phdslam
replaying the draws the authors' run recorded) at the same particle count is compared over their
common seeds: means, the mean paired difference (ours - authors) with its 90 % t interval in % of
the authors' mean, the two-one-sided test of equivalence within +-5 % (as ci/equivalence.py), the
two-sided Wilcoxon signed-rank and paired t p-values.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import stats

from .results import Group, ResultsFolder

AUTHORS_PREFIX = "authors-"
OURS_SUFFIXES = (("", "own random draws"), ("-replay", "the authors' recorded draws"))
"""phdslam's estimator name after the authors' variant, and what its random numbers are."""
METRICS = (("pos_rmse_m", "position RMSE (m)"), ("gospa_m", "GOSPA (m)"))
MARGIN = 0.05
"""Equivalence margin, a fraction of the authors' mean (the project's rule for equal results)."""
ALPHA = 0.05


@dataclass
class PairedRow:
    """One (pairing, N, metric) line: ours against the authors' over their common seeds."""

    ours: str
    draws: str
    particles: int
    metric: str
    n: int
    mean_authors: float
    mean_ours: float
    diff_pct: float
    ci_low_pct: float
    ci_high_pct: float
    equivalent: bool
    p_wilcoxon: float  # NaN when every difference is 0
    p_ttest: float


def _values(folder: ResultsFolder, group: Group, metric: str) -> dict[int, float]:
    values = {}
    for row in folder.runs_rows(group):
        value = float(row[metric])
        if math.isfinite(value):
            values[int(row["seed"])] = value
    return values


def paired_row(ours: Group, draws: str, metric: str, authors: dict[int, float],
               mine: dict[int, float]) -> PairedRow | None:
    """The paired statistics over the seeds both have (None below two seeds)."""
    seeds = sorted(set(authors) & set(mine))
    if len(seeds) < 2:
        return None
    a = np.array([authors[s] for s in seeds])
    b = np.array([mine[s] for s in seeds])
    d = b - a
    n = len(seeds)
    reference = abs(a.mean())
    se = d.std(ddof=1) / math.sqrt(n)
    half = stats.t.ppf(1 - ALPHA, n - 1) * se
    low, high = d.mean() - half, d.mean() + half
    margin = MARGIN * reference
    equivalent = bool(-margin < low and high < margin) if se > 0 else abs(d.mean()) < margin
    nonzero = d[d != 0]
    p_wilcoxon = float(stats.wilcoxon(nonzero).pvalue) if len(nonzero) > 0 else math.nan
    p_ttest = float(stats.ttest_rel(b, a).pvalue) if se > 0 else (1.0 if d.mean() == 0 else 0.0)

    def pct(x: float) -> float:
        return 100.0 * x / reference if reference > 0 else math.nan

    return PairedRow(ours.estimator, draws, ours.particles, metric, n, float(a.mean()),
                     float(b.mean()), pct(d.mean()), pct(low), pct(high), equivalent,
                     p_wilcoxon, p_ttest)


def authors_rows(folder: ResultsFolder) -> list[PairedRow]:
    """Every pairing of an ``authors-<v>`` group with phdslam's ``<v>`` / ``<v>-replay``."""
    groups = folder.groups()
    rows = []
    for authors in groups:
        if not authors.estimator.startswith(AUTHORS_PREFIX):
            continue
        variant = authors.estimator[len(AUTHORS_PREFIX):]
        for suffix, draws in OURS_SUFFIXES:
            ours = Group(variant + suffix, authors.particles)
            if ours not in groups:
                continue
            for metric, _ in METRICS:
                row = paired_row(ours, draws, metric, _values(folder, authors, metric),
                                 _values(folder, ours, metric))
                if row is not None:
                    rows.append(row)
    return rows
