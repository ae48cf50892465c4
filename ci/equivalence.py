#!/usr/bin/env python3
"""Paired equivalence test (TOST) of two phdslam results folders run on the same seeds.

  ci/equivalence.py BEFORE AFTER [--metric pos_rmse_m,gospa_m] [--margin 0.05] [--alpha 0.05]
                    [--min-seeds 2] [--estimator-map BEFORE_NAME=AFTER_NAME] [--csv FILE]

Runs are paired by (estimator, particles, seed) from the runs.csv of both folders (for a sweep
root, sweep.json: every sweep folder in turn). For every (estimator, particles) group and every
metric (a runs.csv column), with d = AFTER - BEFORE over the n seeds where both runs have a value:

  margin    = --margin x |mean of BEFORE|              (default 5 %)
  CI        = mean(d) +- t(1 - alpha, n - 1) x sd(d) / sqrt(n)   (the 1 - 2 alpha = 90 % interval)
  TOST      p = max(p_lower, p_upper) of the one-sided tests of mean(d) > -margin and
              mean(d) < +margin; equivalence is shown when p < alpha, i.e. the CI lies strictly
              inside (-margin, +margin).

When every difference is the same value (sd = 0, e.g. identical runs) the interval is that value.
Fewer than --min-seeds paired seeds (never fewer than 2) is "not shown". A run present in only one
folder, or a value present in only one of a pair, is counted in `unpaired` and left out.

Prints one line per group and metric and exits 0 when equivalence is shown for every tested line,
1 when it is not for some line (or nothing could be tested), 2 for a usage error or a missing or
malformed file. The Student t distribution is computed here (no SciPy needed).
"""

from __future__ import annotations

import argparse
import csv
import json
import math
import sys
from dataclasses import dataclass
from pathlib import Path

DEFAULT_METRICS = ("pos_rmse_m", "gospa_m")


class InputError(Exception):
    """A missing or malformed input file (exit 2)."""


# ---------------------------------------------------------------------------------------------
# Student t distribution


def _betacf(a: float, b: float, x: float) -> float:
    """Continued fraction of the regularised incomplete beta function (modified Lentz)."""
    tiny = 1e-300
    c, d = 1.0, 1.0 - (a + b) * x / (a + 1.0)
    d = 1.0 / (d if abs(d) > tiny else tiny)
    h = d
    for m in range(1, 10000):
        m2 = 2 * m
        for numerator in (m * (b - m) * x / ((a + m2 - 1.0) * (a + m2)),
                          -(a + m) * (a + b + m) * x / ((a + m2) * (a + m2 + 1.0))):
            d = 1.0 + numerator * d
            d = 1.0 / (d if abs(d) > tiny else tiny)
            c = 1.0 + numerator / c
            c = c if abs(c) > tiny else tiny
            h *= d * c
        if abs(d * c - 1.0) < 1e-15:
            break
    return h


def regularized_beta(a: float, b: float, x: float) -> float:
    """I_x(a, b) for a, b > 0 and 0 <= x <= 1."""
    if x <= 0.0:
        return 0.0
    if x >= 1.0:
        return 1.0
    log_front = (math.lgamma(a + b) - math.lgamma(a) - math.lgamma(b) + a * math.log(x) +
                 b * math.log1p(-x))
    if x < (a + 1.0) / (a + b + 2.0):
        return math.exp(log_front) * _betacf(a, b, x) / a
    return 1.0 - math.exp(log_front) * _betacf(b, a, 1.0 - x) / b


def t_cdf(t: float, df: float) -> float:
    """P(T <= t) for Student's t with df degrees of freedom."""
    if math.isinf(t):
        return 1.0 if t > 0 else 0.0
    tail = 0.5 * regularized_beta(0.5 * df, 0.5, df / (df + t * t))
    return 1.0 - tail if t > 0 else tail


def t_quantile(p: float, df: float) -> float:
    """The t with P(T <= t) = p (0 < p < 1), by bisection on t_cdf."""
    if not 0.0 < p < 1.0:
        raise ValueError(f"quantile probability {p} outside (0, 1)")
    if p < 0.5:
        return -t_quantile(1.0 - p, df)
    low, high = 0.0, 1.0
    while t_cdf(high, df) < p:
        high *= 2.0
    for _ in range(200):
        mid = 0.5 * (low + high)
        if t_cdf(mid, df) < p:
            low = mid
        else:
            high = mid
    return 0.5 * (low + high)


# ---------------------------------------------------------------------------------------------
# The test


@dataclass
class Tost:
    """The paired TOST of one group and metric."""

    n: int
    mean_before: float
    mean_after: float
    mean_difference: float
    ci_low: float
    ci_high: float
    margin: float
    p_value: float
    equivalent: bool
    reason: str


