"""Reads the per-run tables the gates compare: a results folder's runs.csv and a stored baseline
(ci/GATES.md, "The baseline"). Every error names the file, the line and the field."""

from __future__ import annotations

import csv
import hashlib
import io
import json
import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from gates_file import InputError, Suite, expand_seeds

MAX_TABLE_BYTES = 256 << 20
KEY_COLUMNS = ("estimator", "particles", "seed")
BASELINE_FORMAT = "phdslam-gates-baseline 1"


def is_timing(column: str) -> bool:
    """Wall-time columns (validation/README.md "Timing columns"): never compared."""
    return column == "ms" or column.startswith("ms_")


RunKey = tuple[str, int, int]


@dataclass
class RunTable:
    """runs.csv rows keyed by (estimator, particles, seed), cells as text."""

    source: str
    columns: list[str]
    rows: dict[RunKey, dict[str, str]]
    lines: dict[RunKey, int]

    def number(self, key: RunKey, column: str) -> float:
        """The cell as a finite number; an error names the file, line and column otherwise."""
        if column not in self.columns:
            raise InputError(f"{self.source}: no column '{column}' (columns: "
                             f"{', '.join(self.columns[:12])}, ...)")
        text = self.rows[key][column]
        try:
            value = float(text)
        except ValueError:
            value = math.nan
        if not math.isfinite(value):
            raise InputError(f"{self.source}: line {self.lines[key]}, column '{column}' "
                             f"({key[0]} N={key[1]} seed {key[2]}): {text!r} is not a finite number")
        return value


def parse_runs(text: str, source: str) -> RunTable:
    if text.startswith("\ufeff"):
        raise InputError(f"{source}: starts with a byte-order mark (U+FEFF); save it as plain UTF-8")
    reader = csv.reader(io.StringIO(text))
    try:
        header = next(reader)
    except StopIteration:
        raise InputError(f"{source}: empty file (expected a runs.csv header)") from None
    missing = [c for c in KEY_COLUMNS if c not in header]
    if missing:
        raise InputError(f"{source}: line 1: no column {missing[0]!r} (header: {','.join(header[:8])}...)")
    if len(set(header)) != len(header):
        raise InputError(f"{source}: line 1: a column name appears twice")
    rows: dict[RunKey, dict[str, str]] = {}
    lines: dict[RunKey, int] = {}
    for line_no, cells in enumerate(reader, start=2):
        if not cells:
            continue
        if len(cells) != len(header):
            raise InputError(f"{source}: line {line_no}: {len(cells)} cells, the header has "
                             f"{len(header)} (a line cut short?)")
        row = dict(zip(header, cells))
        try:
            key = (row["estimator"], int(row["particles"]), int(row["seed"]))
        except ValueError:
            raise InputError(f"{source}: line {line_no}: particles {row['particles']!r} or seed "
                             f"{row['seed']!r} is not a whole number") from None
        if key in rows:
            raise InputError(f"{source}: line {line_no}: run {key[0]} N={key[1]} seed {key[2]} is "
                             f"listed twice (first on line {lines[key]})")
        rows[key], lines[key] = row, line_no
    return RunTable(source, header, rows, lines)


def read_text(path: Path, what: str) -> str:
    try:
        size = path.stat().st_size
        if size > MAX_TABLE_BYTES:
            raise InputError(f"{path}: {size} bytes, more than the {MAX_TABLE_BYTES} a {what} may have")
        return path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise InputError(f"{path}: missing ({what})") from None
    except (OSError, UnicodeDecodeError) as error:
        raise InputError(f"{path}: cannot read the {what}: {error}") from None


def results_runs_path(results: Path, suite: Suite, single: bool) -> Path:
    """RESULTS/<suite>/runs.csv, or RESULTS/runs.csv for a gates file with one suite."""
    nested = results / suite.name / "runs.csv"
    if nested.is_file() or not single:
        return nested
    return results / "runs.csv"


def check_config(runs_path: Path, suite: Suite) -> None:
    """The results folder was made on the suite's scenario (its config.json, when there is one)."""
    config_path = runs_path.parent / "config.json"
    if not config_path.is_file():
        return
    try:
        config = json.loads(read_text(config_path, "results configuration"))
        name = config["scenario"]["name"]
    except (json.JSONDecodeError, KeyError, TypeError):
        raise InputError(f"{config_path}: field 'scenario.name' missing or not JSON") from None
    if name != suite.scenario:
        raise InputError(f"{config_path}: field 'scenario.name' is '{name}', suite '{suite.name}' "
                         f"gates scenario '{suite.scenario}'")


