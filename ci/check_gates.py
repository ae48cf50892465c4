#!/usr/bin/env python3
"""Accuracy regression gates: checks summary.csv of a regression run against ci/thresholds.yaml.

  check_gates.py ci/thresholds.yaml RESULTS/summary.csv   table of gates; exit 1 if any fails
  check_gates.py ci/thresholds.yaml --run-args             the phdslam run arguments, one run
                                                           per line, tab-separated

A gate fails when its metric leaves the band, when it has no band (a placeholder), when summary.csv
has no row or no value for it, or when its group finished fewer runs than the regression asks for.
See ci/GATES.md for how to move a baseline on purpose.
"""

from __future__ import annotations

import argparse
import csv
import math
import re
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import yaml

EXIT_PASS = 0
EXIT_GATE_FAILED = 1
EXIT_BAD_INPUT = 2

GATE_KEYS = {"estimator", "particles", "metric", "band", "reason"}
RUN_KEYS = {"estimators", "particles"}
REGRESSION_KEYS = {"scenario", "seeds", "steps", "runs", "experiment_name", "extra_args"}
_SEEDS = re.compile(r"^\d+(-\d+)?(,\d+(-\d+)?)*$")
_NAME = re.compile(r"^[A-Za-z0-9_.-]+$")


class InputError(ValueError):
    """thresholds.yaml or summary.csv is malformed; the message names the file and the entry."""


@dataclass(frozen=True)
class Gate:
    """One metric of one (estimator, particles) group that must stay inside a band."""

    estimator: str
    particles: int
    metric: str
    band: tuple[float, float] | None
    reason: str


@dataclass(frozen=True)
class RegressionRun:
    """One phdslam invocation of the regression run."""

    estimators: tuple[str, ...]
    particles: tuple[int, ...]


@dataclass(frozen=True)
class Regression:
    """The regression run: scenario, seeds, steps and the invocations."""

    scenario: str
    seeds: str
    steps: int
    runs: tuple[RegressionRun, ...]
    experiment_name: str | None
    extra_args: tuple[str, ...]

    def seed_count(self) -> int:
        """How many seeds the seed list names."""
        count = 0
        for part in self.seeds.split(","):
            low, _, high = part.partition("-")
            count += (int(high) - int(low) + 1) if high else 1
        return count

    def run_arguments(self) -> list[list[str]]:
        """The arguments of ``phdslam run`` for each invocation (without --out)."""
        out = []
        for run in self.runs:
            args = ["--scenario", self.scenario, "--estimator", ",".join(run.estimators),
                    "--particles", ",".join(str(n) for n in run.particles),
                    "--seeds", self.seeds, "--steps", str(self.steps)]
            if self.experiment_name:
                args += ["--experiment-name", self.experiment_name]
            out.append(args + list(self.extra_args))
        return out


@dataclass(frozen=True)
class Outcome:
    """The verdict of one gate."""

    gate: Gate
    value: float | None
    passed: bool
    note: str


def _fail(path: Path, where: str, what: str) -> InputError:
    return InputError(f"{path}: {where}: {what}")


def _parse_band(path: Path, where: str, band: Any) -> tuple[float, float] | None:
    if band is None:
        return None
    if (not isinstance(band, list) or len(band) != 2
            or not all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in band)):
        raise _fail(path, where, f"band must be [low, high] numbers or null, got {band!r}")
    low, high = float(band[0]), float(band[1])
    if not (math.isfinite(low) and math.isfinite(high)) or low > high:
        raise _fail(path, where, f"band [{low}, {high}] must be finite with low <= high")
    return low, high


def _parse_gate(path: Path, index: int, entry: Any) -> Gate:
    where = f"gates[{index}]"
    if not isinstance(entry, dict):
        raise _fail(path, where, "expected a mapping")
    unknown = set(entry) - GATE_KEYS
    if unknown:
        raise _fail(path, where, f"unknown key(s) {sorted(unknown)} (allowed: {sorted(GATE_KEYS)})")
    missing = GATE_KEYS - set(entry)
    if missing:
        raise _fail(path, where, f"missing key(s) {sorted(missing)}")
    estimator, particles, metric = entry["estimator"], entry["particles"], entry["metric"]
    if not isinstance(estimator, str) or not _NAME.match(estimator):
        raise _fail(path, where, f"estimator must be a name, got {estimator!r}")
    if not isinstance(particles, int) or isinstance(particles, bool) or particles < 1:
        raise _fail(path, where, f"particles must be a positive integer, got {particles!r}")
    if not isinstance(metric, str) or not _NAME.match(metric):
        raise _fail(path, where, f"metric must be a summary.csv column, got {metric!r}")
    reason = entry["reason"]
    if not isinstance(reason, str) or not reason.strip():
        raise _fail(path, where, "reason must be a non-empty text")
    band = _parse_band(path, where, entry["band"])
    return Gate(estimator, particles, metric, band, " ".join(reason.split()))


