#!/usr/bin/env python3
"""Paired equivalence test (TOST) of two phdslam results folders run on the same seeds.

  ci/equivalence.py BEFORE AFTER [--column NAME]... [--metric pos_rmse_m,gospa_m] [--margin 0.05]
                    [--alpha 0.05] [--min-seeds 2] [--seeds 1-200]
                    [--estimator-map BEFORE_NAME=AFTER_NAME]... [--csv FILE]

Runs are paired by (scenario, estimator, particles, seed): the scenario is the runs.csv column
`scenario` when there is one, else config.json's scenario, and must be the same in both folders
(name and options, the data folder's path aside). For a sweep root (sweep.json) every sweep
folder is compared in turn. For every (estimator, particles) group of BEFORE (with
--estimator-map: only the mapped estimators, paired with the AFTER name) and every column tested
(position RMSE and GOSPA, plus each --column), with d = AFTER - BEFORE over the n paired seeds:

  margin    = --margin x |mean of BEFORE|              (default 5 %)
  CI        = mean(d) +- t(1 - alpha, n - 1) x sd(d) / sqrt(n)   (the 1 - 2 alpha = 90 % interval)
  TOST      p = max(p_lower, p_upper) of the one-sided tests of mean(d) > -margin and
              mean(d) < +margin; EQUIVALENT when p < alpha, i.e. the CI lies strictly inside
              (-margin, +margin); NOT SHOWN otherwise.
  p_ttest   the two-sided paired t-test of mean(d) = 0 (a difference, not equivalence).
  seeds_needed  the fewest seeds with which differences of this spread would give an interval
              inside the margin if the true mean difference were 0 (a lower bound for planning).

When every difference is the same value (sd = 0, e.g. identical runs) the interval is that value.

Errors (exit 2, naming the file, line, group or seeds): a run of a tested group in one folder only
(restrict the seeds with --seeds), a value missing in one run of a pair, a value that is not a
finite number, fewer than --min-seeds (never fewer than 2) pairs, folders of different scenarios,
a missing or malformed file (a results folder without config.json among them: the scenario check
needs it; a byte-order mark is accepted), a --csv file whose folder does not exist or that cannot
be written. A column empty in every run of both folders (e.g. GOSPA without a
true map) is reported as not tested. Exit 0 when every tested group is EQUIVALENT, 1 when some
is NOT SHOWN. The Student t distribution is computed here (no SciPy needed).
"""

from __future__ import annotations

import argparse
import csv
import io
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


def normal_quantile(p: float) -> float:
    """The z with P(Z <= z) = p (0 < p < 1) for the standard normal, by bisection."""
    if not 0.0 < p < 1.0:
        raise ValueError(f"quantile probability {p} outside (0, 1)")
    low, high = -40.0, 40.0
    for _ in range(200):
        mid = 0.5 * (low + high)
        if 0.5 * math.erfc(-mid / math.sqrt(2.0)) < p:
            low = mid
        else:
            high = mid
    return 0.5 * (low + high)


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
    """The paired TOST of one group and column."""

    n: int
    mean_before: float
    mean_after: float
    mean_difference: float
    sd_difference: float
    ci_low: float
    ci_high: float
    margin: float
    p_value: float
    p_difference: float  # two-sided paired t-test of mean(d) = 0
    equivalent: bool


def paired_tost(before: list[float], after: list[float], margin_fraction: float,
                alpha: float) -> Tost:
    """TOST of mean(after - before) within +-margin_fraction x |mean(before)| (n >= 2 pairs)."""
    n = len(before)
    if n < 2 or len(after) != n:
        raise ValueError(f"paired_tost needs two lists of the same length >= 2 ({n}, {len(after)})")
    mean_before = sum(before) / n
    mean_after = sum(after) / n
    differences = [a - b for a, b in zip(after, before)]
    mean_d = sum(differences) / n
    margin = margin_fraction * abs(mean_before)
    sd = math.sqrt(sum((d - mean_d) ** 2 for d in differences) / (n - 1))
    se = sd / math.sqrt(n)
    df = n - 1
    if se == 0.0:
        low = high = mean_d
        p_value = 0.0 if -margin < mean_d < margin else 1.0
        p_difference = 1.0 if mean_d == 0.0 else 0.0
    else:
        half = t_quantile(1.0 - alpha, df) * se
        low, high = mean_d - half, mean_d + half
        p_lower = 1.0 - t_cdf((mean_d + margin) / se, df)  # H0: mean_d <= -margin
        p_upper = t_cdf((mean_d - margin) / se, df)  # H0: mean_d >= +margin
        p_value = max(p_lower, p_upper)
        p_difference = 2.0 * t_cdf(-abs(mean_d) / se, df)
    return Tost(n, mean_before, mean_after, mean_d, sd, low, high, margin, p_value,
                p_difference, p_value < alpha)