def paired_tost(before: list[float], after: list[float], margin_fraction: float, alpha: float,
                min_seeds: int) -> Tost:
    """TOST of mean(after - before) within +-margin_fraction x |mean(before)|."""
    n = len(before)
    nan = float("nan")
    if n == 0:
        return Tost(0, nan, nan, nan, nan, nan, nan, nan, False, "no paired values")
    mean_before = sum(before) / n
    mean_after = sum(after) / n
    differences = [a - b for a, b in zip(after, before)]
    mean_d = sum(differences) / n
    margin = margin_fraction * abs(mean_before)
    if n < max(2, min_seeds):
        return Tost(n, mean_before, mean_after, mean_d, nan, nan, margin, nan, False,
                    f"too few seeds ({n} < {max(2, min_seeds)})")
    variance = sum((d - mean_d) ** 2 for d in differences) / (n - 1)
    se = math.sqrt(variance / n)
    df = n - 1
    if se == 0.0:
        low = high = mean_d
        p_value = 0.0 if -margin < mean_d < margin else 1.0
    else:
        half = t_quantile(1.0 - alpha, df) * se
        low, high = mean_d - half, mean_d + half
        p_lower = 1.0 - t_cdf((mean_d + margin) / se, df)  # H0: mean_d <= -margin
        p_upper = t_cdf((mean_d - margin) / se, df)  # H0: mean_d >= +margin
        p_value = max(p_lower, p_upper)
    equivalent = p_value < alpha
    if equivalent:
        reason = "equivalent"
    elif margin == 0.0:
        reason = "not shown (zero margin: BEFORE mean is 0)"
    else:
        reason = "not shown (interval leaves the margin)"
    return Tost(n, mean_before, mean_after, mean_d, low, high, margin, p_value, equivalent, reason)


# ---------------------------------------------------------------------------------------------
# Results folders


def read_runs(path: Path, metrics: list[str]) -> dict[tuple[str, int, int], dict[str, str]]:
    """runs.csv keyed by (estimator, particles, seed); every metric must be a column."""
    if not path.is_file():
        raise InputError(f"missing: {path}")
    rows: dict[tuple[str, int, int], dict[str, str]] = {}
    with path.open(encoding="utf-8", newline="") as stream:
        reader = csv.DictReader(stream)
        for key in ("estimator", "particles", "seed", *metrics):
            if reader.fieldnames is None or key not in reader.fieldnames:
                raise InputError(f"{path}: no column '{key}'")
        for line, row in enumerate(reader, start=2):
            try:
                key = (row["estimator"], int(row["particles"]), int(row["seed"]))
            except (TypeError, ValueError):
                raise InputError(f"{path} line {line}: particles or seed is not an integer")
            if key in rows:
                raise InputError(f"{path} line {line}: run {key} appears twice")
            rows[key] = row
    return rows


def value_of(row: dict[str, str], metric: str, path: Path) -> float | None:
    """The metric of a run as a float; None when empty or not finite."""
    text = row.get(metric)
    if text is None or text == "":
        return None
    try:
        value = float(text)
    except ValueError:
        raise InputError(f"{path}: {metric} = '{text}' is not a number")
    return value if math.isfinite(value) else None


def folders_of(root: Path) -> list[Path]:
    """The results folders of a root: itself, or every folder of its sweep.json."""
    sweep = root / "sweep.json"
    if not sweep.is_file():
        return [Path(".")]
    try:
        return [Path(f) for f in json.loads(sweep.read_text(encoding="utf-8"))["folders"]]
    except (ValueError, KeyError, TypeError) as error:
        raise InputError(f"{sweep}: no list 'folders' ({error})")


@dataclass
class Line:
    """One printed result."""

    folder: str
    estimator: str
    particles: int
    metric: str
    unpaired: int
    tost: Tost


def compare_folder(before_dir: Path, after_dir: Path, metrics: list[str], name_map: dict[str, str],
                   margin: float, alpha: float, min_seeds: int) -> list[Line]:
    """Every (group, metric) line of one pair of results folders."""
    before_path, after_path = before_dir / "runs.csv", after_dir / "runs.csv"
    before, after = read_runs(before_path, metrics), read_runs(after_path, metrics)
    groups = sorted({(e, n) for (e, n, _) in before})
    lines = []
    for estimator, particles in groups:
        after_name = name_map.get(estimator, estimator)
        seeds = sorted(s for (e, n, s) in before if (e, n) == (estimator, particles))
        after_seeds = {s for (e, n, s) in after if (e, n) == (after_name, particles)}
        missing_runs = len(set(seeds) ^ after_seeds)
        for metric in metrics:
            xs, ys, unpaired = [], [], missing_runs
            for seed in seeds:
                if seed not in after_seeds:
                    continue
                x = value_of(before[(estimator, particles, seed)], metric, before_path)
                y = value_of(after[(after_name, particles, seed)], metric, after_path)
                if x is None and y is None:
                    continue
                if x is None or y is None:
                    unpaired += 1
                    continue
                xs.append(x)
                ys.append(y)
            label = estimator if after_name == estimator else f"{estimator}={after_name}"
            lines.append(Line(str(before_dir), label, particles, metric, unpaired,
                              paired_tost(xs, ys, margin, alpha, min_seeds)))
    return lines


