#!/usr/bin/env python3
"""Compares two phdslam results folders (or sweep roots) in every non-timing column.

  ci/compare_results.py EXPECTED ACTUAL

For a results folder, runs.csv and summary.csv are compared; for a sweep root (sweep.json),
sweep.csv and the runs.csv and summary.csv of every sweep folder. Timing columns (named ms or
ms_*, validation/README.md "Timing columns") are dropped first; every other cell must be equal
as text. Prints one line per file and exits 0 when all are equal, 1 otherwise (with the first
differing line), 2 for a missing file.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path


def without_timing(text: str) -> list[str]:
    """The CSV lines without the timing columns."""
    lines = [line for line in text.splitlines() if line]
    if not lines:
        return []
    header = lines[0].split(",")
    keep = [i for i, name in enumerate(header) if not (name == "ms" or name.startswith("ms_"))]
    return [",".join(cells[i] for i in keep) for cells in (line.split(",") for line in lines)]


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


def main(argv: list[str]) -> int:
    if len(argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    expected, actual = Path(argv[1]), Path(argv[2])
    status = 0
    for relative in files_to_compare(expected):
        a, b = expected / relative, actual / relative
        for path in (a, b):
            if not path.is_file():
                print(f"missing: {path}", file=sys.stderr)
                return 2
        la = without_timing(a.read_text(encoding="utf-8"))
        lb = without_timing(b.read_text(encoding="utf-8"))
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
