#!/usr/bin/env python3
"""Per-run means of steps.csv columns, written as a runs.csv that `phdslam compare` reads.

    python3 reports/step_means.py RESULTS_DIR OUT_DIR [COLUMN ...]

For every run folder RESULTS_DIR/runs/<estimator>-N<particles>/seed-<seed>/steps.csv, writes one
row of OUT_DIR/runs.csv: estimator, particles, seed and, for each COLUMN (default: pos_err_m and
map_ospa_m, the metrics of single-cluster PHD SLAM's paper over time), `<COLUMN>_mean`, the mean
over the run's steps (empty cells skipped). Then, e.g.,
`phdslam compare --out OUT_DIR --metric map_ospa_m_mean` gives the paired Wilcoxon tests.
"""

from __future__ import annotations

import csv
import math
import re
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from phdslam_reports.dependencies import ensure_dependencies  # noqa: E402

ensure_dependencies()

from phdslam_reports.csv_table import ResultsFormatError, read_csv  # noqa: E402

RUN_FOLDER = re.compile(r"^(?P<estimator>.+)-N(?P<particles>\d+)$")
DEFAULT_COLUMNS = ("pos_err_m", "map_ospa_m")


def run_means(steps: Path, columns: tuple[str, ...]) -> list[str]:
    """The mean of each column over the rows of one steps.csv (empty when it has no finite
    value). ResultsFormatError names the file (line, column) when it lacks a column, has a row
    of the wrong length or a cell that is not a number."""
    table = read_csv(steps, required=columns)
    means = []
    for c in columns:
        values = [v for v in table.num(c) if math.isfinite(v)]
        means.append(repr(sum(values) / len(values)) if values else "")
    return means


def main(argv: list[str]) -> int:
    if len(argv) < 3:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    results, out = Path(argv[1]), Path(argv[2])
    columns = tuple(argv[3:]) or DEFAULT_COLUMNS
    try:
        rows = run_rows(results, columns)
        out.mkdir(parents=True, exist_ok=True)
        with (out / "runs.csv").open("w", newline="") as f:
            writer = csv.writer(f, lineterminator="\n")
            writer.writerow(["estimator", "particles", "seed"] + [f"{c}_mean" for c in columns])
            writer.writerows(rows)
    except ResultsFormatError as error:
        print(f"error: {error}", file=sys.stderr)
        return 1
    except OSError as error:
        print(f"error: {error.filename or results}: {error.strerror or error}", file=sys.stderr)
        return 1
    print(f"{len(rows)} runs: {out / 'runs.csv'}")
    return 0


def run_rows(results: Path, columns: tuple[str, ...]) -> list[list[str]]:
    """One row per run folder with a steps.csv: estimator, particles, seed and the means."""
    runs = results / "runs"
    if not runs.is_dir():
        raise ResultsFormatError(f"{results}: not a results folder (no runs/ folder)")
    rows = []
    for group in sorted(runs.iterdir()):
        match = RUN_FOLDER.match(group.name)
        if not match or not group.is_dir():
            continue
        for seed_dir in sorted(group.glob("seed-*")):
            steps = seed_dir / "steps.csv"
            if steps.is_file():
                rows.append([match["estimator"], match["particles"], seed_dir.name[5:]] +
                            run_means(steps, columns))
    return rows


if __name__ == "__main__":
    sys.exit(main(sys.argv))
