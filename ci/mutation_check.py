#!/usr/bin/env python3
"""The mutation check of the accuracy gates (ci/GATES.md, "Mutation check").

  mutation_check.py measure --build BUILD --seeds 1-1000 --out DIR [--only NAME,...]
                            [--markdown FILE]
      runs each suite's baseline and every mutant and neutral change of ci/mutants.yaml on the
      given seeds (DIR/<suite>/baseline/, DIR/<suite>/<name>/; finished folders are reused), then
      prints per mutant and paired gate: the true effect over all seeds (the change of the
      trimmed mean of the per-seed log ratios, with its 95 % interval, and the change of the plain
      mean), and the rate at which the paired tier fails it on independent blocks of the suite's
      gate seed count; per neutral change the rate at which it passes.
  mutation_check.py short --build BUILD [--seeds 1-500] [--out DIR]
      the test command's short form: every change marked `short:` is run on those seeds (a part of
      its suite's gate seeds) with the suite's first particle count and gated against the stored
      baseline's runs; exits 1 unless each gives the verdict it is marked with (a mutant fails, a
      neutral change passes).

ci/mutants.yaml lists the mutants; ci/gates.yaml the suites, gates and the stored baseline.
"""

from __future__ import annotations

import argparse
import math
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import gate_stats  # noqa: E402
from gate_tables import (RunKey, RunTable, load_baseline, parse_runs, read_text,  # noqa: E402
                         select_suite_runs)
from gate_tiers import log_ratios  # noqa: E402
from gates_file import GatesFile, InputError, PairedGate, Suite, expand_seeds  # noqa: E402
from gates_file import load as load_gates  # noqa: E402

HERE = Path(__file__).resolve().parent


@dataclass(frozen=True)
class Mutant:
    name: str
    suites: tuple[str, ...]
    kind: str  # mutant | neutral
    args: tuple[str, ...]
    short: str | None  # fail | pass | None
    what: str


def load_mutants(path: Path, gates: GatesFile) -> list[Mutant]:
    import yaml

    try:
        data = yaml.safe_load(read_text(path, "mutants file"))
    except yaml.YAMLError as error:
        raise InputError(f"{path}: not valid YAML: {str(error).splitlines()[0]}") from None
    if not isinstance(data, dict) or data.get("version") != 1 or not isinstance(
            data.get("mutants"), list):
        raise InputError(f"{path}: expected version: 1 and a list 'mutants'")
    suites = {s.name for s in gates.suites}
    mutants = []
    for i, m in enumerate(data["mutants"]):
        where = f"{path}: mutants[{i}]"
        if not isinstance(m, dict) or not {"name", "suites", "kind", "args", "what"} <= set(m):
            raise InputError(f"{where}: needs name, suites, kind, args and what")
        if not isinstance(m["suites"], list) or not m["suites"]:
            raise InputError(f"{where}: field 'suites': a list of suite names")
        for name in m["suites"]:
            if name not in suites:
                raise InputError(f"{where}: field 'suites': '{name}' is not a suite of {gates.path}")
        if m["kind"] not in ("mutant", "neutral"):
            raise InputError(f"{where}: field 'kind': mutant or neutral, got {m['kind']!r}")
        if m.get("short") not in (None, "fail", "pass"):
            raise InputError(f"{where}: field 'short': fail or pass, got {m['short']!r}")
        if not isinstance(m["args"], list) or not all(isinstance(a, str) for a in m["args"]):
            raise InputError(f"{where}: field 'args': a list of texts")
        mutants.append(Mutant(str(m["name"]), tuple(m["suites"]), m["kind"], tuple(m["args"]),
                              m.get("short"), str(m["what"])))
    return mutants


def phdslam_of(build: Path) -> Path:
    for candidate in (build / "apps" / "phdslam" / "phdslam", build / "apps" / "phdslam"):
        if candidate.is_file():
            return candidate
    raise InputError(f"{build}: no phdslam program (apps/phdslam); build it first")


def run_suite(phdslam: Path, suite: Suite, seeds: str, particles: list[int] | None,
              extra: tuple[str, ...], out: Path) -> RunTable:
    """Runs the suite (its seeds replaced, optionally its particle counts) into `out`; a folder
    whose runs.csv already holds every run is taken as it is, an unfinished one is resumed by
    phdslam itself."""
    wanted = _only_particles(suite, particles[0], seeds) if particles else Suite(
        suite.name, suite.scenario, suite.steps, seeds, suite.runs, suite.args)
    if (out / "runs.csv").is_file():
        try:
            table = parse_runs(read_text(out / "runs.csv", "runs table"), str(out / "runs.csv"))
            return select_suite_runs(table, wanted, "results folder")
        except InputError:
            pass
    for run in suite.runs:
        counts = particles or list(run.particles)
        args = [str(phdslam), "run", "--scenario", suite.scenario, "--estimator",
                ",".join(run.estimators), "--particles", ",".join(map(str, counts)), "--seeds",
                seeds, "--steps", str(suite.steps), *suite.args, *extra, "--out", str(out),
                "--quiet"]
        print("mutation-check: " + " ".join(args[1:]), file=sys.stderr, flush=True)
        result = subprocess.run(args, stdout=subprocess.DEVNULL)
        if result.returncode != 0:
            raise InputError(f"{out}: the run above failed (exit {result.returncode})")
    path = out / "runs.csv"
    return parse_runs(read_text(path, "runs table"), str(path))


