"""Reading the CSV files of a results folder, with errors that name the file and column.

Every results CSV has a header line; empty cells mean "not available" and are read as NaN.
Lines that are blank or start with ``#`` are skipped (the map files allow comments).
"""

from __future__ import annotations

import csv
import io
import math
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Iterable, Sequence

import numpy as np

from .results_format_error import ResultsFormatError  # noqa: F401  (re-exported)


@dataclass
class CsvTable:
    """A CSV file held column by column: numeric columns as float arrays, the others as strings."""

    path: Path
    header: list[str]
    numeric: dict[str, np.ndarray] = field(default_factory=dict)
    text: dict[str, list[str]] = field(default_factory=dict)
    rows: int = 0
    line_numbers: list[int] = field(default_factory=list)  # the file line of each row (1-based)

    def has(self, column: str) -> bool:
        """True when the file's header names ``column``."""
        return column in self.header

    def num(self, column: str) -> np.ndarray:
        """The numeric column ``column`` (NaN for empty cells)."""
        if column not in self.numeric:
            raise ResultsFormatError(f"{self.path}: column '{column}' is missing or not numeric")
        return self.numeric[column]

    def str(self, column: str) -> list[str]:
        """The text column ``column``."""
        if column not in self.text:
            raise ResultsFormatError(f"{self.path}: column '{column}' is missing or not text")
        return self.text[column]

    def line(self, row: int) -> int:
        """The 1-based file line of the 0-based data row ``row`` (comments and blanks skipped)."""
        return self.line_numbers[row] if row < len(self.line_numbers) else row + 2

    def records(self) -> list[dict[str, object]]:
        """One dict per row, text and numeric columns together."""
        out: list[dict[str, object]] = []
        for i in range(self.rows):
            row: dict[str, object] = {}
            for name in self.header:
                if name in self.numeric:
                    row[name] = float(self.numeric[name][i])
                elif name in self.text:
                    row[name] = self.text[name][i]
            out.append(row)
        return out


#: Largest magnitude of a number in a results file. Beyond it (or infinite) a value is refused
#: with its file, line and column: the statistics of such a column (squares, sums) would
#: overflow, and no metric of a run reaches it (phdslam writes empty cells for non-finite values),
#: except the consistency statistics below.
MAX_MAGNITUDE = 1e100

#: Columns of consistency statistics (NEES, NIS and their bands). A filter whose particles
#: collapse onto a few poses (no resampling) reports a near-singular pose covariance, and its NEES
#: reaches 1e300 while finite; phdslam writes it as computed. These statistics are never negative,
#: so these columns may hold any finite number down to -MAX_MAGNITUDE; below it, or infinite, a
#: value is refused as in every column.
UNBOUNDED_COLUMN = re.compile(r"(?:^|_)(?:nees|nis)(?:_|$)")


def _check_magnitudes(table: CsvTable, allow_infinite: bool) -> None:
    """Raises ResultsFormatError at the first huge (or, unless allowed, infinite) number."""
    for name, values in table.numeric.items():
        unbounded = UNBOUNDED_COLUMN.search(name) is not None
        with np.errstate(invalid="ignore"):
            huge = (np.isinf(values) | (values < -MAX_MAGNITUDE)) if unbounded else \
                np.abs(values) > MAX_MAGNITUDE
            bad = np.flatnonzero(huge & np.isfinite(values) if allow_infinite else huge)
        if bad.size:
            row = int(bad[0])
            limit = f"infinite or below -{MAX_MAGNITUDE:.0e}" if unbounded else \
                f"infinite or beyond +-{MAX_MAGNITUDE:.0e}"
            raise ResultsFormatError(
                f"{table.path}, line {table.line(row)}, column '{name}': {values[row]:.6g} is "
                f"{limit} (not a plausible metric); {bad.size} such value(s) in the column")


_EMPTY_CELL = re.compile(r"(?:(?<=,)|^)(?=,|$)", re.MULTILINE)


def parse_number(cell: str) -> float:
    """A cell as a float: empty means NaN; anything else that is not a number raises ValueError."""
    stripped = cell.strip()
    if stripped == "":
        return math.nan
    return float(stripped)


