#!/usr/bin/env python3
"""Compares two phdslam results folders (or sweep roots) in every non-timing column.

  ci/compare_results.py EXPECTED ACTUAL

For a results folder, runs.csv and summary.csv are compared; for a sweep root (sweep.json),
sweep.csv and the runs.csv and summary.csv of every sweep folder. Timing columns (named ms or
ms_*, validation/README.md "Timing columns") are dropped first; every other cell must be equal
as text. Columns that only ACTUAL has (new columns) are reported as added and not compared;
a column of EXPECTED missing from ACTUAL is a difference. The steps.csv of every run folder under
runs/ of EXPECTED is compared the same way. Prints one line per file and exits 0 when all are
equal, 1 otherwise (with the first differing line), 2 for a missing file.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path


def is_timing(name: str) -> bool:
    return name == "ms" or name.startswith("ms_")


def header_of(text: str) -> list[str]:
    lines = [line for line in text.splitlines() if line]
    return lines[0].split(",") if lines else []


def columns(text: str, names: list[str]) -> list[str]:
    """The CSV lines restricted to `names` (in that order); a missing name gives a marker."""
    lines = [line for line in text.splitlines() if line]
    if not lines:
        return []
    header = lines[0].split(",")
    index = {name: i for i, name in enumerate(header)}
    rows = [line.split(",") for line in lines]
    return [",".join(cells[index[n]] if n in index else "<missing>" for n in names) for cells in rows]


def without_timing(text: str) -> list[str]:
    """The CSV lines without the timing columns."""
    names = [name for name in header_of(text) if not is_timing(name)]
    return columns(text, names)


def files_to_compare(root: Path) -> list[Path]:
    """Relative paths of the CSV files that must agree."""
    sweep = root / "sweep.json"
    if not sweep.is_file():
        return [Path("runs.csv"), Path("summary.csv")]
    folders = json.loads(sweep.read_text(encoding="utf-8"))["folders"]
    files = [Path("sweep.csv")]
    for folder in folders:
        files += [Path(folder) / "runs.csv", Path(folder) / "summary.csv"]
    return files


def steps_files(root: Path) -> list[Path]:
    """Relative paths of every run's steps.csv under runs/ (a results folder only)."""
    runs = root / "runs"
    if not runs.is_dir():
        return []
    return sorted(p.relative_to(root) for p in runs.glob("*/seed-*/steps.csv"))


def main(argv: list[str]) -> int:
    if len(argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    expected, actual = Path(argv[1]), Path(argv[2])
    status = 0
    for relative in files_to_compare(expected) + steps_files(expected):
        a, b = expected / relative, actual / relative
        for path in (a, b):
            if not path.is_file():
                print(f"missing: {path}", file=sys.stderr)
                return 2
        ta, tb = a.read_text(encoding="utf-8"), b.read_text(encoding="utf-8")
        names = [name for name in header_of(ta) if not is_timing(name)]
        added = [name for name in header_of(tb) if name not in header_of(ta)]
        if added:
            print(f"added columns in {relative}: {' '.join(added)}")
        la = columns(ta, names)
        lb = columns(tb, names)
        if la == lb:
            print(f"identical (non-timing columns): {relative} ({len(la) - 1} rows)")
            continue
        status = 1
        print(f"DIFFERENT: {relative}")
        for index, (x, y) in enumerate(zip(la, lb)):
            if x != y:
                print(f"  line {index + 1}:\n    {a}: {x}\n    {b}: {y}")
                break
        else:
            print(f"  {len(la)} vs {len(lb)} lines")
    return status


if __name__ == "__main__":
    sys.exit(main(sys.argv))