def restrict(table: RunTable, seeds: list[int]) -> RunTable:
    keep = set(seeds)
    rows = {k: v for k, v in table.rows.items() if k[2] in keep}
    return RunTable(table.source, table.columns, rows, {k: table.lines[k] for k in rows})


def block_verdicts(gates: GatesFile, gate: PairedGate, new: RunTable, old: RunTable,
                   blocks: list[list[int]]) -> list[bool]:
    """For each block of seeds: did the paired test fail the gate?"""
    failed = []
    for block in blocks:
        d, _, _ = log_ratios(gate, restrict(new, block), restrict(old, block))
        test = gate_stats.yuen_test(d, gates.trim, gates.per_gate_alpha, gates.indifference)
        failed.append(test.rejected)
    return failed


def effect(gates: GatesFile, gate: PairedGate, new: RunTable, old: RunTable) -> dict:
    d, olds, news = log_ratios(gate, new, old)
    n = len(d)
    location = gate_stats.trimmed_mean(d, gates.trim)
    se = gate_stats.winsorised_sd(d, gates.trim) / ((1 - 2 * gates.trim) * math.sqrt(n))
    diffs = [(y - x) for x, y in zip(olds, news)]
    base_mean = sum(olds) / n
    mean_change, mean_se = gate_stats.mean_and_se(diffs)
    return {"n": n, "trimmed": math.expm1(location),
            "trimmed_low": math.expm1(location - 1.96 * se),
            "trimmed_high": math.expm1(location + 1.96 * se),
            "mean": mean_change / base_mean,
            "mean_low": (mean_change - 1.96 * mean_se) / base_mean,
            "mean_high": (mean_change + 1.96 * mean_se) / base_mean}