def _content_lines(path: Path) -> list[tuple[int, str]]:
    """The (1-based line number, text) of every line that is neither blank nor a comment."""
    try:
        # utf-8-sig: a byte-order mark (written by some editors) is dropped, not read as part of
        # the first column's name.
        raw = path.read_text(encoding="utf-8-sig")
    except FileNotFoundError as error:
        raise ResultsFormatError(f"{path}: file not found") from error
    except (OSError, UnicodeDecodeError) as error:
        raise ResultsFormatError(f"{path}: cannot read: {error}") from error
    lines = []
    for number, line in enumerate(raw.splitlines(), start=1):
        content = line.strip()
        if content and not content.startswith("#"):
            lines.append((number, content))
    return lines


def _fast_numeric_block(lines: Sequence[str], columns: int) -> np.ndarray | None:
    """All-numeric data lines parsed by numpy, or None when any cell needs a closer look."""
    if not lines:
        return np.zeros((0, columns))
    text = _EMPTY_CELL.sub("nan", "\n".join(lines))
    try:
        block = np.loadtxt(io.StringIO(text), delimiter=",", ndmin=2, dtype=float)
    except ValueError:
        return None
    if block.shape[1] != columns:
        return None
    return block


def read_csv(
    path: Path | str,
    required: Iterable[str] = (),
    text_columns: Iterable[str] = (),
    finite_only: bool = False,
    allow_infinite: bool = False,
) -> CsvTable:
    """Reads ``path``; every column not in ``text_columns`` must hold numbers or be empty.

    With ``finite_only`` a cell that spells a non-finite number ('nan', 'inf', ...) is an error
    too: phdslam writes an empty cell for "not available", so such a cell was written by hand and
    would silently change the statistics computed from the column.

    Raises ResultsFormatError naming the file (and the line and column) when the file is missing,
    has no header, lacks a column of ``required``, has a row of the wrong length or a cell that is
    not a number, or a number beyond +-MAX_MAGNITUDE or (without ``allow_infinite``, for
    files whose own validation names non-finite cells) infinite.
    """
    path = Path(path)
    lines = _content_lines(path)
    if not lines:
        raise ResultsFormatError(f"{path}: empty file (expected a header line)")
    header = [name.strip() for name in next(csv.reader([lines[0][1]]))]
    for name in required:
        if name not in header:
            raise ResultsFormatError(
                f"{path}: required column '{name}' is missing (header: {','.join(header)})"
            )
    text_set = set(text_columns)
    numbers = [number for number, _ in lines[1:]]
    data = [content for _, content in lines[1:]]
    table = CsvTable(path=path, header=header, rows=len(data), line_numbers=numbers)
    numeric_names = [h for h in header if h not in text_set]

    if not finite_only and not text_set.intersection(header):
        block = _fast_numeric_block(data, len(header))
        if block is not None:
            for j, name in enumerate(header):
                table.numeric[name] = block[:, j].copy()
            _check_magnitudes(table, allow_infinite)
            return table

    columns: dict[str, list] = {name: [] for name in header}
    for line_number, cells in zip(numbers, csv.reader(data)):
        if len(cells) != len(header):
            raise ResultsFormatError(
                f"{path}, line {line_number}: {len(cells)} cells, but the header has "
                f"{len(header)} columns"
            )
        for name, cell in zip(header, cells):
            if name in text_set:
                columns[name].append(cell.strip())
                continue
            try:
                value = parse_number(cell)
            except ValueError:
                raise ResultsFormatError(
                    f"{path}, line {line_number}, column '{name}': '{cell}' is not a number"
                ) from None
            if finite_only and cell.strip() and not math.isfinite(value):
                raise ResultsFormatError(
                    f"{path}, line {line_number}, column '{name}': '{cell}' is not a finite "
                    f"number (phdslam writes an empty cell for a value that is not available)")
            columns[name].append(value)
    for name in header:
        if name in text_set:
            table.text[name] = columns[name]
    for name in numeric_names:
        table.numeric[name] = np.asarray(columns[name], dtype=float)
    _check_magnitudes(table, allow_infinite)
    return table
