"""The batch smoothers' negative log posterior in the report: is the own association's solution
less probable than the known association's under the scenario's model?

runs.csv's ``neg_log_posterior`` (reference/ceres/README.md, "The posterior of a solution") scores
a batch smoother's final trajectory, map and association in nats, up to terms every solution of
the same data shares, so only paired differences on the same seed mean anything.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

from .results import ResultsFolder

#: The batch smoothers (window* are online and do not score their solution).
BATCH_SMOOTHER_PREFIX = "smoother-"
#: The reference the others are scored against: the smoother with the true association.
KNOWN = "smoother-known"
COLUMN = "neg_log_posterior"


@dataclass
class PosteriorGap:
    """One smoother against the known association: paired over their common seeds."""

    estimator: str
    seeds: int
    mean_difference: float  # nats, this smoother minus the known association (> 0: less probable)
    less_probable: int  # seeds on which this smoother's solution is the less probable


def _scores(folder: ResultsFolder, estimator: str) -> dict[int, float]:
    """seed -> finite neg_log_posterior of ``estimator``'s runs (N = 1 groups and others alike)."""
    table = folder.runs_table
    if table is None or not table.has(COLUMN):
        return {}
    out: dict[int, float] = {}
    for group in folder.groups():
        if group.estimator != estimator:
            continue
        for row in folder.runs_rows(group):
            value = row.get(COLUMN)
            if isinstance(value, float) and math.isfinite(value):
                out[int(row["seed"])] = value
    return out


def posterior_gaps(folder: ResultsFolder) -> list[PosteriorGap]:
    """Every other batch smoother against ``smoother-known`` over the seeds both scored; empty
    when the folder has no scored known-association run."""
    known = _scores(folder, KNOWN)
    if not known:
        return []
    gaps = []
    others = sorted({g.estimator for g in folder.groups()
                     if g.estimator.startswith(BATCH_SMOOTHER_PREFIX) and g.estimator != KNOWN})
    for estimator in others:
        scores = _scores(folder, estimator)
        seeds = sorted(set(scores) & set(known))
        if not seeds:
            continue
        differences = [scores[s] - known[s] for s in seeds]
        gaps.append(PosteriorGap(estimator, len(seeds), sum(differences) / len(seeds),
                                 sum(d > 0 for d in differences)))
    return gaps


def posterior_sentence(gaps: list[PosteriorGap], name: Callable[[str], str]) -> str:
    """The gaps in words; empty when there are none."""
    if not gaps:
        return ""
    parts = [f"Negative log posterior of the smoothers' solutions under the scenario's model "
             f"(runs.csv {COLUMN}, nats; lower is more probable), paired with {name(KNOWN)} on "
             "the same seeds:"]
    for g in gaps:
        parts.append(f"{name(g.estimator)} is {g.mean_difference:+,.0f} nats on average over "
                     f"{g.seeds} seed{'s' if g.seeds != 1 else ''}, less probable on "
                     f"{g.less_probable}.")
    if any(g.less_probable > 0 for g in gaps):
        parts.append("Where a solution is less probable than the known association's, the "
                     "model prefers the true association, and that smoother's association "
                     "search, not the model, is what falls short.")
    return " ".join(parts)
