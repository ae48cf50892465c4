"""The three tiers of the accuracy gates (ci/GATES.md): exact, paired and anchor."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import gate_stats
from gate_tables import RunTable, is_timing
from gates_file import Anchor, GatesFile, InputError, PairedGate


@dataclass
class ExactOutcome:
    """One suite's run-by-run comparison with the baseline."""

    suite: str
    runs: int
    changed_runs: int
    columns: dict[str, tuple[int, float, str]] = field(default_factory=dict)
    # column -> (runs that moved, largest relative change, where)
    added: list[str] = field(default_factory=list)

    @property
    def passed(self) -> bool:
        return self.changed_runs == 0


def _cells_equal(a: str, b: str, rel: float, abs_: float) -> tuple[bool, float]:
    if a == b:
        return True, 0.0
    try:
        x, y = float(a), float(b)
    except ValueError:
        return False, math.inf
    if math.isnan(x) and math.isnan(y):
        return True, 0.0
    if not (math.isfinite(x) and math.isfinite(y)):
        return x == y, (0.0 if x == y else math.inf)
    diff = abs(x - y)
    scale = max(abs(x), abs(y))
    relative = diff / scale if scale > 0 else 0.0
    return diff <= rel * scale + abs_, relative


def exact_tier(gates: GatesFile, suite: str, new: RunTable, old: RunTable) -> ExactOutcome:
    compared = [c for c in old.columns if not is_timing(c)]
    missing = [c for c in compared if c not in new.columns]
    if missing:
        raise InputError(f"{new.source}: no column '{missing[0]}', which the baseline "
                         f"{old.source} has")
    outcome = ExactOutcome(suite, len(old.rows), 0)
    outcome.added = [c for c in new.columns if c not in old.columns and not is_timing(c)]
    for key, old_row in old.rows.items():
        new_row = new.rows[key]
        moved = False
        for column in compared:
            equal, relative = _cells_equal(old_row[column], new_row[column], gates.exact_relative,
                                           gates.exact_absolute)
            if equal:
                continue
            moved = True
            count, largest, where = outcome.columns.get(column, (0, -1.0, ""))
            if relative > largest:
                largest = relative
                where = (f"{key[0]} N={key[1]} seed {key[2]}: {old_row[column]} -> "
                         f"{new_row[column]}")
            outcome.columns[column] = (count + 1, largest, where)
        outcome.changed_runs += moved
    return outcome


@dataclass
class PairedOutcome:
    gate: PairedGate
    seeds: int
    baseline_mean: float
    new_mean: float
    change: float  # exp(trimmed mean of the log ratios) - 1
    test: gate_stats.YuenTest | None
    detectable: float
    power_at_margin: float
    passed: bool
    note: str


def log_ratios(gate: PairedGate, new: RunTable, old: RunTable) -> tuple[list[float], list[float],
                                                                        list[float]]:
    keys = [k for k in old.rows if k[0] == gate.estimator and k[1] == gate.particles]
    olds = [old.number(k, gate.metric) for k in keys]
    news = [new.number(k, gate.metric) for k in keys]
    d = []
    for key, x, y in zip(keys, olds, news):
        if x < 0 or y < 0:
            raise InputError(f"{new.source if y < 0 else old.source}: column '{gate.metric}' "
                             f"({key[0]} N={key[1]} seed {key[2]}): a gated metric is an error, "
                             "never negative")
        if x == y:
            d.append(0.0)
        else:
            # an exact zero (a perfect run) is floored at 1e-12 so that its ratio stays finite
            d.append(math.log(max(y, 1e-12)) - math.log(max(x, 1e-12)))
    return d, olds, news


def paired_tier(gates: GatesFile, gate: PairedGate, new: RunTable, old: RunTable) -> PairedOutcome:
    d, olds, news = log_ratios(gate, new, old)
    seeds = len(d)
    base_mean, new_mean = sum(olds) / seeds, sum(news) / seeds
    detectable = gates.detectable(gate, gate.spread_redraw)
    if gate.deterministic:
        change = math.expm1(sum(d) / seeds)
        passed = change <= gate.margin
        return PairedOutcome(gate, seeds, base_mean, new_mean, change, None, gate.margin, 1.0,
                             passed, "deterministic: fails above the margin")
    alpha = gates.per_gate_alpha
    test = gate_stats.yuen_test(d, gates.trim, alpha, gates.indifference)
    power = gates.power_at(gate, gate.margin)
    note = "identical" if all(v == 0.0 for v in d) else (
        f"t = {test.statistic:.2f} > {test.critical:.2f}" if test.rejected
        else f"t = {test.statistic:.2f} <= {test.critical:.2f}")
    return PairedOutcome(gate, seeds, base_mean, new_mean, math.expm1(test.location), test,
                         detectable, power, not test.rejected, note)


@dataclass
class AnchorOutcome:
    anchor: Anchor
    value: float
    se: float
    checks: list[tuple[str, float, float, float, bool]]  # source, reference, se, allowed, passed

    @property
    def passed(self) -> bool:
        return all(c[4] for c in self.checks)


def anchor_statistic(anchor: Anchor, table: RunTable) -> tuple[float, float]:
    keys = [k for k in table.rows if k[0] == anchor.estimator and k[1] == anchor.particles]
    values = [table.number(k, anchor.metric) for k in keys]
    if anchor.statistic == "mean":
        return gate_stats.mean_and_se(values)
    if anchor.statistic == "pooled-rmse":
        counts = [table.number(k, "pos_err_count") for k in keys]
        return gate_stats.pooled_rmse_and_se(values, counts)
    # step-mean: a per-run mean over steps, weighted by the run's steps
    steps = [table.number(k, "steps") for k in keys]
    total = sum(steps)
    mean = sum(v * s for v, s in zip(values, steps)) / total
    _, se = gate_stats.mean_and_se(values)
    return mean, se


def anchor_tier(gates: GatesFile, anchor: Anchor, table: RunTable) -> AnchorOutcome:
    """Passes when, for every reference, |value - reference| <= tolerance * |reference| + z * SE,
    z the two-sided normal quantile of the anchor family's level split over its anchors and SE
    the combined Monte Carlo error of both."""
    value, se = anchor_statistic(anchor, table)
    if anchor.band is not None:
        low, high = anchor.band
        centre, half = (low + high) / 2.0, (high - low) / 2.0
        return AnchorOutcome(anchor, value, se, [(f"band [{low:g}, {high:g}]", centre, 0.0, half,
                                                  low <= value <= high)])
    z = gate_stats.normal_quantile(1.0 - gates.per_anchor_alpha / 2.0)
    checks = []
    for ref in anchor.references:
        allowed = anchor.tolerance * abs(ref.value) + z * math.hypot(se, ref.se)
        checks.append((ref.source, ref.value, ref.se, allowed, abs(value - ref.value) <= allowed))
    return AnchorOutcome(anchor, value, se, checks)
