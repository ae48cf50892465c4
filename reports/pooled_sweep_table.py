#!/usr/bin/env python3
"""Prints a Markdown table of a sweep's runs pooled over its points, one row per estimator and N.

Example (validation/experiments/mrclam.yaml, the five robots of MRCLAM dataset 6):
  python3 reports/pooled_sweep_table.py results/mrclam

Reads runs.csv of every point folder named in sweep.json. Per (estimator, N): the position and
heading RMSE pooled over every scored step of every run (sqrt of the summed squared errors over
the summed counts), the position RMSE of each point the same way, the means over runs of the
final-map GOSPA, missed and false landmarks and map size, the data-association TPR and TNR
pooled over measurements (each run's rate weighted by its positives and negatives, from the
points' summary.csv), the fraction of steps whose true pose lies inside the 95 % ellipsoid of the
estimate's pose covariance (particle spread, and its Rao-Blackwellised form; 0.95 for a
consistent filter: unlike the mean NEES it is not dominated by a few collapsed covariances;
each run's fraction weighted by its scored steps), the NIS per measurement pooled over measurements, the
mean time per step and the number of runs. Empty cells: not defined for that estimator.

When the points hold the rows of a posterior Cramer-Rao bound (docs/algorithms/pcrb.md section 6),
each estimator row also gets its position and heading efficiency: its RMSE over the bound's on
the runs (robot, seed) both have, pooled like the RMSE (sqrt of the summed squared errors over
the bound's), ± the delta-method Monte Carlo SE over those runs (reports/pcrb_efficiency.py);
the filters against `pcrb`, the smoothers against `pcrb-smoother`. The bound rows are marked
"(bound)" and have no efficiency.
"""

from __future__ import annotations

import argparse
import csv
import json
import math
import sys
from collections import defaultdict
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from phdslam_reports.dependencies import ensure_dependencies  # noqa: E402

ensure_dependencies()

from phdslam_reports.bound_efficiency import (  # noqa: E402
    BOUNDS,
    Efficiency,
    ratio_with_error,
    row_name,
)
from phdslam_reports.bound_efficiency import cell as efficiency_cell  # noqa: E402
from phdslam_reports.table_efficiency import bound_of  # noqa: E402


def number(row: dict, key: str) -> float | None:
    text = row.get(key, "")
    if text in ("", None):
        return None
    value = float(text)
    return value if math.isfinite(value) else None


class Pool:
    """Sums of one (estimator, N) over the runs of every point."""

    def __init__(self) -> None:
        self.sq = defaultdict(float)
        self.count = defaultdict(float)
        self.means = defaultdict(list)
        self.runs = 0
        self.squared_errors: dict[tuple[str, int], dict[str, float]] = {}
        """Per run (point, seed): the summed squared position and heading errors."""

    def add_rms(self, key: str, rms: float | None, count: float | None) -> None:
        if rms is not None and count:
            self.sq[key] += rms * rms * count
            self.count[key] += count

    def rms(self, key: str) -> float | None:
        return math.sqrt(self.sq[key] / self.count[key]) if self.count[key] else None

    def add_weighted(self, key: str, value: float | None, weight: float | None) -> None:
        if value is not None and weight:
            self.sq[key] += value * weight
            self.count[key] += weight

    def weighted(self, key: str) -> float | None:
        return self.sq[key] / self.count[key] if self.count[key] else None

    def add_run(self, run: tuple[str, int], row: dict, count: float | None) -> None:
        sums = {}
        for key, column in (("pos", "pos_rmse_m"), ("heading", "heading_rmse_deg")):
            rms = number(row, column)
            if rms is not None and count:
                sums[key] = rms * rms * count
        self.squared_errors[run] = sums

    def mean(self, key: str) -> float | None:
        values = self.means[key]
        return sum(values) / len(values) if values else None


def read_csv(path: Path) -> list[dict]:
    with path.open(newline="", encoding="utf-8") as handle:
        return list(csv.DictReader(handle))


def pool_sweep(root: Path) -> tuple[list[str], dict[tuple[str, int], Pool]]:
    sweep = json.loads((root / "sweep.json").read_text(encoding="utf-8"))
    folders = sweep["folders"]
    pools: dict[tuple[str, int], Pool] = defaultdict(Pool)
    for point in folders:
        for_each_row(root / point / "runs.csv", lambda row: add_run_row(pools, point, row))
        for_each_row(root / point / "summary.csv", lambda row: add_summary_row(pools, row))
    return folders, pools


