"""Reads and checks a gates file (ci/gates.yaml; the format is in ci/GATES.md).

Every error is an InputError whose message names the file and the entry (and the field), so a
malformed or hostile file ends in one line, never a traceback.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import gate_stats

_NAME = re.compile(r"^[A-Za-z0-9_.-]+$")
_SEEDS = re.compile(r"^\d+(-\d+)?(,\d+(-\d+)?)*$")
MAX_FILE_BYTES = 1 << 20


class InputError(ValueError):
    """A malformed gates file, baseline or results folder; the message names the file and field."""


@dataclass(frozen=True)
class RunEntry:
    """One `phdslam run` of a suite: estimators with their particle counts."""

    estimators: tuple[str, ...]
    particles: tuple[int, ...]


@dataclass(frozen=True)
class Suite:
    """The runs one results folder holds: scenario, steps, seeds, invocations and extra options."""

    name: str
    scenario: str
    steps: int
    seeds: str
    runs: tuple[RunEntry, ...]
    args: tuple[str, ...]

    def seed_list(self) -> list[int]:
        return expand_seeds(self.seeds)

    def groups(self) -> list[tuple[str, int]]:
        return [(e, n) for run in self.runs for e in run.estimators for n in run.particles]

    def definition(self) -> dict[str, Any]:
        """What a baseline of this suite must have been run with (recorded in its header)."""
        return {"scenario": self.scenario, "steps": self.steps, "seeds": self.seeds,
                "runs": [{"estimators": list(r.estimators), "particles": list(r.particles)}
                         for r in self.runs],
                "args": list(self.args)}

    def run_arguments(self) -> list[list[str]]:
        """The arguments of `phdslam run` of each invocation (without --out)."""
        return [["--scenario", self.scenario, "--estimator", ",".join(run.estimators),
                 "--particles", ",".join(str(n) for n in run.particles), "--seeds", self.seeds,
                 "--steps", str(self.steps)] + list(self.args) for run in self.runs]


@dataclass(frozen=True)
class PairedGate:
    """One metric of one group, tested run by run against the baseline (the paired tier)."""

    suite: str
    estimator: str
    particles: int
    metric: str
    margin: float
    spread_redraw: float  # winsorised sd of the per-seed log ratio, neutral change re-drawing
    spread_keep: float  # the same for a neutral change that keeps the random draws
    deterministic: bool
    reason: str

    @property
    def label(self) -> str:
        return f"{self.estimator} N={self.particles} {self.metric}"


@dataclass(frozen=True)
class Reference:
    """A published value an anchor is checked against."""

    source: str
    value: float
    se: float


@dataclass(frozen=True)
class Anchor:
    """A statistic of one group kept near published values (the anchor tier)."""

    suite: str
    estimator: str
    particles: int
    metric: str
    statistic: str  # mean | pooled-rmse | step-mean
    tolerance: float
    references: tuple[Reference, ...]
    band: tuple[float, float] | None  # instead of references: the value must lie inside
    reason: str

    @property
    def label(self) -> str:
        return f"{self.estimator} N={self.particles} {self.metric}"


@dataclass(frozen=True)
class GatesFile:
    path: Path
    baseline: Path
    family_false_alarm: float
    power: float
    trim: float
    indifference: float
    exact_relative: float
    exact_absolute: float
    anchor_false_alarm: float
    suites: tuple[Suite, ...]
    paired: tuple[PairedGate, ...]
    anchors: tuple[Anchor, ...]

    def suite(self, name: str) -> Suite:
        return next(s for s in self.suites if s.name == name)

    @property
    def per_gate_alpha(self) -> float:
        """Bonferroni: the family's false-alarm rate split over the statistical paired gates."""
        tested = sum(1 for g in self.paired if not g.deterministic)
        return self.family_false_alarm / max(1, tested)

    @property
    def per_anchor_alpha(self) -> float:
        return self.anchor_false_alarm / max(1, len(self.anchors))

    def seeds_needed(self, gate: PairedGate) -> int:
        if gate.deterministic:
            return 1
        return gate_stats.seeds_needed(gate.spread_redraw, gate.margin, self.per_gate_alpha,
                                       self.power, self.trim, self.indifference)

    def detectable(self, gate: PairedGate, spread: float) -> float:
        if gate.deterministic:
            return gate.margin
        seeds = len(self.suite(gate.suite).seed_list())
        return gate_stats.minimum_detectable_effect(spread, seeds, self.per_gate_alpha,
                                                    self.power, self.trim, self.indifference)

    def power_at(self, gate: PairedGate, effect: float) -> float:
        if gate.deterministic:
            return 1.0 if effect > gate.margin else 0.0
        seeds = len(self.suite(gate.suite).seed_list())
        return gate_stats.power_at(effect, gate.spread_redraw, seeds, self.per_gate_alpha,
                                   self.trim, self.indifference)