def select_suite_runs(table: RunTable, suite: Suite, what: str) -> RunTable:
    """The suite's runs of the table; an error names the first missing run."""
    wanted = [(e, n, s) for e, n in suite.groups() for s in suite.seed_list()]
    groups_present = {(k[0], k[1]) for k in table.rows}
    for estimator, particles in suite.groups():
        if (estimator, particles) not in groups_present:
            present = ", ".join(f"{e} N={n}" for e, n in sorted(groups_present)) or "none"
            raise InputError(f"{table.source}: field 'estimator': no run of {estimator} N={particles} "
                             f"in this {what} (it has: {present})")
    for key in wanted:
        if key not in table.rows:
            raise InputError(f"{table.source}: field 'seed': the run {key[0]} N={key[1]} seed {key[2]} "
                             f"is missing from this {what} (suite '{suite.name}', seeds {suite.seeds})")
    rows = {k: table.rows[k] for k in wanted}
    return RunTable(table.source, table.columns, rows, {k: table.lines[k] for k in wanted})


def baseline_csv_text(table: RunTable) -> str:
    """The stored form: the non-timing columns, rows sorted by estimator, particles, seed."""
    columns = [c for c in table.columns if not is_timing(c)]
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow(columns)
    for key in sorted(table.rows):
        writer.writerow([table.rows[key][c] for c in columns])
    return out.getvalue()


def sha256_text(text: str) -> str:
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def header_checksum(header: dict[str, Any]) -> str:
    body = {k: v for k, v in header.items() if k != "checksum"}
    return sha256_text(json.dumps(body, sort_keys=True, separators=(",", ":")))


@dataclass
class Baseline:
    folder: Path
    header: dict[str, Any]
    tables: dict[str, RunTable]


def load_baseline(folder: Path, suites: tuple[Suite, ...], fewer_seeds: bool = False) -> Baseline:
    """Reads baseline.json and each suite's table, checking the header's checksum, that each suite
    was run as the gates file defines it, and each table against its recorded checksum. With
    `fewer_seeds` (moving the baseline to a suite of fewer seeds) a baseline whose seeds include
    the suite's is accepted and restricted to them."""
    header_path = folder / "baseline.json"
    try:
        header = json.loads(read_text(header_path, "baseline header"))
    except json.JSONDecodeError as error:
        raise InputError(f"{header_path}: not JSON: {error}") from None
    if not isinstance(header, dict) or header.get("format") != BASELINE_FORMAT:
        raise InputError(f"{header_path}: field 'format': expected '{BASELINE_FORMAT}'")
    if header.get("checksum") != header_checksum(header):
        raise InputError(f"{header_path}: field 'checksum': does not match the header: it was "
                         "edited by hand; write baselines with ci/update-baseline.sh")
    recorded = header.get("suites")
    if not isinstance(recorded, dict):
        raise InputError(f"{header_path}: field 'suites': expected a mapping")
    tables = {}
    for suite in suites:
        entry = recorded.get(suite.name)
        if not isinstance(entry, dict):
            raise InputError(f"{header_path}: field 'suites.{suite.name}': this baseline has no "
                             f"suite '{suite.name}'; update it with ci/update-baseline.sh")
        for field, expected in suite.definition().items():
            recorded_value = entry.get("definition", {}).get(field)
            if (fewer_seeds and field == "seeds" and isinstance(recorded_value, str)
                    and set(suite.seed_list()) <= set(expand_seeds(recorded_value))):
                continue
            if recorded_value != expected:
                raise InputError(
                    f"{header_path}: field 'suites.{suite.name}.definition.{field}': the baseline "
                    f"was run with {entry.get('definition', {}).get(field)!r}, the gates file says "
                    f"{expected!r} (a baseline of another scenario, seed set or run)")
        path = folder / f"{suite.name}.csv"
        text = read_text(path, "baseline table")
        if sha256_text(text) != entry.get("sha256"):
            raise InputError(f"{path}: its SHA-256 differs from field 'suites.{suite.name}.sha256' "
                             f"of {header_path}: the table was changed after it was recorded")
        tables[suite.name] = select_suite_runs(parse_runs(text, str(path)), suite, "baseline")
    return Baseline(folder, header, tables)
