"""The table of a sweep root: sweep.json (swept parameters and their values) with sweep.csv
(one leading column per swept parameter, then the columns of summary.csv)."""

from __future__ import annotations

import csv
import json
import math
from dataclasses import dataclass
from pathlib import Path

from .csv_table import ResultsFormatError, parse_number

SWEEP_JSON = "sweep.json"
SWEEP_CSV = "sweep.csv"


@dataclass(frozen=True)
class SweepRow:
    """One summary.csv row of one sweep point."""

    point: tuple[str, ...]  # the swept values as written in sweep.csv
    estimator: str
    particles: int
    values: dict[str, float]  # the numeric summary columns


@dataclass(frozen=True)
class SweepTable:
    """Every row of a sweep root, with the parameters in sweep order."""

    root: Path
    parameters: tuple[str, ...]
    values: tuple[tuple[str, ...], ...]  # per parameter, its values in sweep order (as text)
    rows: tuple[SweepRow, ...]


def value_text(value: object) -> str:
    """A sweep.json value as sweep.csv writes it (numbers as %.10g, true/false, names)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float)):
        return f"{float(value):.10g}"
    return str(value)


def _parameters(root: Path) -> tuple[tuple[str, ...], tuple[tuple[str, ...], ...]]:
    path = root / SWEEP_JSON
    try:
        spec = json.loads(path.read_text(encoding="utf-8"))
        dims = spec.get("parameters") or [{"parameter": spec["parameter"],
                                           "values": spec["values"]}]
        names = tuple(str(d["parameter"]) for d in dims)
        values = tuple(tuple(value_text(v) for v in d["values"]) for d in dims)
    except (OSError, ValueError, KeyError, TypeError, AttributeError) as error:
        raise ResultsFormatError(f"{path}: expected 'parameters' (or 'parameter' and 'values'): "
                                 f"{error}") from error
    return names, values


def read_sweep_table(root: Path) -> SweepTable | None:
    """The sweep of ``root``, or None when it has no sweep.json or no sweep.csv."""
    if not (root / SWEEP_JSON).is_file() or not (root / SWEEP_CSV).is_file():
        return None
    names, values = _parameters(root)
    path = root / SWEEP_CSV
    with path.open(encoding="utf-8", newline="") as handle:
        lines = [cells for cells in csv.reader(handle) if cells]
    if not lines:
        raise ResultsFormatError(f"{path}: empty file (expected a header line)")
    k = len(names)
    header = lines[0]
    if tuple(header[:k]) != names:
        raise ResultsFormatError(f"{path}: the leading columns {header[:k]} are not the swept "
                                 f"parameters {list(names)} of {SWEEP_JSON}")
    summary = header[k:]
    rows = []
    for number, cells in enumerate(lines[1:], start=2):
        if len(cells) != len(header):
            raise ResultsFormatError(f"{path}, line {number}: {len(cells)} cells, but the header "
                                     f"has {len(header)} columns")
        record = dict(zip(summary, cells[k:]))
        numbers = {}
        for name, cell in record.items():
            try:
                numbers[name] = parse_number(cell)
            except ValueError:
                numbers[name] = math.nan
        try:
            rows.append(SweepRow(tuple(cells[:k]), record["estimator"],
                                 int(float(record["particles"])), numbers))
        except (KeyError, ValueError) as error:
            raise ResultsFormatError(f"{path}, line {number}: no estimator/particles ({error})") \
                from error
    return SweepTable(root, names, values, tuple(rows))


def sweep_root_of(folder: Path) -> Path | None:
    """The sweep root whose sweep.json lists ``folder`` as one of its points, or None."""
    parent = folder.parent
    path = parent / SWEEP_JSON
    if not path.is_file():
        return None
    try:
        folders = json.loads(path.read_text(encoding="utf-8")).get("folders") or []
    except (OSError, ValueError, AttributeError):
        return None
    return parent if folder.name in folders else None


def sweep_point_of(folder: Path) -> list[tuple[str, str]]:
    """The (parameter, value) pairs of the sweep point ``folder`` holds, or [] when it is not a
    point of a sweep root."""
    root = sweep_root_of(folder)
    if root is None:
        return []
    try:
        names, values = _parameters(root)
        folders = json.loads((root / SWEEP_JSON).read_text(encoding="utf-8"))["folders"]
    except (ResultsFormatError, OSError, ValueError, KeyError, TypeError):
        return []
    points: list[tuple[str, ...]] = [()]
    for options in values:
        points = [p + (v,) for p in points for v in options]
    index = folders.index(folder.name)
    return list(zip(names, points[index])) if index < len(points) else []
