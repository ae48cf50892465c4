#!/usr/bin/env python3
"""Builds one self-contained HTML report from phdslam results folders.

Example:
  phdslam run --scenario paper-synthetic --estimator odometry --seeds 1-3 --steps 500 --out /tmp/r
  python3 reports/make_report.py /tmp/r            # writes /tmp/r/report/index.html + PNG files
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from phdslam_reports.dependencies import ensure_dependencies  # noqa: E402

ensure_dependencies()

from phdslam_reports.csv_table import ResultsFormatError  # noqa: E402
from phdslam_reports.paper import DEFAULT_PAPER_VALUES, PaperValues  # noqa: E402
from phdslam_reports.report import ReportOptions, build_report  # noqa: E402
from phdslam_reports.sweep_folders import sweep_folder_names  # noqa: E402


def parse_arguments(argv: list[str] | None = None) -> argparse.Namespace:
    """The command line."""
    parser = argparse.ArgumentParser(
        prog="make_report.py",
        description=(
            "Build ONE self-contained HTML report (figures embedded as base64 PNG, no scripts, no "
            "external resources) from one or more phdslam results folders (phdslam run --out "
            "DIR). Sections: summary beside the paper's values with Monte Carlo standard errors "
            "and 15 %% flags; Tables I/II/III when the configuration matches; Fig. 1 (trajectory "
            "and map), Fig. 2 (metrics over time), Fig. 3 (particle paths, from particles.csv), "
            "NEES (from a 'nees' column of steps.csv), scaling (scaling.csv), the single-cluster "
            "vs RB-PHD parent weighting (parent_weights.csv from 'phdslam parent-weights') and "
            "Fig. 5 (sensitivity, across folders with different pD / clutter rate). For GPS-only "
            "data (Victoria Park) Fig. 1 draws the GPS fixes of truth/seed-<s>/gps.csv. A "
            "section whose data are missing is skipped with a short note."),
        epilog="Exit codes: 0 report written; 1 a results file is missing or malformed (the "
               "message names the file and column); 2 usage error.",
    )
    parser.add_argument("results_dirs", nargs="+", type=Path, metavar="RESULTS_DIR",
                        help="results folder written by 'phdslam run --out'; a sweep's root "
                             "folder (sweep.json) stands for its value folders")
    parser.add_argument("--out", type=Path, default=None, metavar="REPORT_DIR",
                        help="folder for index.html and the PNG files "
                             "(default: FIRST_RESULTS_DIR/report)")
    parser.add_argument("--title", default="PHD-SLAM validation report",
                        help="report title (default: %(default)s)")
    parser.add_argument("--paper-values", type=Path, default=DEFAULT_PAPER_VALUES,
                        metavar="YAML",
                        help="published numbers (default: reports/paper_values.yaml)")
    parser.add_argument("--paper-table", default=None, metavar="ID",
                        help="compare with this table of the paper-values file (table1, table2, "
                             "table3, ...) whatever the configuration, or 'none'; default: "
                             "chosen from the scenario and the resampling setting")
    return parser.parse_args(argv)


def expand_sweep_roots(dirs: list[Path]) -> list[Path]:
    """A sweep root ('phdslam run' of an experiment with a sweep: sweep.json, no summary.csv)
    stands for its value folders, in the order of sweep.json."""
    expanded: list[Path] = []
    for folder in dirs:
        if not (folder / "sweep.json").is_file() or (folder / "summary.csv").is_file():
            expanded.append(folder)
            continue
        folders = sweep_folder_names(folder)
        expanded.extend(folder / f for f in folders)
    return expanded


def main(argv: list[str] | None = None) -> int:
    """Builds the report; returns the exit code."""
    # A path with bytes that are not UTF-8 is printed with escapes instead of failing.
    for stream in (sys.stdout, sys.stderr):
        if hasattr(stream, "reconfigure"):
            stream.reconfigure(errors="backslashreplace")
    args = parse_arguments(argv)
    out = args.out if args.out is not None else args.results_dirs[0] / "report"
    try:
        args.results_dirs = expand_sweep_roots(args.results_dirs)
        paper = PaperValues.load(args.paper_values)
        if args.paper_table not in (None, "none") and args.paper_table not in paper.tables:
            sys.stderr.write(f"error: --paper-table {args.paper_table}: unknown table (known: "
                             f"{', '.join(paper.tables)}, none)\n")
            return 2
        report = build_report(args.results_dirs, out, paper,
                              ReportOptions(title=args.title, paper_table=args.paper_table))
    except ResultsFormatError as error:
        sys.stderr.write(f"error: {error}\n")
        return 1
    except (OSError, ValueError, OverflowError, ArithmeticError) as error:
        # Whatever else a malformed input makes fail: one line, no traceback; index.html is
        # written last and atomically, so an older report stays whole.
        sys.stderr.write(f"error: the report of {', '.join(map(str, args.results_dirs))} could "
                         f"not be built: {type(error).__name__}: {error}\n")
        return 1
    skipped = [s.title for s in report.sections if not s.shown]
    print(f"report: {(out / 'index.html').resolve()}")
    print(f"{len(report.sections) - len(skipped)} section(s) shown, {len(skipped)} skipped, "
          f"{len(report.figure_files)} figure(s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
