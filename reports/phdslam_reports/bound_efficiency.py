"""Estimators' RMSE over the posterior Cramer-Rao bounds (docs/algorithms/pcrb.md section 6).

Per (estimator, N), over the seeds that have both the estimator's run and the bound's: the pooled
RMSE (root of the mean over runs of each run's mean squared error, every run having the same
steps), and the efficiency ratio RMSE / bound with its Monte Carlo standard error (delta method on
the paired per-seed mean squared errors: var log r = (var a / a^2 + var b / b^2 - 2 cov(a, b) /
(a b)) / 4n). A ratio more than two standard errors below 1 is flagged, from
MIN_FLAG_SEEDS paired seeds on: a run's mean squared error is heavy-tailed (a few runs with a
large drift carry much of the mean; paper-synthetic, smoother-known, 1000 steps: per-run MSE
from 0.03 to 3.0 m^2 about a median of 0.26), so on few seeds the mean and its standard error are
low together when no such run was drawn. Seeds 1-10 there give 0.68 +- 0.09, seeds 1-200
1.04 +- 0.04 (docs/algorithms/pcrb.md section 8). Below MIN_FLAG_SEEDS the ratio is marked
"few seeds" instead. The filtering bound `pcrb` holds only for an estimator whose estimate at a
step uses the data up to that step: a batch estimator (config.json's `batch`, the smoothers) is
compared with it but never flagged below it; `pcrb-smoother` holds for every estimator.
"""

from __future__ import annotations

import csv
import json
import math
from collections import defaultdict
from pathlib import Path
from typing import NamedTuple

BOUNDS = ("pcrb", "pcrb-smoother")
MIN_FLAG_SEEDS = 50
METRICS = (("pos_rmse_m", "position"), ("heading_rmse_deg", "heading"))


class Efficiency(NamedTuple):
    """An estimator's RMSE over a bound on the same seeds."""

    ratio: float
    se: float
    seeds: int
    bound_applies: bool = True  # False: a batch estimator against the filtering bound


def row_name(display: str, estimator: str) -> str:
    """A row's or a line's label: a bound's display name says that it is a bound."""
    if estimator in BOUNDS and "bound" not in display.lower():
        return f"{display} (bound)"
    return display


def read_runs(folder: Path) -> list[dict]:
    with (folder / "runs.csv").open(newline="", encoding="utf-8") as f:
        return list(csv.DictReader(f))


def read_batch_estimators(folder: Path) -> frozenset[str]:
    """The estimators config.json records as batch (smoothers); none when it is absent."""
    path = folder / "config.json"
    if not path.exists():
        return frozenset()
    estimators = json.loads(path.read_text(encoding="utf-8")).get("estimators", {})
    if not isinstance(estimators, dict):
        raise ValueError(f"{path}: 'estimators' is not an object")
    return frozenset(name for name, e in estimators.items()
                     if isinstance(e, dict) and e.get("batch") is True)


def squared(row: dict, key: str) -> float | None:
    text = row.get(key, "")
    if text in ("", None):
        return None
    value = float(text)
    return value * value if math.isfinite(value) else None


def ratio_with_error(a: list[float], b: list[float]) -> tuple[float, float]:
    """sqrt(mean a / mean b) and its delta-method standard error over paired samples."""
    n = len(a)
    ma, mb = sum(a) / n, sum(b) / n
    r = math.sqrt(ma / mb)
    if n < 2:
        return r, math.nan
    va = sum((x - ma) ** 2 for x in a) / (n - 1)
    vb = sum((y - mb) ** 2 for y in b) / (n - 1)
    cab = sum((x - ma) * (y - mb) for x, y in zip(a, b)) / (n - 1)
    var_log = (va / ma**2 + vb / mb**2 - 2.0 * cab / (ma * mb)) / (4.0 * n)
    return r, r * math.sqrt(max(var_log, 0.0))


def efficiency_rows(runs: list[dict], batch: frozenset[str] = frozenset()) -> list[dict]:
    """One dict per (estimator, N): pooled RMSEs, bounds and ratios against each bound.

    `batch`: the batch estimators (read_batch_estimators), to which `pcrb` does not apply."""
    by_key: dict[tuple[str, int], dict[int, dict]] = defaultdict(dict)
    for row in runs:
        by_key[(row["estimator"], int(row["particles"]))][int(row["seed"])] = row
    bounds = {name: by_key.get((name, 1), {}) for name in BOUNDS}
    out = []
    for (estimator, n), seeds in sorted(by_key.items()):
        entry = {"estimator": estimator, "particles": n, "bound": estimator in BOUNDS}
        for key, label in METRICS:
            values = [squared(r, key) for r in seeds.values()]
            values = [v for v in values if v is not None]
            entry[f"{label}_rmse"] = math.sqrt(sum(values) / len(values)) if values else math.nan
            entry["runs"] = len(values)
            for bound_name, bound_runs in bounds.items():
                pairs = [(squared(seeds[s], key), squared(bound_runs[s], key))
                         for s in seeds if s in bound_runs]
                pairs = [(x, y) for x, y in pairs if x is not None and y is not None and y > 0]
                if not pairs or entry["bound"]:
                    continue
                r, se = ratio_with_error([x for x, _ in pairs], [y for _, y in pairs])
                applies = bound_name != "pcrb" or estimator not in batch
                entry[f"{label}_ratio_{bound_name}"] = Efficiency(r, se, len(pairs), applies)
                entry[f"{label}_bound_{bound_name}"] = math.sqrt(
                    sum(y for _, y in pairs) / len(pairs))
        out.append(entry)
    return out


def cell(value) -> str:
    if isinstance(value, Efficiency):
        r, se, seeds, applies = value
        flag = ""
        if not applies:
            flag = " (batch: filtering bound not binding)"
        elif seeds < MIN_FLAG_SEEDS:
            flag = f" (few seeds: {seeds})"
        elif math.isfinite(se) and r + 2.0 * se < 1.0:
            flag = " ⚠ below"
        return f"{r:.3g} ± {se:.2g}{flag}"
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return "—"
    return f"{value:.4g}"


def markdown(rows: list[dict], point: str = "") -> str:
    head = ("| " + ("point | " if point else "") + "estimator | N | runs | position RMSE (m) | "
            "efficiency vs pcrb | efficiency vs pcrb-smoother | heading RMSE (deg) | "
            "efficiency vs pcrb | efficiency vs pcrb-smoother |")
    lines = [head, "|" + "---|" * (head.count("|") - 1)]
    for e in rows:
        name = f"{e['estimator']} (bound)" if e["bound"] else e["estimator"]
        cells = ([point] if point else []) + [name, str(e["particles"]), str(e["runs"])]
        for label in ("position", "heading"):
            cells += [cell(e[f"{label}_rmse"]), cell(e.get(f"{label}_ratio_pcrb")),
                      cell(e.get(f"{label}_ratio_pcrb-smoother"))]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)
