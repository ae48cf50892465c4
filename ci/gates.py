#!/usr/bin/env python3
"""Accuracy gates of phdslam: an exact, a paired and an anchor tier (ci/GATES.md).

  gates.py check --gates FILE --results DIR [--baseline DIR] [--tiers exact,paired,anchor]
                 [--csv OUT]
      gates the results folder DIR (DIR/<suite>/runs.csv per suite of FILE, or DIR/runs.csv when
      FILE has one suite) against the stored baseline; prints one table per tier; exit 0 when every
      gate passes, 1 when one fails, 2 for bad input (the message names the file and field).
  gates.py plan --gates FILE [--markdown]
      the gate table without results: seeds, margin, minimum detectable effect and its power.
  gates.py run-args --gates FILE
      one line per `phdslam run` of the regression: the suite name, a tab, its arguments.
  gates.py update-baseline --gates FILE --results DIR [--accept-inferior REASON]
      stores DIR's runs as the new baseline, after printing the paired verdict against the old
      one; refuses a new baseline that fails the paired tier unless --accept-inferior gives the
      reason, which the header then records (with the commit).
  gates.py spread --gates FILE --results DIR --against DIR2
      the winsorised standard deviation of each paired gate's per-seed log ratios between two
      results folders (a baseline run and a neutral change): the `spread` values of FILE.

`phdslam gate` runs `check`; ci/check-gates.sh runs the regression and then `check`.
"""

from __future__ import annotations

import argparse
import csv
import datetime
import json
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import gate_stats  # noqa: E402
from gate_tables import (BASELINE_FORMAT, Baseline, RunTable, baseline_csv_text,  # noqa: E402
                         check_config, header_checksum, load_baseline, parse_runs,
                         read_text, results_runs_path, select_suite_runs, sha256_text)
from gate_tiers import (AnchorOutcome, ExactOutcome, PairedOutcome, anchor_tier,  # noqa: E402
                        exact_tier, log_ratios, paired_tier)
from gates_file import GatesFile, InputError, load  # noqa: E402

EXIT_PASS, EXIT_FAIL, EXIT_BAD_INPUT = 0, 1, 2
TIERS = ("exact", "paired", "anchor")


def read_results(gates: GatesFile, results: Path) -> dict[str, RunTable]:
    tables = {}
    single = len(gates.suites) == 1
    for suite in gates.suites:
        path = results_runs_path(results, suite, single)
        check_config(path, suite)
        tables[suite.name] = select_suite_runs(parse_runs(read_text(path, "runs table"), str(path)),
                                               suite, "results folder")
    return tables


def print_table(rows: list[list[str]], indent: str = "  ") -> None:
    widths = [max(len(r[i]) for r in rows) for i in range(len(rows[0]))]
    for row in rows:
        print(indent + "  ".join(cell.ljust(w) for cell, w in zip(row, widths)).rstrip())


def pct(value: float, digits: int = 1) -> str:
    return f"{value * 100:+.{digits}f} %"


def print_exact(gates: GatesFile, outcomes: list[ExactOutcome]) -> None:
    print(f"exact tier: every non-timing column of runs.csv, run by run (tolerance |a - b| <= "
          f"{gates.exact_relative:g} max(|a|, |b|) + {gates.exact_absolute:g})")
    rows = [["suite", "runs", "changed", "result"]]
    for o in outcomes:
        rows.append([o.suite, str(o.runs), str(o.changed_runs), "PASS" if o.passed else "FAIL"])
    print_table(rows)
    for o in outcomes:
        for column, (count, largest, where) in sorted(o.columns.items(),
                                                      key=lambda item: -item[1][0])[:12]:
            print(f"    {o.suite}: {column} moved in {count} of {o.runs} runs; largest relative "
                  f"change {largest:.3g} ({where})")
        if len(o.columns) > 12:
            print(f"    {o.suite}: ... and {len(o.columns) - 12} more columns")
        if o.added:
            print(f"    {o.suite}: new columns, not compared: {', '.join(o.added)}")