def command_measure(args: argparse.Namespace) -> int:
    gates = load_gates(Path(args.gates))
    mutants = load_mutants(Path(args.mutants), gates)
    if args.only:
        wanted = set(args.only.split(","))
        mutants = [m for m in mutants if m.name in wanted]
    phdslam = phdslam_of(Path(args.build))
    out = Path(args.out)
    baselines: dict[str, RunTable] = {}
    lines = ["| change | kind | gate | seeds | true effect: the gate's statistic (95 % interval) | "
             "true effect: plain mean (95 % interval) | blocks | blocks failing the gate | "
             "blocks failing the suite | predicted rate, block | predicted rate, CI seeds | "
             "on the CI seeds |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for mutant, suite in ((m, gates.suite(name)) for m in mutants for name in m.suites):
        seed_text = suite_seeds(args.seeds, suite.name)
        seeds = expand_seeds(seed_text)
        if suite.name not in baselines:
            baselines[suite.name] = run_suite(phdslam, suite, seed_text, None, (),
                                              out / suite.name / "baseline")
        new = run_suite(phdslam, suite, seed_text, None, mutant.args,
                        out / suite.name / mutant.name)
        block = int(suite_seeds(args.block, suite.name)) if args.block else len(suite.seed_list())
        blocks = [seeds[i:i + block] for i in range(0, len(seeds) - block + 1, block)]
        suite_failed = [False] * len(blocks)
        rows = []
        for gate in (g for g in gates.paired if g.suite == suite.name and not g.deterministic):
            e = effect(gates, gate, new, baselines[suite.name])
            failed = block_verdicts(gates, gate, new, baselines[suite.name], blocks)
            suite_failed = [a or b for a, b in zip(suite_failed, failed)]
            gate_seeds = suite.seed_list()
            on_ci = ("n/a" if not set(gate_seeds) <= set(seeds) else
                     "FAIL" if block_verdicts(gates, gate, new, baselines[suite.name],
                                              [gate_seeds])[0] else "pass")
            rows.append((gate, e, failed, on_ci))
        for gate, e, failed, on_ci in rows:
            if mutant.kind == "neutral":  # a neutral change fails at the false-alarm rate
                at_block = at_gate = gates.per_gate_alpha
            else:
                at_block = gate_stats.power_at(max(e["trimmed"], -0.99), gate.spread_redraw,
                                               block, gates.per_gate_alpha, gates.trim,
                                               gates.indifference)
                at_gate = gates.power_at(gate, max(e["trimmed"], -0.99))
            lines.append(
                f"| `{mutant.name}` | {mutant.kind} | {gate.label} | {e['n']} | "
                f"{e['trimmed']:+.2%} [{e['trimmed_low']:+.2%}, {e['trimmed_high']:+.2%}] | "
                f"{e['mean']:+.2%} [{e['mean_low']:+.2%}, {e['mean_high']:+.2%}] | {len(blocks)} x "
                f"{block} | {sum(failed)}/{len(blocks)} | {sum(suite_failed)}/{len(blocks)} | "
                f"{at_block:.3f} | {at_gate:.3f} | {on_ci} |")
        print("\n".join(lines[-len(rows):]), flush=True)
    text = "\n".join(lines) + "\n"
    if args.markdown:
        Path(args.markdown).write_text(text, encoding="utf-8")
    print(text)
    return 0


def suite_seeds(text: str, suite: str) -> str:
    """--seeds is one seed list for every suite, or SUITE=SEEDS pairs separated by ';'."""
    if "=" not in text:
        return text
    pairs = dict(part.split("=", 1) for part in text.split(";") if part)
    if suite not in pairs:
        raise InputError(f"--seeds: no seeds for suite '{suite}' (give {suite}=SEEDS)")
    return pairs[suite]


def command_short(args: argparse.Namespace) -> int:
    gates = load_gates(Path(args.gates))
    mutants = [m for m in load_mutants(Path(args.mutants), gates) if m.short]
    phdslam = phdslam_of(Path(args.build))
    baseline = load_baseline(gates.baseline, gates.suites)
    status = 0
    with tempfile.TemporaryDirectory(prefix="phdslam-mutants.") as tmp:
        out = Path(args.out) if args.out else Path(tmp)
        for mutant in mutants:
            suite = gates.suite(mutant.suites[0])
            first = suite.runs[0].particles[0]
            new = run_suite(phdslam, suite, args.seeds, [first], mutant.args, out / mutant.name)
            new = select_suite_runs(new, _only_particles(suite, first, args.seeds), "mutant run")
            old = restrict(baseline.tables[suite.name], expand_seeds(args.seeds))
            verdicts = []
            for gate in gates.paired:
                if gate.suite != suite.name or gate.particles != first or gate.deterministic:
                    continue
                d, _, _ = log_ratios(gate, new, old)
                test = gate_stats.yuen_test(d, gates.trim, gates.per_gate_alpha,
                                            gates.indifference)
                verdicts.append(test.rejected)
                print(f"mutation-check: {mutant.name}: {gate.label}: change "
                      f"{math.expm1(test.location):+.2%}, t = {test.statistic:.2f} "
                      f"({'FAIL' if test.rejected else 'pass'} at {test.critical:.2f})")
            got = "fail" if any(verdicts) else "pass"
            ok = got == mutant.short
            verb = "fails" if got == "fail" else "passes"
            print(f"mutation-check: {mutant.name} ({mutant.kind}) {verb} the paired tier: "
                  f"{'as it must' if ok else 'WRONG, it must ' + mutant.short}")
            status |= 0 if ok else 1
    print(f"mutation-check: short form {'passed' if status == 0 else 'FAILED'} "
          f"({len(mutants)} changes)")
    return status


def _only_particles(suite: Suite, particles: int, seeds: str) -> Suite:
    from gates_file import RunEntry

    runs = tuple(RunEntry(r.estimators, (particles,)) for r in suite.runs
                 if particles in r.particles)
    return Suite(suite.name, suite.scenario, suite.steps, seeds, runs, suite.args)


def main(argv: list[str]) -> int:
    p = argparse.ArgumentParser(prog="mutation_check.py", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--gates", default=str(HERE / "gates.yaml"))
    p.add_argument("--mutants", default=str(HERE / "mutants.yaml"))
    sub = p.add_subparsers(dest="command", required=True)
    measure = sub.add_parser("measure")
    measure.add_argument("--build", required=True)
    measure.add_argument("--seeds", default="1-1000",
                         help="one seed list, or SUITE=SEEDS pairs separated by ';'")
    measure.add_argument("--block", default="",
                         help="seeds per block, or SUITE=N pairs separated by ';' (default: the "
                              "suite's gate seed count)")
    measure.add_argument("--out", required=True)
    measure.add_argument("--only")
    measure.add_argument("--markdown")
    measure.set_defaults(run=command_measure)
    short = sub.add_parser("short")
    short.add_argument("--build", required=True)
    short.add_argument("--seeds", default="1-500",
                       help="seeds of the short form, a part of the suites' gate seeds")
    short.add_argument("--out")
    short.set_defaults(run=command_short)
    args = p.parse_args(argv)
    try:
        return args.run(args)
    except (InputError, ValueError) as error:
        print(f"mutation-check: {error}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
