#!/usr/bin/env python3
"""Writes RESULTS_DIR/table.md: our values ± Monte Carlo standard error beside the paper's.

Example:
  python3 reports/tables.py /tmp/r          # writes /tmp/r/table.md and /tmp/r/table.csv
"""

from __future__ import annotations

import argparse
import csv
import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from phdslam_reports.dependencies import ensure_dependencies  # noqa: E402

ensure_dependencies()

from phdslam_reports.comparison import Comparison, compare  # noqa: E402
from phdslam_reports.csv_table import ResultsFormatError  # noqa: E402
from phdslam_reports.markdown import report_markdown  # noqa: E402
from phdslam_reports.paper import DEFAULT_PAPER_VALUES, PaperValues  # noqa: E402
from phdslam_reports.results import ResultsFolder  # noqa: E402


def write_comparison_csv(comparison: Comparison, path: Path) -> None:
    """One line per (estimator, N, metric): ours, se, paper, relative difference, flagged.

    paper_table is the id of the table that gave the paper's value (da_accuracy for the DA
    rates), else the table the row was compared with.
    """
    with path.open("w", newline="", encoding="utf-8") as out:
        writer = csv.writer(out, lineterminator="\n")
        writer.writerow(["estimator", "particles", "runs", "metric", "ours", "se", "paper",
                         "relative_difference", "flagged", "paper_table"])

        def text(value: float | None) -> str:
            return "" if value is None or not math.isfinite(value) else f"{value:.10g}"

        for row in comparison.rows:
            for cell in row.cells:
                writer.writerow([row.group.estimator, row.group.particles, row.runs, cell.metric,
                                 text(cell.ours), text(cell.se), text(cell.paper),
                                 text(cell.relative), int(cell.flagged),
                                 cell.source or (row.table.id if row.table else "")])


def parse_arguments(argv: list[str] | None = None) -> argparse.Namespace:
    """The command line."""
    parser = argparse.ArgumentParser(
        prog="tables.py",
        description=(
            "Write RESULTS_DIR/table.md (Markdown) and RESULTS_DIR/table.csv: every summary.csv "
            "row with its Monte Carlo standard error beside the paper's value and the relative "
            "difference (flagged beyond 15 %%), plus Tables I/II/III in the paper's layout when "
            "the results hold their configuration."),
        epilog="Exit codes: 0 written; 1 a results file is missing or malformed; 2 usage error.",
    )
    parser.add_argument("results_dir", type=Path, metavar="RESULTS_DIR",
                        help="results folder written by 'phdslam run --out'")
    parser.add_argument("--out", type=Path, default=None, metavar="MD_FILE",
                        help="Markdown file to write (default: RESULTS_DIR/table.md)")
    parser.add_argument("--csv", type=Path, default=None, metavar="CSV_FILE",
                        help="CSV file to write (default: RESULTS_DIR/table.csv)")
    parser.add_argument("--paper-values", type=Path, default=DEFAULT_PAPER_VALUES,
                        metavar="YAML",
                        help="published numbers (default: reports/paper_values.yaml)")
    parser.add_argument("--paper-table", default=None, metavar="ID",
                        help="compare with this table id (table1, table2, table3) or 'none'; "
                             "default: chosen from the configuration")
    return parser.parse_args(argv)


def main(argv: list[str] | None = None) -> int:
    """Writes the tables; returns the exit code."""
    args = parse_arguments(argv)
    try:
        paper = PaperValues.load(args.paper_values)
        if args.paper_table not in (None, "none") and args.paper_table not in paper.tables:
            sys.stderr.write(f"error: --paper-table {args.paper_table}: unknown table\n")
            return 2
        results = ResultsFolder(args.results_dir)
        if results.summary is None:
            raise ResultsFormatError(f"{results.path / 'summary.csv'}: file not found")
        comparison = compare(results, paper, args.paper_table)
        markdown = report_markdown(results, paper, comparison)
    except ResultsFormatError as error:
        sys.stderr.write(f"error: {error}\n")
        return 1
    md_path = args.out or args.results_dir / "table.md"
    csv_path = args.csv or args.results_dir / "table.csv"
    md_path.write_text(markdown + "\n", encoding="utf-8")
    write_comparison_csv(comparison, csv_path)
    print(f"tables: {md_path} {csv_path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