def paired_header(gates: GatesFile) -> str:
    tested = sum(1 for g in gates.paired if not g.deterministic)
    test = (f"one-sided Yuen test of the {gates.trim:.0%}-trimmed mean" if gates.trim > 0
            else "one-sided paired t-test of the mean")
    return (f"paired tier: {test} of the per-seed log ratios new / baseline, changes below "
            f"{gates.indifference:.1%} indifferent; "
            f"family false-alarm rate {gates.family_false_alarm:g} "
            f"(Bonferroni over {tested} gate{'s' if tested != 1 else ''}: {gates.per_gate_alpha:.3g} each); power "
            f"{gates.power:g} at the margin for changes that re-draw the random numbers")


def plan_rows(gates: GatesFile) -> list[list[str]]:
    rows = [["estimator", "N", "metric", "suite", "seeds", "margin", "MDE redraw", "MDE keep",
             "power@margin"]]
    for g in gates.paired:
        seeds = len(gates.suite(g.suite).seed_list())
        if g.deterministic:
            rows.append([g.estimator, str(g.particles), g.metric, g.suite, str(seeds),
                         f"{g.margin:.1%}", "deterministic", "deterministic", "1"])
            continue
        power = gates.power_at(g, g.margin)
        rows.append([g.estimator, str(g.particles), g.metric, g.suite, str(seeds),
                     f"{g.margin:.1%}", f"{gates.detectable(g, g.spread_redraw):.2%}",
                     f"{gates.detectable(g, g.spread_keep):.2%}", f"{power:.3f}"])
    return rows


def print_paired(gates: GatesFile, outcomes: list[PairedOutcome]) -> None:
    print(paired_header(gates))
    rows = [["estimator", "N", "metric", "seeds", "margin", "MDE", "power", "baseline", "new",
             "change", "result", "note"]]
    for o in outcomes:
        rows.append([o.gate.estimator, str(o.gate.particles), o.gate.metric, str(o.seeds),
                     f"{o.gate.margin:.1%}", f"{o.detectable:.2%}", f"{o.power_at_margin:.2f}",
                     f"{o.baseline_mean:.4g}", f"{o.new_mean:.4g}", pct(o.change, 2),
                     "PASS" if o.passed else "FAIL", o.note])
    print_table(rows)


def print_anchors(gates: GatesFile, outcomes: list[AnchorOutcome]) -> None:
    print(f"anchor tier: |value - published| <= tolerance x published + z x combined Monte Carlo "
          f"error (family level {gates.anchor_false_alarm:g}, {len(outcomes)} anchors)")
    rows = [["estimator", "N", "metric", "value", "se", "reference", "ref", "ref se", "allowed",
             "result"]]
    for o in outcomes:
        for source, ref, ref_se, allowed, passed in o.checks:
            rows.append([o.anchor.estimator, str(o.anchor.particles), o.anchor.metric,
                         f"{o.value:.4g}", f"{o.se:.2g}", source, f"{ref:.4g}", f"{ref_se:.2g}",
                         f"+-{allowed:.3g}", "PASS" if passed else "FAIL"])
    print_table(rows)


def write_csv(path: Path, exact: list[ExactOutcome], paired: list[PairedOutcome],
              anchors: list[AnchorOutcome]) -> None:
    """One row per gate: tier, suite, estimator, particles, metric, value, passed."""
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(path.name + ".tmp")
    with tmp.open("w", newline="", encoding="utf-8") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["tier", "suite", "estimator", "particles", "metric", "seeds", "margin",
                    "detectable", "baseline", "new", "change", "statistic", "critical", "passed"])
        for o in exact:
            w.writerow(["exact", o.suite, "", "", "", o.runs, "", "", "", "", o.changed_runs, "",
                        "", int(o.passed)])
        for o in paired:
            t = o.test
            w.writerow(["paired", o.gate.suite, o.gate.estimator, o.gate.particles, o.gate.metric,
                        o.seeds, o.gate.margin, f"{o.detectable:.6g}", f"{o.baseline_mean:.10g}",
                        f"{o.new_mean:.10g}", f"{o.change:.6g}",
                        f"{t.statistic:.6g}" if t else "", f"{t.critical:.6g}" if t else "",
                        int(o.passed)])
        for o in anchors:
            for source, ref, _, allowed, passed in o.checks:
                w.writerow(["anchor", o.anchor.suite, o.anchor.estimator, o.anchor.particles,
                            o.anchor.metric, "", o.anchor.tolerance, f"{allowed:.6g}",
                            f"{ref:.10g}", f"{o.value:.10g}", f"{o.value - ref:.6g}", source, "",
                            int(passed)])
    tmp.replace(path)


