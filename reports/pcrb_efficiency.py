#!/usr/bin/env python3
"""Prints each estimator's RMSE beside the posterior Cramer-Rao bounds and its efficiency ratio.

Example (validation/experiments/pcrb_table2.yaml):
  python3 reports/pcrb_efficiency.py results/pcrb-table2

Reads runs.csv of a results folder, or of every point folder of a sweep root (sweep.json), which
holds the bound rows `pcrb` and `pcrb-smoother` (docs/algorithms/pcrb.md section 6) beside the
estimators' rows. Per point and (estimator, N), over the seeds that have both the estimator's run
and the bound's: the pooled position and heading RMSE (root of the mean over runs of each run's
mean squared error, every run having the same steps), the pooled bound on the same seeds, and the
efficiency ratio RMSE / bound with its Monte Carlo standard error (delta method on the paired
per-seed mean squared errors: var log r = (var a / a^2 + var b / b^2 - 2 cov(a, b) / (a b)) / 4n).
A ratio more than two standard errors below 1 is flagged, on 50 paired seeds or more: an
estimator significantly below its bound means a bug in the bound or in the estimator's
evaluation. On fewer seeds the ratio is marked "few seeds" instead: a run's mean squared error is
heavy-tailed, and on few seeds its mean and standard error are low together (on the synthetic
scenario, 1000 steps, smoother-known: 0.68 +- 0.09 on seeds 1-10, 1.04 +- 0.04 on seeds 1-200).
The filtering bound `pcrb` is not binding for batch estimators (the smoothers,
config.json's `batch`): their ratio against it is shown, never flagged. The bound rows are labelled
"bound", never ranked.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from phdslam_reports.bound_efficiency import (  # noqa: F401  (re-exported for the tests)
    BOUNDS,
    MIN_FLAG_SEEDS,
    Efficiency,
    cell,
    efficiency_rows,
    markdown,
    ratio_with_error,
    read_batch_estimators,
    read_runs,
)
from phdslam_reports.sweep_folders import sweep_folder_names


def rows_of(folder: Path) -> list[dict]:
    return efficiency_rows(read_runs(folder), read_batch_estimators(folder))


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("results", type=Path, help="a results folder or a sweep root")
    args = parser.parse_args(argv)
    try:
        folders = sweep_folder_names(args.results)
        if folders is not None:
            tables = [markdown(rows_of(args.results / f), f) for f in folders]
        else:
            tables = [markdown(rows_of(args.results))]
    except (OSError, KeyError, ValueError, TypeError) as error:
        print(f"error: {args.results}: {error}", file=sys.stderr)
        return 2
    print("\n\n".join(tables))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