def format_number(x: float) -> str:
    return "" if math.isnan(x) else f"{x:.6g}"


HEADER = ("estimator", "N", "metric", "n", "unpaired", "mean_before", "mean_after",
          "mean_diff", "ci90_low", "ci90_high", "ci90_low_pct", "ci90_high_pct", "margin", "p_tost", "verdict")


def percent_of(x: float, reference: float) -> float:
    """x as a percentage of |reference| (NaN when undefined)."""
    if math.isnan(x) or math.isnan(reference) or reference == 0.0:
        return float("nan")
    return 100.0 * x / abs(reference)


def cells(line: Line) -> list[str]:
    t = line.tost
    low_pct, high_pct = percent_of(t.ci_low, t.mean_before), percent_of(t.ci_high, t.mean_before)
    return [line.estimator, str(line.particles), line.metric, str(t.n), str(line.unpaired),
            format_number(t.mean_before), format_number(t.mean_after),
            format_number(t.mean_difference), format_number(t.ci_low), format_number(t.ci_high),
            format_number(low_pct), format_number(high_pct), format_number(t.margin), format_number(t.p_value), t.reason]


def print_table(lines: list[Line], folder_label: str) -> None:
    rows = [list(HEADER)] + [cells(line) for line in lines]
    widths = [max(len(row[i]) for row in rows) for i in range(len(HEADER))]
    if folder_label:
        print(f"# {folder_label}")
    for row in rows:
        print("  ".join(cell.ljust(width) for cell, width in zip(row, widths)).rstrip())


def parse_arguments(argv: list[str]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(
        prog="equivalence.py", description=__doc__.split("\n\n")[0],
        epilog="validation/README.md, 'Equivalence of two builds', says the rest.")
    parser.add_argument("before", type=Path, help="results folder (or sweep root) of the old code")
    parser.add_argument("after", type=Path, help="results folder (or sweep root) of the new code")
    parser.add_argument("--metric", default=",".join(DEFAULT_METRICS),
                        help="comma list of runs.csv columns (default: pos_rmse_m,gospa_m)")
    parser.add_argument("--margin", type=float, default=0.05,
                        help="equivalence margin as a fraction of BEFORE's mean (default 0.05)")
    parser.add_argument("--alpha", type=float, default=0.05, help="test level (default 0.05)")
    parser.add_argument("--min-seeds", type=int, default=2,
                        help="fewer paired seeds than this is 'not shown' (default 2)")
    parser.add_argument("--estimator-map", action="append", default=[], metavar="BEFORE=AFTER",
                        help="pair BEFORE's estimator with another name in AFTER (repeatable)")
    parser.add_argument("--csv", type=Path, help="also write the lines to this CSV file")
    args = parser.parse_args(argv)
    if not 0.0 < args.margin:
        parser.error("--margin must be > 0")
    if not 0.0 < args.alpha < 0.5:
        parser.error("--alpha must be in (0, 0.5)")
    args.metrics = [m for m in args.metric.split(",") if m]
    if not args.metrics:
        parser.error("--metric is empty")
    args.name_map = {}
    for item in args.estimator_map:
        if item.count("=") != 1 or item.startswith("=") or item.endswith("="):
            parser.error(f"--estimator-map '{item}' is not BEFORE=AFTER")
        old, new = item.split("=")
        args.name_map[old] = new
    return args


def main(argv: list[str]) -> int:
    try:
        args = parse_arguments(argv)
    except SystemExit as stop:
        return int(stop.code or 0) and 2
    try:
        all_lines: list[Line] = []
        folders = folders_of(args.before)
        for folder in folders:
            lines = compare_folder(args.before / folder, args.after / folder, args.metrics,
                                   args.name_map, args.margin, args.alpha, args.min_seeds)
            print_table(lines, "" if len(folders) == 1 else str(folder))
            all_lines += lines
    except InputError as error:
        print(f"equivalence: {error}", file=sys.stderr)
        return 2
    tested = [line for line in all_lines if line.tost.reason != "no paired values"]
    shown = sum(line.tost.equivalent for line in tested)
    print(f"equivalence (TOST, alpha = {args.alpha}, margin = +-{100 * args.margin:g} % of "
          f"BEFORE's mean, 90 % CI): {shown} of {len(tested)} shown")
    if args.csv:
        with args.csv.open("w", encoding="utf-8", newline="") as stream:
            writer = csv.writer(stream)
            writer.writerow(("folder",) + HEADER)
            for line in all_lines:
                writer.writerow([line.folder] + cells(line))
    return 0 if tested and shown == len(tested) else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