def for_each_row(path: Path, add) -> None:
    """Calls ``add`` on every row of a CSV file; a malformed cell is named by file and line."""
    for line, row in enumerate(read_csv(path), start=2):
        try:
            add(row)
        except KeyError as error:
            raise ValueError(f"{path}, line {line}: no column {error}") from error
        except ValueError as error:
            raise ValueError(f"{path}, line {line}: {error}") from error


def add_run_row(pools: dict[tuple[str, int], Pool], point: str, row: dict) -> None:
    p = pools[(row["estimator"], int(row["particles"]))]
    p.runs += 1
    count = number(row, "pos_err_count")
    p.add_rms("pos", number(row, "pos_rmse_m"), count)
    p.add_rms("heading", number(row, "heading_rmse_deg"), count)
    p.add_rms(f"pos:{point}", number(row, "pos_rmse_m"), count)
    p.add_run((point, int(row["seed"])), row, count)
    p.add_weighted("nis", number(row, "nis_mean"), number(row, "nis_count"))
    p.add_weighted("coverage", number(row, "coverage"), count)
    p.add_weighted("coverage_rb", number(row, "coverage_rb"), count)
    for key in ("gospa_m", "n_missed", "n_false", "map_size", "ms_per_step_mean"):
        value = number(row, key)
        if value is not None:
            p.means[key].append(value)


def add_summary_row(pools: dict[tuple[str, int], Pool], row: dict) -> None:
    p = pools[(row["estimator"], int(row["particles"]))]
    p.add_weighted("tpr", number(row, "da_tpr"), number(row, "da_positives"))
    p.add_weighted("tnr", number(row, "da_tnr"), number(row, "da_negatives"))


def efficiency(pools: dict[tuple[str, int], Pool], estimator: str, n: int,
               key: str) -> Efficiency | None:
    """(RMSE / bound, its SE, paired runs) over the runs the estimator and its bound share."""
    bound = pools.get((bound_of(estimator), 1))
    if estimator in BOUNDS or bound is None:
        return None
    mine = pools[(estimator, n)].squared_errors
    pairs = [(mine[run][key], bound.squared_errors[run][key]) for run in mine
             if key in mine[run] and key in bound.squared_errors.get(run, {})
             and bound.squared_errors[run][key] > 0]
    if not pairs:
        return None
    ratio, se = ratio_with_error([a for a, _ in pairs], [b for _, b in pairs])
    return Efficiency(ratio, se, len(pairs))


def cell(value: float | None, digits: int) -> str:
    return "" if value is None else f"{value:.{digits}f}"


def markdown(folders: list[str], pools: dict[tuple[str, int], Pool]) -> str:
    with_bound = any(estimator in BOUNDS for estimator, _ in pools)
    header = (["estimator", "N", "runs", "pos RMSE m", "heading RMSE deg"]
              + (["pos efficiency", "heading efficiency"] if with_bound else [])
              + [f"pos RMSE {f.removeprefix('sweep-')}" for f in folders]
              + ["GOSPA m", "missed", "false", "map size", "DA TPR", "DA TNR",
                 "95 % coverage", "95 % coverage RB", "NIS", "ms/step"])
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    for (estimator, n), p in sorted(pools.items()):
        cells = [row_name(estimator, estimator), str(n), str(p.runs), cell(p.rms("pos"), 2),
                 cell(p.rms("heading"), 1)]
        if with_bound:
            cells += [efficiency_cell(efficiency(pools, estimator, n, key))
                      for key in ("pos", "heading")]
        cells += [cell(p.rms(f"pos:{f}"), 2) for f in folders]
        cells += [cell(p.mean("gospa_m"), 2), cell(p.mean("n_missed"), 1),
                  cell(p.mean("n_false"), 1), cell(p.mean("map_size"), 1),
                  cell(p.weighted("tpr"), 3), cell(p.weighted("tnr"), 3),
                  cell(p.weighted("coverage"), 3), cell(p.weighted("coverage_rb"), 3),
                  cell(p.weighted("nis"), 2), cell(p.mean("ms_per_step_mean"), 2)]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("sweep_root", type=Path, help="a sweep's results folder (sweep.json)")
    args = parser.parse_args(argv)
    try:
        folders, pools = pool_sweep(args.sweep_root)
    except (OSError, KeyError, ValueError) as error:
        print(f"error: {args.sweep_root}: {error}".splitlines()[0], file=sys.stderr)
        return 1
    sys.stdout.write(markdown(folders, pools))
    return 0


if __name__ == "__main__":
    sys.exit(main())