def run_tiers(gates: GatesFile, new: dict[str, RunTable], baseline: Baseline | None,
              tiers: set[str]) -> tuple[list[ExactOutcome], list[PairedOutcome],
                                        list[AnchorOutcome]]:
    exact, paired, anchors = [], [], []
    if baseline is not None:
        if "exact" in tiers:
            exact = [exact_tier(gates, s.name, new[s.name], baseline.tables[s.name])
                     for s in gates.suites]
        if "paired" in tiers:
            paired = [paired_tier(gates, g, new[g.suite], baseline.tables[g.suite])
                      for g in gates.paired]
    if "anchor" in tiers:
        anchors = [anchor_tier(gates, a, new[a.suite]) for a in gates.anchors]
    return exact, paired, anchors


def baseline_line(baseline: Baseline) -> str:
    h = baseline.header
    line = f"baseline {baseline.folder}: commit {h.get('commit', '?')}, {h.get('created', '?')}"
    if h.get("accepted_inferior"):
        line += f"; ACCEPTED DESPITE A FAILED PAIRED TIER: {h['accepted_inferior']}"
    return line


def command_check(args: argparse.Namespace) -> int:
    gates = load(Path(args.gates))
    tiers = set(args.tiers.split(","))
    unknown = tiers - set(TIERS)
    if unknown:
        raise InputError(f"--tiers: unknown tier(s) {sorted(unknown)} (exact, paired, anchor)")
    new = read_results(gates, Path(args.results))
    baseline = None
    if tiers & {"exact", "paired"}:
        folder = Path(args.baseline) if args.baseline else gates.baseline
        baseline = load_baseline(folder, gates.suites)
        print(baseline_line(baseline))
    exact, paired, anchors = run_tiers(gates, new, baseline, tiers)
    if exact:
        print_exact(gates, exact)
    if paired:
        print_paired(gates, paired)
    if anchors:
        print_anchors(gates, anchors)
    if args.csv:
        write_csv(Path(args.csv), exact, paired, anchors)
    verdicts = {"exact": all(o.passed for o in exact), "paired": all(o.passed for o in paired),
                "anchor": all(o.passed for o in anchors)}
    shown = [t for t in TIERS if t in tiers and (t == "anchor" or baseline is not None)]
    print("gates: " + ", ".join(f"{t} {'PASS' if verdicts[t] else 'FAIL'}" for t in shown))
    return EXIT_PASS if all(verdicts[t] for t in shown) else EXIT_FAIL


def command_plan(args: argparse.Namespace) -> int:
    gates = load(Path(args.gates))
    rows = plan_rows(gates)
    if args.markdown:
        print("| " + " | ".join(rows[0]) + " |")
        print("|" + "---|" * len(rows[0]))
        for row in rows[1:]:
            print("| " + " | ".join(row) + " |")
        return EXIT_PASS
    print(paired_header(gates))
    print_table(rows)
    return EXIT_PASS


def command_run_args(args: argparse.Namespace) -> int:
    gates = load(Path(args.gates))
    for suite in gates.suites:
        for run in suite.run_arguments():
            print("\t".join([suite.name] + run))
    return EXIT_PASS


def git_commit(repo: Path) -> str:
    try:
        head = subprocess.run(["git", "-C", str(repo), "rev-parse", "--short=12", "HEAD"],
                              capture_output=True, text=True, check=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", str(repo), "status", "--porcelain", "--",
                                ":!ci/baseline"], capture_output=True, text=True,
                               check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown (not a git checkout)"
    return head + (" with uncommitted changes" if dirty else "")


