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

RUN_FOLDER = re.compile(r"^(?P<estimator>.+)-N(?P<particles>\d+)$")
DEFAULT_COLUMNS = ("pos_err_m", "map_ospa_m")


def run_means(steps: Path, columns: tuple[str, ...]) -> list[str]:
    """The mean of each column over the rows of one steps.csv (empty when it has no value)."""
    sums = {c: 0.0 for c in columns}
    counts = {c: 0 for c in columns}
    with steps.open(newline="") as f:
        for row in csv.DictReader(f):
            for c in columns:
                cell = row.get(c, "")
                if cell and math.isfinite(float(cell)):
                    sums[c] += float(cell)
                    counts[c] += 1
    return [repr(sums[c] / counts[c]) if counts[c] else "" for c in columns]


def main(argv: list[str]) -> int:
    if len(argv) < 3:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    results, out = Path(argv[1]), Path(argv[2])
    columns = tuple(argv[3:]) or DEFAULT_COLUMNS
    rows = []
    for group in sorted((results / "runs").iterdir()):
        match = RUN_FOLDER.match(group.name)
        if not match or not group.is_dir():
            continue
        for seed_dir in sorted(group.glob("seed-*")):
            steps = seed_dir / "steps.csv"
            if steps.is_file():
                rows.append([match["estimator"], match["particles"], seed_dir.name[5:]] +
                            run_means(steps, columns))
    out.mkdir(parents=True, exist_ok=True)
    with (out / "runs.csv").open("w", newline="") as f:
        writer = csv.writer(f, lineterminator="\n")
        writer.writerow(["estimator", "particles", "seed"] + [f"{c}_mean" for c in columns])
        writer.writerows(rows)
    print(f"{len(rows)} runs: {out / 'runs.csv'}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