def seeds_needed(sd: float, margin: float, alpha: float) -> float:
    """Fewest n >= 2 with t(1 - alpha, n - 1) sd / sqrt(n) < margin (inf when margin is 0)."""
    if margin <= 0.0:
        return math.inf
    if sd == 0.0:
        return 2
    # t(1 - alpha, n - 1) > z(1 - alpha): the normal quantile's n is a lower bound to start from.
    z = normal_quantile(1.0 - alpha)
    n = max(2, math.floor((z * sd / margin) ** 2))
    if n > 10**9:
        return math.inf
    while t_quantile(1.0 - alpha, n - 1) * sd / math.sqrt(n) >= margin:
        n += 1
    return n


# ---------------------------------------------------------------------------------------------
# Results folders

RunKey = tuple[str, int, int]  # (estimator, particles, seed)


@dataclass
class Runs:
    """One runs.csv: rows keyed by (estimator, particles, seed), their line numbers, scenario."""

    path: Path
    rows: dict[RunKey, dict[str, str]]
    lines: dict[RunKey, int]
    scenario: str


def scenario_of(folder: Path) -> tuple[str, dict]:
    """config.json's scenario name and options (without the data folder's path). A folder without
    config.json is an error: without it the scenario check would be skipped silently."""
    config = folder / "config.json"
    if not config.is_file():
        raise InputError(f"missing: {config} (needed to check both folders ran the same "
                         "scenario)")
    try:
        scenario = json.loads(read_text(config))["scenario"]
        options = dict(scenario.get("options", {}))
        name = str(scenario["name"])
    except (ValueError, KeyError, TypeError, AttributeError) as error:
        raise InputError(f"{config}: no scenario name ({error})")
    options.pop("data_dir", None)
    return name, options


def read_text(path: Path) -> str:
    """A text file's content (a byte-order mark dropped); InputError naming it when unreadable."""
    try:
        return path.read_text(encoding="utf-8-sig")
    except (OSError, UnicodeDecodeError) as error:
        raise InputError(f"{path}: cannot be read ({error})")


def read_runs(folder: Path, columns: list[str]) -> Runs:
    """runs.csv of a results folder; every tested column must be one of its columns."""
    path = folder / "runs.csv"
    if not path.is_file():
        raise InputError(f"missing: {path}")
    default_scenario, _ = scenario_of(folder)
    rows: dict[RunKey, dict[str, str]] = {}
    lines: dict[RunKey, int] = {}
    scenarios = set()
    with io.StringIO(read_text(path), newline="") as stream:
        reader = csv.DictReader(stream)
        for key in ("estimator", "particles", "seed", *columns):
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
            lines[key] = line
            scenarios.add(row.get("scenario") or default_scenario)
    if len(scenarios) > 1:
        raise InputError(f"{path}: runs of several scenarios ({', '.join(sorted(scenarios))})")
    return Runs(path, rows, lines, scenarios.pop() if scenarios else default_scenario)


def check_same_scenario(before_dir: Path, after_dir: Path, before: Runs, after: Runs) -> None:
    """Both folders must hold runs of the same scenario with the same options."""
    if before.scenario and after.scenario and before.scenario != after.scenario:
        raise InputError(f"scenarios differ: {before.path} has '{before.scenario}', "
                         f"{after.path} has '{after.scenario}'")
    _, before_options = scenario_of(before_dir)
    _, after_options = scenario_of(after_dir)
    if before_options and after_options:
        for key in sorted(set(before_options) | set(after_options)):
            if before_options.get(key) != after_options.get(key):
                raise InputError(f"scenario option '{key}' differs: {before_dir / 'config.json'} "
                                 f"has {before_options.get(key)!r}, {after_dir / 'config.json'} "
                                 f"has {after_options.get(key)!r}")