def expand_seeds(text: str) -> list[int]:
    seeds: list[int] = []
    for part in text.split(","):
        low, _, high = part.partition("-")
        seeds += list(range(int(low), int(high) + 1)) if high else [int(low)]
    return seeds


class _Reader:
    """Field access with errors that name the file, the entry and the field."""

    def __init__(self, path: Path):
        self.path = path

    def fail(self, where: str, what: str) -> InputError:
        return InputError(f"{self.path}: {where}: {what}")

    def mapping(self, value: Any, where: str, allowed: set[str], required: set[str]) -> dict:
        if not isinstance(value, dict):
            raise self.fail(where, "expected a mapping")
        unknown = set(value) - allowed
        if unknown:
            raise self.fail(where, f"unknown key(s) {sorted(map(str, unknown))} "
                                   f"(allowed: {sorted(allowed)})")
        missing = required - set(value)
        if missing:
            raise self.fail(where, f"missing key(s) {sorted(missing)}")
        return value

    def name(self, value: Any, where: str) -> str:
        if not isinstance(value, str) or not _NAME.match(value):
            raise self.fail(where, f"expected a name (letters, digits, _.-), got {value!r}")
        return value

    def integer(self, value: Any, where: str, low: int, high: int) -> int:
        if not isinstance(value, int) or isinstance(value, bool) or not low <= value <= high:
            raise self.fail(where, f"expected a whole number from {low} to {high}, got {value!r}")
        return value

    def number(self, value: Any, where: str, low: float, high: float) -> float:
        if (not isinstance(value, (int, float)) or isinstance(value, bool)
                or not math.isfinite(float(value)) or not low <= float(value) <= high):
            raise self.fail(where, f"expected a number from {low:g} to {high:g}, got {value!r}")
        return float(value)

    def text(self, value: Any, where: str) -> str:
        if not isinstance(value, str) or not value.strip():
            raise self.fail(where, "expected a non-empty text")
        return " ".join(value.split())

    def seeds(self, value: Any, where: str) -> str:
        text = str(value).replace(" ", "") if isinstance(value, (str, int)) else ""
        if not _SEEDS.match(text):
            raise self.fail(where, f"seeds must look like 1-5 or 1,3,7-9, got {value!r}")
        seeds = expand_seeds(text)
        if len(seeds) > 100000 or len(set(seeds)) != len(seeds) or min(seeds) < 1:
            raise self.fail(where, f"seeds {text}: at most 100000 distinct positive seeds")
        return text


def _suite(r: _Reader, index: int, entry: Any) -> Suite:
    where = f"suites[{index}]"
    r.mapping(entry, where, {"name", "scenario", "steps", "seeds", "runs", "args"},
              {"name", "scenario", "steps", "seeds", "runs"})
    runs = entry["runs"]
    if not isinstance(runs, list) or not runs or len(runs) > 100:
        raise r.fail(f"{where}.runs", "expected a list of 1 to 100 runs")
    parsed = []
    for i, run in enumerate(runs):
        run_where = f"{where}.runs[{i}]"
        r.mapping(run, run_where, {"estimators", "particles"}, {"estimators", "particles"})
        estimators, particles = run["estimators"], run["particles"]
        if not isinstance(estimators, list) or not estimators:
            raise r.fail(f"{run_where}.estimators", "expected a non-empty list of names")
        if not isinstance(particles, list) or not particles:
            raise r.fail(f"{run_where}.particles", "expected a non-empty list of particle counts")
        parsed.append(RunEntry(
            tuple(r.name(e, f"{run_where}.estimators") for e in estimators),
            tuple(r.integer(n, f"{run_where}.particles", 1, 100000) for n in particles)))
    args = entry.get("args") or []
    if not isinstance(args, list) or not all(
            isinstance(a, str) and "\t" not in a and "\n" not in a for a in args):
        raise r.fail(f"{where}.args", "expected a list of texts without tabs or newlines")
    return Suite(r.name(entry["name"], f"{where}.name"),
                 r.name(entry["scenario"], f"{where}.scenario"),
                 r.integer(entry["steps"], f"{where}.steps", 0, 10**7),
                 r.seeds(entry["seeds"], f"{where}.seeds"), tuple(parsed), tuple(args))


