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
A ratio more than two standard errors below 1 is flagged: an estimator significantly below its
bound means a bug in the bound or in the estimator's evaluation. The bound rows are labelled
"bound", never ranked.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from phdslam_reports.bound_efficiency import (  # noqa: F401  (re-exported for the tests)
    BOUNDS,
    cell,
    efficiency_rows,
    markdown,
    ratio_with_error,
    read_runs,
)
from phdslam_reports.sweep_folders import sweep_folder_names


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("results", type=Path, help="a results folder or a sweep root")
    args = parser.parse_args(argv)
    try:
        folders = sweep_folder_names(args.results)
        if folders is not None:
            tables = [markdown(efficiency_rows(read_runs(args.results / f)), f) for f in folders]
        else:
            tables = [markdown(efficiency_rows(read_runs(args.results)))]
    except (OSError, KeyError, ValueError, TypeError) as error:
        print(f"error: {args.results}: {error}", file=sys.stderr)
        return 2
    print("\n\n".join(tables))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