def _parse_regression(path: Path, entry: Any) -> Regression:
    where = "regression"
    if not isinstance(entry, dict):
        raise _fail(path, where, "expected a mapping")
    unknown = set(entry) - REGRESSION_KEYS
    if unknown:
        raise _fail(path, where, f"unknown key(s) {sorted(unknown)}")
    for key in ("scenario", "seeds", "steps", "runs"):
        if key not in entry:
            raise _fail(path, where, f"missing key '{key}'")
    scenario = entry["scenario"]
    if not isinstance(scenario, str) or not _NAME.match(scenario):
        raise _fail(path, where, f"scenario must be a name, got {scenario!r}")
    seeds = str(entry["seeds"]).replace(" ", "")
    if not _SEEDS.match(seeds):
        raise _fail(path, where, f"seeds must look like 1-5 or 1,3,7-9, got {entry['seeds']!r}")
    steps = entry["steps"]
    if not isinstance(steps, int) or isinstance(steps, bool) or steps < 0:
        raise _fail(path, where, f"steps must be a non-negative integer (0 = all), got {steps!r}")
    runs = []
    if not isinstance(entry["runs"], list) or not entry["runs"]:
        raise _fail(path, where, "runs must be a non-empty list")
    for i, run in enumerate(entry["runs"]):
        run_where = f"regression.runs[{i}]"
        if not isinstance(run, dict) or set(run) != RUN_KEYS:
            raise _fail(path, run_where, f"expected exactly the keys {sorted(RUN_KEYS)}")
        estimators, particles = run["estimators"], run["particles"]
        if (not isinstance(estimators, list) or not estimators
                or not all(isinstance(e, str) and _NAME.match(e) for e in estimators)):
            raise _fail(path, run_where, f"estimators must be a list of names, got {estimators!r}")
        if (not isinstance(particles, list) or not particles
                or not all(isinstance(n, int) and not isinstance(n, bool) and n >= 1
                           for n in particles)):
            raise _fail(path, run_where,
                        f"particles must be a list of positive integers, got {particles!r}")
        runs.append(RegressionRun(tuple(estimators), tuple(particles)))
    experiment = entry.get("experiment_name")
    if experiment is not None and (not isinstance(experiment, str) or not _NAME.match(experiment)):
        raise _fail(path, where, f"experiment_name must be a name, got {experiment!r}")
    extra = entry.get("extra_args") or []
    if not isinstance(extra, list) or not all(
            isinstance(a, str) and "\t" not in a and "\n" not in a for a in extra):
        raise _fail(path, where, "extra_args must be a list of texts without tabs or newlines")
    return Regression(scenario, seeds, steps, tuple(runs), experiment, tuple(extra))