def command_update(args: argparse.Namespace) -> int:
    gates = load(Path(args.gates))
    new = read_results(gates, Path(args.results))
    verdict: dict = {"against": None, "paired": []}
    status = EXIT_PASS
    old_header = gates.baseline / "baseline.json"
    if old_header.exists():
        old = load_baseline(gates.baseline, gates.suites, fewer_seeds=True)
        print(baseline_line(old))
        exact, paired, _ = run_tiers(gates, new, old, {"exact", "paired"})
        print_exact(gates, exact)
        print_paired(gates, paired)
        verdict["against"] = old.header.get("commit")
        verdict["paired"] = [{"gate": o.gate.label, "seeds": o.seeds,
                              "change": round(o.change, 6), "passed": o.passed} for o in paired]
        if not all(o.passed for o in paired):
            if not args.accept_inferior:
                print("update-baseline: REFUSED: the new results fail the paired tier against the "
                      "old baseline; fix the regression, or give --accept-inferior REASON",
                      file=sys.stderr)
                return EXIT_FAIL
            status = EXIT_PASS
    else:
        print(f"update-baseline: no baseline in {gates.baseline} yet; writing the first one")
    gates.baseline.mkdir(parents=True, exist_ok=True)
    header = {"format": BASELINE_FORMAT,
              "created": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d"),
              "commit": git_commit(gates.path.resolve().parent),
              "gates_file": gates.path.name,
              "verdict": verdict,
              "accepted_inferior": args.accept_inferior or None,
              "suites": {}}
    for suite in gates.suites:
        text = baseline_csv_text(new[suite.name])
        path = gates.baseline / f"{suite.name}.csv"
        tmp = path.with_name(path.name + ".tmp")
        tmp.write_text(text, encoding="utf-8")
        tmp.replace(path)
        header["suites"][suite.name] = {"definition": suite.definition(),
                                        "runs": len(new[suite.name].rows),
                                        "sha256": sha256_text(text)}
    header["checksum"] = header_checksum(header)
    tmp = old_header.with_name("baseline.json.tmp")
    tmp.write_text(json.dumps(header, indent=1, sort_keys=True) + "\n", encoding="utf-8")
    tmp.replace(old_header)
    print(f"update-baseline: wrote {gates.baseline} ({header['commit']})")
    return status


def command_spread(args: argparse.Namespace) -> int:
    gates = load(Path(args.gates))
    base = read_results(gates, Path(args.results))
    other = read_results(gates, Path(args.against))
    rows = [["estimator", "N", "metric", "seeds", "winsorised sd", "trimmed mean change",
             "seeds for the margin"]]
    for g in gates.paired:
        if g.deterministic:
            continue
        d, _, _ = log_ratios(g, other[g.suite], base[g.suite])
        sd = gate_stats.winsorised_sd(d, gates.trim)
        needed = gate_stats.seeds_needed(sd, g.margin, gates.per_gate_alpha, gates.power,
                                         gates.trim, gates.indifference)
        rows.append([g.estimator, str(g.particles), g.metric, str(len(d)), f"{sd:.4f}",
                     pct(gate_stats.trimmed_mean(d, gates.trim) if d else 0.0, 2), str(needed)])
    print_table(rows)
    return EXIT_PASS


def parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="gates.py", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="command", required=True)
    check = sub.add_parser("check", help="gate a results folder")
    check.add_argument("--gates", required=True, help="gates file (ci/gates.yaml)")
    check.add_argument("--results", required=True, help="results folder")
    check.add_argument("--baseline", help="baseline folder (default: the gates file's)")
    check.add_argument("--tiers", default=",".join(TIERS), help="comma list of exact,paired,anchor")
    check.add_argument("--csv", help="also write one row per gate to this CSV file")
    check.set_defaults(run=command_check)
    plan = sub.add_parser("plan", help="the gate table without results")
    plan.add_argument("--gates", required=True)
    plan.add_argument("--markdown", action="store_true", help="the table as Markdown")
    plan.set_defaults(run=command_plan)
    run_args = sub.add_parser("run-args", help="the regression's phdslam run arguments")
    run_args.add_argument("--gates", required=True)
    run_args.set_defaults(run=command_run_args)
    update = sub.add_parser("update-baseline", help="store a results folder as the baseline")
    update.add_argument("--gates", required=True)
    update.add_argument("--results", required=True)
    update.add_argument("--accept-inferior", metavar="REASON",
                        help="store it even when it fails the paired tier, with this reason")
    update.set_defaults(run=command_update)
    spread = sub.add_parser("spread", help="paired spreads between two results folders")
    spread.add_argument("--gates", required=True)
    spread.add_argument("--results", required=True)
    spread.add_argument("--against", required=True)
    spread.set_defaults(run=command_spread)
    return p


def main(argv: list[str]) -> int:
    args = parser().parse_args(argv)
    try:
        return args.run(args)
    except InputError as error:
        print(f"gates: {error}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except ValueError as error:  # e.g. fewer than 5 common seeds
        print(f"gates: {error}", file=sys.stderr)
        return EXIT_BAD_INPUT


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