def value_of(runs: Runs, key: RunKey, column: str) -> float | None:
    """A run's value as a float; None when the cell is empty; an error when not finite."""
    text = runs.rows[key].get(column)
    if text is None or text == "":
        return None
    where = f"{runs.path} line {runs.lines[key]}, column {column}"
    try:
        value = float(text)
    except ValueError:
        raise InputError(f"{where}: '{text}' is not a number")
    if not math.isfinite(value):
        raise InputError(f"{where}: '{text}' is not a finite number")
    return value


def folders_of(root: Path) -> list[Path]:
    """The results folders of a root: itself, or every folder of its sweep.json."""
    sweep = root / "sweep.json"
    if not sweep.is_file():
        return [Path(".")]
    try:
        folders = json.loads(read_text(sweep))["folders"]
        if not isinstance(folders, list) or not all(isinstance(f, str) for f in folders):
            raise TypeError("'folders' is not a list of names")
        return [Path(f) for f in folders]
    except (ValueError, KeyError, TypeError) as error:
        raise InputError(f"{sweep}: no list 'folders' ({error})")


def seed_list(seeds: list[int]) -> str:
    """Seeds as a short text: the first ten, then how many more."""
    shown = ", ".join(str(s) for s in seeds[:10])
    return shown + (f" and {len(seeds) - 10} more" if len(seeds) > 10 else "")


@dataclass
class Line:
    """One printed result; tost is None when the column is empty in every run (not tested)."""

    folder: str
    scenario: str
    estimator: str
    particles: int
    column: str
    tost: Tost | None
    needed: float


@dataclass
class Options:
    """What to compare and how."""

    columns: list[str]
    name_map: dict[str, str]
    seeds: set[int] | None
    margin: float
    alpha: float
    min_seeds: int


def paired_seeds(before: Runs, after: Runs, estimator: str, after_name: str, particles: int,
                 seeds: set[int] | None) -> list[int]:
    """The seeds of one group; an error when a run has no partner in the other folder."""
    def group(runs: Runs, name: str) -> set[int]:
        return {s for (e, n, s) in runs.rows if (e, n) == (name, particles)
                and (seeds is None or s in seeds)}

    in_before, in_after = group(before, estimator), group(after, after_name)
    for runs, name, missing in ((after, after_name, sorted(in_before - in_after)),
                                (before, estimator, sorted(in_after - in_before))):
        if missing:
            raise InputError(f"{runs.path} has no run of {name} N={particles} for seed(s) "
                             f"{seed_list(missing)} that the other folder has (unpaired runs; "
                             f"--seeds restricts the comparison)")
    return sorted(in_before)


def compare_group(before: Runs, after: Runs, estimator: str, particles: int, seeds: list[int],
                  options: Options, folder: str) -> list[Line]:
    """Every column's line of one (estimator, particles) group."""
    after_name = options.name_map.get(estimator, estimator)
    label = estimator if after_name == estimator else f"{estimator}={after_name}"
    lines = []
    for column in options.columns:
        xs, ys = [], []
        for seed in seeds:
            x = value_of(before, (estimator, particles, seed), column)
            y = value_of(after, (after_name, particles, seed), column)
            if x is None and y is None:
                continue
            if x is None or y is None:
                runs, name = (before, estimator) if x is None else (after, after_name)
                raise InputError(f"{runs.path} line {runs.lines[(name, particles, seed)]}: "
                                 f"{column} is empty for {name} N={particles} seed {seed} but "
                                 f"not in the other folder's run")
            xs.append(x)
            ys.append(y)
        if not xs:
            lines.append(Line(folder, before.scenario, label, particles, column, None, math.nan))
            continue
        if len(xs) < max(2, options.min_seeds):
            raise InputError(f"{label} N={particles} {column}: {len(xs)} paired seed(s), fewer "
                             f"than {max(2, options.min_seeds)} (--min-seeds)")
        tost = paired_tost(xs, ys, options.margin, options.alpha)
        needed = seeds_needed(tost.sd_difference, tost.margin, options.alpha)
        lines.append(Line(folder, before.scenario, label, particles, column, tost, needed))
    return lines