def load_thresholds(path: Path) -> tuple[Regression, list[Gate]]:
    """Reads and checks thresholds.yaml."""
    try:
        data = yaml.safe_load(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise InputError(f"{path}: file not found") from None
    except (OSError, UnicodeDecodeError, yaml.YAMLError) as error:
        raise InputError(f"{path}: cannot read YAML: {error}") from None
    if not isinstance(data, dict) or "gates" not in data or "regression" not in data:
        raise InputError(f"{path}: expected a mapping with 'regression' and 'gates'")
    if not isinstance(data["gates"], list) or not data["gates"]:
        raise InputError(f"{path}: gates must be a non-empty list")
    gates = [_parse_gate(path, i, g) for i, g in enumerate(data["gates"])]
    seen = set()
    for i, gate in enumerate(gates):
        key = (gate.estimator, gate.particles, gate.metric)
        if key in seen:
            raise _fail(path, f"gates[{i}]", f"duplicate gate {key}")
        seen.add(key)
    return _parse_regression(path, data["regression"]), gates


def load_summary(path: Path) -> tuple[list[str], list[dict[str, str]]]:
    """summary.csv as its header and rows of text cells."""
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise InputError(f"{path}: file not found") from None
    except (OSError, UnicodeDecodeError) as error:
        raise InputError(f"{path}: cannot read: {error}") from None
    rows = list(csv.reader(text.splitlines()))
    if not rows:
        raise InputError(f"{path}: empty file (expected a header line)")
    header = [h.strip() for h in rows[0]]
    for column in ("estimator", "particles", "runs"):
        if column not in header:
            raise InputError(f"{path}: required column '{column}' is missing")
    records = []
    for line, cells in enumerate(rows[1:], start=2):
        if not cells:
            continue
        if len(cells) != len(header):
            raise InputError(f"{path}, line {line}: {len(cells)} cells, header has {len(header)}")
        records.append(dict(zip(header, (c.strip() for c in cells))))
    return header, records


def _number(path: Path, row: dict[str, str], column: str, line: int) -> float | None:
    cell = row.get(column, "")
    if cell == "":
        return None
    try:
        return float(cell)
    except ValueError:
        raise InputError(f"{path}, line {line}, column '{column}': '{cell}' is not a number") \
            from None


def evaluate(gates: list[Gate], summary_path: Path, expected_runs: int | None) -> list[Outcome]:
    """The verdict of every gate against summary.csv."""
    header, records = load_summary(summary_path)
    outcomes = []
    for gate in gates:
        match = [(line, r) for line, r in enumerate(records, start=2)
                 if r["estimator"] == gate.estimator and r["particles"] == str(gate.particles)]
        if not match:
            note = "no row in summary.csv"
            if gate.band is None:
                note = "no band (placeholder); " + note
            outcomes.append(Outcome(gate, None, False, note))
            continue
        line, row = match[0]
        if gate.metric not in header:
            outcomes.append(Outcome(gate, None, False, f"no column '{gate.metric}'"))
            continue
        value = _number(summary_path, row, gate.metric, line)
        runs = _number(summary_path, row, "runs", line) or 0
        failed = _number(summary_path, row, "failed_runs", line) if "failed_runs" in header else 0
        if value is None or not math.isfinite(value):
            outcomes.append(Outcome(gate, None, False, "value empty (not defined)"))
        elif gate.band is None:
            outcomes.append(Outcome(gate, value, False, "no band (placeholder)"))
        elif expected_runs is not None and (int(runs) != expected_runs or (failed or 0) > 0):
            outcomes.append(Outcome(gate, value, False,
                                    f"{int(runs)} of {expected_runs} runs finished"))
        elif gate.band[0] <= value <= gate.band[1]:
            outcomes.append(Outcome(gate, value, True, ""))
        else:
            side = "below" if value < gate.band[0] else "above"
            outcomes.append(Outcome(gate, value, False, f"{side} band"))
    return outcomes


def render_table(outcomes: list[Outcome]) -> str:
    """A fixed-width table: estimator, N, metric, value, band, result, reason."""
    headers = ["estimator", "N", "metric", "value", "band", "result", "reason"]
    rows = []
    for o in outcomes:
        band = "none" if o.gate.band is None else f"[{o.gate.band[0]:.6g}, {o.gate.band[1]:.6g}]"
        value = "-" if o.value is None else f"{o.value:.6g}"
        result = "PASS" if o.passed else f"FAIL: {o.note}"
        rows.append([o.gate.estimator, str(o.gate.particles), o.gate.metric, value, band, result,
                     o.gate.reason])
    widths = [max(len(r[i]) for r in rows + [headers]) for i in range(len(headers) - 1)]
    lines = []
    for row in [headers] + rows:
        lines.append("  ".join(cell.ljust(w) for cell, w in zip(row, widths)) + "  " + row[-1])
    passed = sum(o.passed for o in outcomes)
    lines.append(f"{passed} of {len(outcomes)} gates passed")
    return "\n".join(lines)


def parse_arguments(argv: list[str] | None) -> argparse.Namespace:
    """The command line."""
    parser = argparse.ArgumentParser(
        prog="check_gates.py",
        description=(
            "Check the summary.csv of the regression run against the gates of thresholds.yaml "
            "and print one line per gate (estimator, N, metric, value, band, PASS/FAIL, "
            "reason). A gate fails when its value leaves the band, when the band is null (a "
            "placeholder still to be filled in), when summary.csv has no row or value for it, "
            "or when fewer runs finished than the regression's seeds. With --run-args, print "
            "the 'phdslam run' arguments of the regression definition instead (one invocation "
            "per line, tab-separated; ci/check-gates.sh adds --out)."),
        epilog="Exit codes: 0 every gate passed; 1 a gate failed; 2 a malformed or missing "
               "input (the message names the file and the entry). See ci/GATES.md.",
    )
    parser.add_argument("thresholds", type=Path, metavar="THRESHOLDS_YAML",
                        help="gates and regression definition (ci/thresholds.yaml)")
    parser.add_argument("summary", type=Path, nargs="?", metavar="SUMMARY_CSV",
                        help="summary.csv of the regression run")
    parser.add_argument("--run-args", action="store_true",
                        help="print the phdslam run arguments of the regression and exit")
    parser.add_argument("--no-run-count", action="store_true",
                        help="do not require every group to have finished one run per "
                             "regression seed")
    args = parser.parse_args(argv)
    if not args.run_args and args.summary is None:
        parser.error("SUMMARY_CSV is required unless --run-args is given")
    return args


def main(argv: list[str] | None = None) -> int:
    """Runs the check; returns the exit code."""
    args = parse_arguments(argv)
    try:
        regression, gates = load_thresholds(args.thresholds)
        if args.run_args:
            for run in regression.run_arguments():
                print("\t".join(run))
            return EXIT_PASS
        expected = None if args.no_run_count else regression.seed_count()
        outcomes = evaluate(gates, args.summary, expected)
    except InputError as error:
        sys.stderr.write(f"check_gates: error: {error}\n")
        return EXIT_BAD_INPUT
    print(render_table(outcomes))
    return EXIT_PASS if all(o.passed for o in outcomes) else EXIT_GATE_FAILED


if __name__ == "__main__":
    sys.exit(main())