def _paired(r: _Reader, index: int, entry: Any, default_margin: float) -> PairedGate:
    where = f"paired[{index}]"
    r.mapping(entry, where, {"suite", "estimator", "particles", "metric", "margin", "spread",
                             "deterministic", "reason"},
              {"suite", "estimator", "particles", "metric", "reason"})
    deterministic = entry.get("deterministic", False)
    if not isinstance(deterministic, bool):
        raise r.fail(f"{where}.deterministic", f"expected true or false, got {deterministic!r}")
    spread = entry.get("spread")
    if deterministic:
        if spread is not None:
            raise r.fail(f"{where}.spread", "a deterministic gate has no spread")
        redraw = keep = 0.0
    else:
        r.mapping(spread, f"{where}.spread", {"redraw", "keep"}, {"redraw", "keep"})
        redraw = r.number(spread["redraw"], f"{where}.spread.redraw", 1e-9, 100.0)
        keep = r.number(spread["keep"], f"{where}.spread.keep", 0.0, 100.0)
    margin = r.number(entry.get("margin", default_margin), f"{where}.margin", 1e-6, 10.0)
    return PairedGate(r.name(entry["suite"], f"{where}.suite"),
                      r.name(entry["estimator"], f"{where}.estimator"),
                      r.integer(entry["particles"], f"{where}.particles", 1, 100000),
                      r.name(entry["metric"], f"{where}.metric"), margin, redraw, keep,
                      deterministic, r.text(entry["reason"], f"{where}.reason"))


def _anchor(r: _Reader, index: int, entry: Any) -> Anchor:
    where = f"anchors[{index}]"
    r.mapping(entry, where, {"suite", "estimator", "particles", "metric", "statistic",
                             "tolerance", "references", "band", "reason"},
              {"suite", "estimator", "particles", "metric", "statistic", "reason"})
    if ("band" in entry) == ("references" in entry):
        raise r.fail(where, "give either references (with a tolerance) or a band [low, high]")
    if "band" in entry:
        band = entry["band"]
        if not isinstance(band, list) or len(band) != 2:
            raise r.fail(f"{where}.band", f"expected [low, high], got {band!r}")
        low = r.number(band[0], f"{where}.band", -1e12, 1e12)
        high = r.number(band[1], f"{where}.band", low, 1e12)
        return Anchor(r.name(entry["suite"], f"{where}.suite"),
                      r.name(entry["estimator"], f"{where}.estimator"),
                      r.integer(entry["particles"], f"{where}.particles", 1, 100000),
                      r.name(entry["metric"], f"{where}.metric"), _statistic(r, where, entry),
                      0.0, (), (low, high), r.text(entry["reason"], f"{where}.reason"))
    if "tolerance" not in entry:
        raise r.fail(where, "missing key 'tolerance' (the allowed departure from the references)")
    statistic = _statistic(r, where, entry)
    refs = entry["references"]
    if not isinstance(refs, list) or not refs or len(refs) > 20:
        raise r.fail(f"{where}.references", "expected a list of 1 to 20 references")
    parsed = []
    for i, ref in enumerate(refs):
        ref_where = f"{where}.references[{i}]"
        r.mapping(ref, ref_where, {"source", "value", "se"}, {"source", "value", "se"})
        parsed.append(Reference(r.text(ref["source"], f"{ref_where}.source"),
                                r.number(ref["value"], f"{ref_where}.value", -1e12, 1e12),
                                r.number(ref["se"], f"{ref_where}.se", 0.0, 1e12)))
    return Anchor(r.name(entry["suite"], f"{where}.suite"),
                  r.name(entry["estimator"], f"{where}.estimator"),
                  r.integer(entry["particles"], f"{where}.particles", 1, 100000),
                  r.name(entry["metric"], f"{where}.metric"), statistic,
                  r.number(entry["tolerance"], f"{where}.tolerance", 0.0, 10.0), tuple(parsed),
                  None, r.text(entry["reason"], f"{where}.reason"))


def _statistic(r: _Reader, where: str, entry: dict) -> str:
    statistic = entry["statistic"]
    if statistic not in ("mean", "pooled-rmse", "step-mean"):
        raise r.fail(f"{where}.statistic",
                     f"expected mean, pooled-rmse or step-mean, got {statistic!r}")
    return statistic