def compare_folder(before_dir: Path, after_dir: Path, options: Options,
                   folder: str) -> list[Line]:
    """Every (group, column) line of one pair of results folders."""
    before = read_runs(before_dir, options.columns)
    after = read_runs(after_dir, options.columns)
    check_same_scenario(before_dir, after_dir, before, after)
    groups = sorted({(e, n) for (e, n, _) in before.rows
                     if not options.name_map or e in options.name_map})
    if options.name_map:
        for name in options.name_map:
            if not any(e == name for e, _ in groups):
                raise InputError(f"{before.path}: no runs of estimator '{name}' (--estimator-map)")
    else:
        extra = sorted({(e, n) for (e, n, _) in after.rows} - set(groups))
        if extra:
            raise InputError(f"{after.path}: runs of {extra[0][0]} N={extra[0][1]} that "
                             f"{before.path} does not have (unpaired runs)")
    lines = []
    for estimator, particles in groups:
        after_name = options.name_map.get(estimator, estimator)
        seeds = paired_seeds(before, after, estimator, after_name, particles, options.seeds)
        if not seeds:
            continue
        lines += compare_group(before, after, estimator, particles, seeds, options, folder)
    return lines


# ---------------------------------------------------------------------------------------------
# Output


def format_number(x: float) -> str:
    return "" if math.isnan(x) else f"{x:.6g}"


HEADER = ("scenario", "estimator", "N", "column", "n", "mean_before", "mean_after", "mean_diff",
          "diff_pct", "ci90_low", "ci90_high", "ci90_low_pct", "ci90_high_pct", "margin",
          "p_tost", "p_ttest", "seeds_needed", "verdict")


def percent_of(x: float, reference: float) -> float:
    """x as a percentage of |reference| (NaN when undefined)."""
    if math.isnan(x) or math.isnan(reference) or reference == 0.0:
        return float("nan")
    return 100.0 * x / abs(reference)


def verdict(line: Line) -> str:
    if line.tost is None:
        return "NOT TESTED (empty in every run)"
    return "EQUIVALENT" if line.tost.equivalent else "NOT SHOWN"


def cells(line: Line) -> list[str]:
    t = line.tost
    head = [line.scenario, line.estimator, str(line.particles), line.column]
    if t is None:
        return head + [""] * (len(HEADER) - len(head) - 1) + [verdict(line)]
    pct = [percent_of(x, t.mean_before) for x in (t.mean_difference, t.ci_low, t.ci_high)]
    needed = "" if math.isinf(line.needed) else str(int(line.needed))
    return head + [str(t.n)] + [format_number(x) for x in (
        t.mean_before, t.mean_after, t.mean_difference, pct[0], t.ci_low, t.ci_high, pct[1],
        pct[2], t.margin, t.p_value, t.p_difference)] + [needed, verdict(line)]


def print_table(lines: list[Line], folder_label: str) -> None:
    rows = [list(HEADER)] + [cells(line) for line in lines]
    widths = [max(len(row[i]) for row in rows) for i in range(len(HEADER))]
    if folder_label:
        print(f"# {folder_label}")
    for row in rows:
        print("  ".join(cell.ljust(width) for cell, width in zip(row, widths)).rstrip())


# ---------------------------------------------------------------------------------------------
# Command line


def parse_seed_text(text: str) -> set[int]:
    """'1-100' or '1,3,7' or a mix."""
    seeds: set[int] = set()
    for part in text.split(","):
        low, dash, high = part.partition("-")
        try:
            if dash and not high.strip():
                raise ValueError(part)  # "1-": a range without its end
            seeds.update(range(int(low), int(high or low) + 1))
        except ValueError:
            raise ValueError(f"--seeds '{text}': expected a-b or a comma list of seeds")
    if not seeds:
        raise ValueError(f"--seeds '{text}' is empty")
    return seeds


