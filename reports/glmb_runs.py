#!/usr/bin/env python3
"""Per-run numbers of the delta-GLMB-SLAM paper's comparisons, as runs.csv files that
`phdslam compare` reads.

    python3 reports/glmb_runs.py RESULTS_DIR OUT_DIR

RESULTS_DIR is a results folder or a sweep root (sweep.json); for each results folder F it writes
OUT_DIR/<F's name>/runs.csv (OUT_DIR/runs.csv for a single folder) with estimator, particles,
seed and map_ospa_m_mean (the run's mean per-step map OSPA), false_landmarks (final-map estimates
without a true landmark within the OSPA cut-off), x_rmse_m and y_rmse_m (phdslam_reports/
glmb_paper.py). Then `phdslam compare --out OUT_DIR/<F> --metric map_ospa_m_mean,false_landmarks`.
"""

from __future__ import annotations

import csv
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from phdslam_reports.dependencies import ensure_dependencies  # noqa: E402

ensure_dependencies()

from phdslam_reports.glmb_paper import RUN_COLUMNS, run_rows  # noqa: E402
from phdslam_reports.csv_table import ResultsFormatError  # noqa: E402
from phdslam_reports.results import ResultsFolder  # noqa: E402
from phdslam_reports.sweep_folders import sweep_folder_names  # noqa: E402


def main(argv: list[str]) -> int:
    if len(argv) != 3:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    results, out = Path(argv[1]), Path(argv[2])
    try:
        names = sweep_folder_names(results)
        targets = [(results, out)] if names is None else [(results / n, out / n) for n in names]
        # Every folder is read before anything is written.
        tables = [(target, run_rows(ResultsFolder(source))) for source, target in targets]
        for target, rows in tables:
            write_runs(target, rows)
    except ResultsFormatError as error:
        print(f"error: {error}", file=sys.stderr)
        return 1
    except (OSError, ValueError, ArithmeticError) as error:
        print(f"error: {results}: {type(error).__name__}: {error}", file=sys.stderr)
        return 1
    return 0


def write_runs(target: Path, rows: list) -> None:
    target.mkdir(parents=True, exist_ok=True)
    with (target / "runs.csv").open("w", newline="", encoding="utf-8") as f:
        writer = csv.writer(f, lineterminator="\n")
        writer.writerow(["estimator", "particles", "seed", *RUN_COLUMNS])
        writer.writerows([[*r[:3], *(repr(v) for v in r[3:])] for r in rows])
    print(f"{len(rows)} runs: {target / 'runs.csv'}")


if __name__ == "__main__":
    sys.exit(main(sys.argv))