def _load_yaml(path: Path) -> Any:
    import yaml  # Debian python3-yaml; imported here so --help works without it

    try:
        size = path.stat().st_size
        if size > MAX_FILE_BYTES:
            raise InputError(f"{path}: {size} bytes; a gates file has at most {MAX_FILE_BYTES}")
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise InputError(f"{path}: file not found") from None
    except (OSError, UnicodeDecodeError) as error:
        raise InputError(f"{path}: cannot read: {error}") from None
    try:
        documents = list(yaml.safe_load_all(text))
    except (yaml.YAMLError, RecursionError) as error:
        raise InputError(f"{path}: not valid YAML: {str(error).splitlines()[0]}") from None
    if len(documents) != 1:
        raise InputError(f"{path}: expected one YAML document, found {len(documents)}")
    return documents[0]


TOP_KEYS = {"version", "baseline", "family_false_alarm", "power", "margin", "trim",
            "indifference", "exact",
            "anchor_false_alarm", "suites", "paired", "anchors"}


def load(path: Path) -> GatesFile:
    """Reads and checks a gates file, including that each paired gate's suite has the seeds its
    stated margin needs."""
    data = _load_yaml(path)
    r = _Reader(path)
    r.mapping(data, "top level", TOP_KEYS, {"version", "suites"})
    if data["version"] != 1:
        raise r.fail("version", f"this checker reads version 1, got {data['version']!r}")
    exact = data.get("exact", {"relative": 1e-9, "absolute": 1e-12})
    r.mapping(exact, "exact", {"relative", "absolute"}, {"relative", "absolute"})
    suites_in = data["suites"]
    if not isinstance(suites_in, list) or not suites_in or len(suites_in) > 100:
        raise r.fail("suites", "expected a list of 1 to 100 suites")
    suites = tuple(_suite(r, i, s) for i, s in enumerate(suites_in))
    names = [s.name for s in suites]
    if len(set(names)) != len(names):
        raise r.fail("suites", f"a suite name is used twice: {names}")
    margin = r.number(data.get("margin", 0.05), "margin", 1e-6, 10.0)
    paired_in = data.get("paired") or []
    anchors_in = data.get("anchors") or []
    if not isinstance(paired_in, list) or len(paired_in) > 1000:
        raise r.fail("paired", "expected a list of at most 1000 gates")
    if not isinstance(anchors_in, list) or len(anchors_in) > 1000:
        raise r.fail("anchors", "expected a list of at most 1000 anchors")
    baseline = data.get("baseline", "baseline")
    gates = GatesFile(
        path, (path.parent / r.text(baseline, "baseline")),
        r.number(data.get("family_false_alarm", 0.05), "family_false_alarm", 1e-6, 0.5),
        r.number(data.get("power", 0.8), "power", 0.5, 0.9999),
        r.number(data.get("trim", 0.2), "trim", 0.0, 0.4),
        r.number(data.get("indifference", 0.001), "indifference", 0.0, 0.5),
        r.number(exact["relative"], "exact.relative", 0.0, 1.0),
        r.number(exact["absolute"], "exact.absolute", 0.0, 1e6),
        r.number(data.get("anchor_false_alarm", 0.05), "anchor_false_alarm", 1e-6, 0.5),
        suites, tuple(_paired(r, i, g, margin) for i, g in enumerate(paired_in)),
        tuple(_anchor(r, i, a) for i, a in enumerate(anchors_in)))
    _check_references(gates, r)
    return gates


def _check_references(gates: GatesFile, r: _Reader) -> None:
    """Every gate names a suite that runs its group, and has the seeds its margin needs."""
    by_name = {s.name: s for s in gates.suites}
    for kind, entries in (("paired", gates.paired), ("anchors", gates.anchors)):
        for i, gate in enumerate(entries):
            where = f"{kind}[{i}] ({gate.label})"
            suite = by_name.get(gate.suite)
            if suite is None:
                raise r.fail(where, f"suite '{gate.suite}' is not defined (suites: {sorted(by_name)})")
            if (gate.estimator, gate.particles) not in suite.groups():
                raise r.fail(where, f"suite '{gate.suite}' does not run {gate.estimator} "
                                    f"with {gate.particles} particles")
    for i, gate in enumerate(gates.paired):
        seeds = len(gates.suite(gate.suite).seed_list())
        needed = gates.seeds_needed(gate)
        if seeds < needed:
            detectable = gates.detectable(gate, gate.spread_redraw)
            raise r.fail(f"paired[{i}] ({gate.label})",
                         f"margin {gate.margin:.1%} needs {needed} seeds at power "
                         f"{gates.power:g} and per-gate alpha {gates.per_gate_alpha:.2g}; suite "
                         f"'{gate.suite}' has {seeds} (detects {detectable:.1%}): raise its seeds "
                         "or state the larger margin")