def parse_arguments(argv: list[str]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(
        prog="equivalence.py", description=__doc__.split("\n\n")[0],
        epilog="validation/README.md, 'Equivalence of two builds', says the rest.")
    parser.add_argument("before", type=Path, help="results folder (or sweep root) of the old code")
    parser.add_argument("after", type=Path, help="results folder (or sweep root) of the new code")
    parser.add_argument("--metric", default=",".join(DEFAULT_METRICS),
                        help="comma list of the runs.csv columns tested (default: "
                             "pos_rmse_m,gospa_m)")
    parser.add_argument("--column", action="append", default=[], metavar="NAME",
                        help="also test this runs.csv column (repeatable)")
    parser.add_argument("--margin", type=float, default=0.05,
                        help="equivalence margin as a fraction of BEFORE's mean (default 0.05)")
    parser.add_argument("--alpha", type=float, default=0.05, help="test level (default 0.05)")
    parser.add_argument("--min-seeds", type=int, default=2,
                        help="fewer paired seeds than this is an error (default 2)")
    parser.add_argument("--seeds", help="compare only these seeds (a-b or a comma list)")
    parser.add_argument("--estimator-map", action="append", default=[], metavar="BEFORE=AFTER",
                        help="test only BEFORE's estimator, paired with another name in AFTER "
                             "(repeatable)")
    parser.add_argument("--csv", type=Path, help="also write the lines to this CSV file")
    args = parser.parse_args(argv)
    if not 0.0 < args.margin:
        parser.error("--margin must be > 0")
    if not 0.0 < args.alpha < 0.5:
        parser.error("--alpha must be in (0, 0.5)")
    if args.csv is not None and not (args.csv.parent if str(args.csv.parent) else Path(".")).is_dir():
        parser.error(f"--csv {args.csv}: the folder {args.csv.parent} does not exist")
    columns = [m for m in args.metric.split(",") if m] + args.column
    args.columns = list(dict.fromkeys(columns))
    if not args.columns:
        parser.error("no column to test (--metric is empty)")
    args.name_map = {}
    for item in args.estimator_map:
        if item.count("=") != 1 or item.startswith("=") or item.endswith("="):
            parser.error(f"--estimator-map '{item}' is not BEFORE=AFTER")
        old, new = item.split("=")
        args.name_map[old] = new
    try:
        args.seed_set = parse_seed_text(args.seeds) if args.seeds else None
    except ValueError as error:
        parser.error(str(error))
    return args


def main(argv: list[str]) -> int:
    try:
        args = parse_arguments(argv)
    except SystemExit as stop:
        return int(stop.code or 0) and 2
    options = Options(args.columns, args.name_map, args.seed_set, args.margin, args.alpha,
                      args.min_seeds)
    try:
        all_lines: list[Line] = []
        folders = folders_of(args.before)
        for folder in folders:
            lines = compare_folder(args.before / folder, args.after / folder, options,
                                   str(folder))
            print_table(lines, "" if len(folders) == 1 else str(folder))
            all_lines += lines
        tested = [line for line in all_lines if line.tost is not None]
        if not tested:
            raise InputError("nothing to test: no paired runs with values "
                             f"({args.before}, {args.after})")
    except (InputError, csv.Error) as error:
        print(f"equivalence: {error}", file=sys.stderr)
        return 2
    shown = sum(line.tost.equivalent for line in tested)
    print(f"equivalence (TOST, alpha = {args.alpha}, margin = +-{100 * args.margin:g} % of "
          f"BEFORE's mean, {100 * (1 - 2 * args.alpha):g} % CI): {shown} of {len(tested)} "
          f"EQUIVALENT")
    if args.csv:
        try:
            write_csv(args.csv, all_lines)
        except OSError as error:
            print(f"equivalence: --csv {args.csv}: cannot be written ({error.strerror})",
                  file=sys.stderr)
            return 2
    return 0 if shown == len(tested) else 1


def write_csv(path: Path, lines: list[Line]) -> None:
    """The table's lines as a CSV file."""
    with path.open("w", encoding="utf-8", newline="") as stream:
        writer = csv.writer(stream)
        writer.writerow(("folder",) + HEADER)
        for line in lines:
            writer.writerow([line.folder] + cells(line))


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
