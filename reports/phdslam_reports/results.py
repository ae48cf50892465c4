"""A phdslam results folder (layout in validation/README.md) opened for reading.

Files are read lazily and validated on first use; every problem raises ResultsFormatError naming
the file (and, for CSV files, the line and column).
"""

from __future__ import annotations

import json
import math
import re
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path
from typing import Any

import numpy as np

from .csv_table import CsvTable, ResultsFormatError, read_csv

SUMMARY_FILE = "summary.csv"
RUNS_TABLE_FILE = "runs.csv"
CONFIG_FILE = "config.json"
TRUTH_MAP_FILE = "truth_map.csv"
RUNS_FOLDER = "runs"
STEPS_FILE = "steps.csv"
MAP_FILE = "map.csv"
PARTICLES_FILE = "particles.csv"
SCALING_FILE = "scaling.csv"
MAP_SCALING_FILE = "map_scaling.csv"
SWEEP_FILE = "sweep.csv"
TRUTH_FOLDER = "truth"
GPS_FILE = "gps.csv"
PARENT_WEIGHTS_FILE = "parent_weights.csv"
PARENT_WEIGHTS_META_FILE = "parent_weights.json"

SUMMARY_COLUMNS = (
    "estimator", "particles", "runs", "steps", "pos_rmse_m", "heading_rmse_deg", "gospa_mean_m",
    "gospa_std_m", "ess_pct", "resampling_pct", "ms_per_step_mean",
)
RUNS_COLUMNS = (
    "estimator", "particles", "seed", "steps", "pos_rmse_m", "heading_rmse_deg", "gospa_m",
    "ess_pct", "resampling_pct", "ms_per_step_mean",
)
STEPS_COLUMNS = (
    "step", "t", "x", "y", "theta", "x_true", "y_true", "theta_true", "pos_err_m",
    "heading_err_deg", "ess", "resampled", "hypotheses", "map_components", "ms",
)
MAP_COLUMNS = ("x", "y")
PARTICLES_COLUMNS = ("step", "particle", "x", "y")
PARTICLE_WEIGHT_COLUMNS = ("log_weight", "weight")
"""particles.csv carries one of these: ``log_weight`` (what ``phdslam run --particles-trace``
writes, normalised natural-log weights) or ``weight`` (linear weights)."""
SCALING_COLUMNS = ("estimator", "landmarks_in_fov", "us_per_call")
MAP_SCALING_COLUMNS = ("landmarks", "particles", "ms_per_step", "map_bytes")
GPS_COLUMNS = ("t", "x", "y")
PARENT_WEIGHTS_COLUMNS = ("parent", "x", "y", "theta", "sc_weight", "rb_weight")
PARENT_WEIGHT_COLUMNS = ("sc_weight", "rb_weight")
PARENT_LOG_WEIGHT_COLUMNS = ("sc_log_weight", "rb_log_weight")
"""Optional: the normalised natural-log weights (log-sum-exp 0), finite where weights underflow."""
PARENT_MISSED_MASS_COLUMN = "missed_mass"
"""Optional: sum of pD w over the predicted map seen from each parent (>= 0)."""
WEIGHT_SUM_TOLERANCE = 1e-6
"""|sum of a weight column - 1| (and |log-sum-exp| of a log-weight column) allowed in
parent_weights.csv (cells are printed with %.10g)."""

_GROUP_FOLDER = re.compile(r"^(?P<estimator>.+)-N(?P<particles>\d+)$")
_SEED_FOLDER = re.compile(r"^seed-(?P<seed>\d+)$")


@dataclass(frozen=True, order=True)
class Group:
    """One (estimator, particle count) pair: a row of summary.csv and a folder of runs/."""

    estimator: str
    particles: int

    @property
    def folder_name(self) -> str:
        """``<estimator>-N<particles>``, as the runner names the group's folder."""
        return f"{self.estimator}-N{self.particles}"


def _as_int(value: float, path: Path, column: str, row: int) -> int:
    if value != value or value != int(value):
        raise ResultsFormatError(f"{path}, row {row}, column '{column}': expected an integer")
    return int(value)


def _validate_parent_weights(table: CsvTable) -> CsvTable:
    """Every cell of parent_weights.csv present; weights >= 0 and each column summing to 1.

    The optional columns sc_log_weight and rb_log_weight (both or neither) must be finite with a
    log-sum-exp of 0, and missed_mass finite and >= 0.
    """
    path = table.path
    if table.rows == 0:
        raise ResultsFormatError(f"{path}: no parent rows (expected one row per parent pose)")
    present_logs = [c for c in PARENT_LOG_WEIGHT_COLUMNS if table.has(c)]
    if len(present_logs) == 1:
        other = next(c for c in PARENT_LOG_WEIGHT_COLUMNS if c not in present_logs)
        raise ResultsFormatError(
            f"{path}: column '{present_logs[0]}' without '{other}' (the log-weights of both "
            "weightings are needed for their shared colour scale)")
    optional = present_logs + ([PARENT_MISSED_MASS_COLUMN]
                               if table.has(PARENT_MISSED_MASS_COLUMN) else [])
    for column in list(PARENT_WEIGHTS_COLUMNS) + optional:
        values = table.num(column)
        for row, value in enumerate(values):
            if value != value:
                raise ResultsFormatError(
                    f"{path}, line {table.line(row)}, column '{column}': empty cell (every "
                    "parent needs a value)")
            if not math.isfinite(value):
                raise ResultsFormatError(
                    f"{path}, line {table.line(row)}, column '{column}': '{value:g}' is not a "
                    "finite number")
            if column == "parent" and value != int(value):
                raise ResultsFormatError(
                    f"{path}, line {table.line(row)}, column 'parent': '{value:g}' is not an "
                    "integer")
            if column in PARENT_WEIGHT_COLUMNS and value < 0:
                raise ResultsFormatError(
                    f"{path}, line {table.line(row)}, column '{column}': negative weight "
                    f"{value:g}")
            if column == PARENT_MISSED_MASS_COLUMN and value < 0:
                raise ResultsFormatError(
                    f"{path}, line {table.line(row)}, column '{column}': negative "
                    f"missed-detection mass {value:g}")
    lines = f"lines {table.line(0)}-{table.line(table.rows - 1)}"
    for column in PARENT_WEIGHT_COLUMNS:
        total = float(np.sum(table.num(column)))
        if not abs(total - 1.0) <= WEIGHT_SUM_TOLERANCE:
            raise ResultsFormatError(
                f"{path}, {lines}, column '{column}': the weights sum to {total:.10g}, expected "
                f"1 within {WEIGHT_SUM_TOLERANCE:g} (normalised weights)")
    for column in present_logs:
        values = table.num(column)
        top = float(np.max(values))
        log_total = top + math.log(float(np.sum(np.exp(values - top))))
        if not abs(log_total) <= WEIGHT_SUM_TOLERANCE:
            raise ResultsFormatError(
                f"{path}, {lines}, column '{column}': the log-sum-exp of the log-weights is "
                f"{log_total:.10g}, expected 0 within {WEIGHT_SUM_TOLERANCE:g} (normalised "
                "log-weights)")
    return table


def _json_number(value: object) -> bool:
    return (isinstance(value, (int, float)) and not isinstance(value, bool)
            and math.isfinite(value))


def _validate_parent_weights_meta(data: object, path: Path, parents: int) -> dict[str, Any]:
    """The keys of parent_weights.json that the report uses, with their types."""
    if not isinstance(data, dict):
        raise ResultsFormatError(f"{path}: expected a JSON object at the top level")

    def fail(key: str, expected: str) -> None:
        shown = json.dumps(data[key]) if key in data else "missing"
        raise ResultsFormatError(f"{path}: key '{key}': expected {expected}, got {shown}")

    for key in ("step", "parents", "measurements", "map_components"):
        value = data.get(key)
        if not _json_number(value) or value != int(value) or value < 0:
            fail(key, "a non-negative integer")
    for key in ("ess_single_cluster", "ess_rb_phd"):
        if not _json_number(data.get(key)):
            fail(key, "a number")
    for key in ("previous_pose", "predicted_mean", "true_pose"):
        value = data.get(key)
        if key == "true_pose" and key in data and value is None:
            continue
        if not (isinstance(value, list) and len(value) == 3 and all(map(_json_number, value))):
            fail(key, "[x, y, theta]" + (" or null" if key == "true_pose" else ""))
    cov = data.get("predicted_cov")
    if not (isinstance(cov, list) and len(cov) == 3 and all(
            isinstance(r, list) and len(r) == 3 and all(map(_json_number, r)) for r in cov)):
        fail("predicted_cov", "a 3x3 nested list of numbers")
    if "scenario" in data and not isinstance(data["scenario"], str):
        fail("scenario", "a string")
    if "seed" in data and not _json_number(data["seed"]):
        fail("seed", "a number")
    if "spread" in data and not (_json_number(data["spread"]) and data["spread"] > 0):
        fail("spread", "a positive number")
    if int(data["parents"]) != parents:
        raise ResultsFormatError(
            f"{path}: key 'parents' is {data['parents']}, but {PARENT_WEIGHTS_FILE} has "
            f"{parents} parent rows")
    return data


class ResultsFolder:
    """Read access to the files of one ``phdslam run --out DIR`` folder."""

    def __init__(self, path: Path | str) -> None:
        self.path = Path(path)
        if not self.path.is_dir():
            raise ResultsFormatError(f"{self.path}: not a folder")
        if (not (self.path / SUMMARY_FILE).is_file() and not (self.path / RUNS_FOLDER).is_dir()
                and not (self.path / PARENT_WEIGHTS_FILE).is_file()):
            raise ResultsFormatError(
                f"{self.path}: not a results folder (neither {SUMMARY_FILE}, {RUNS_FOLDER}/ nor "
                f"{PARENT_WEIGHTS_FILE})"
            )
        self._steps_cache: dict[tuple[Group, int], CsvTable] = {}

    # --- folder-level files -------------------------------------------------------------------

    @cached_property
    def config(self) -> dict[str, Any] | None:
        """config.json as a dict, or None when absent."""
        path = self.path / CONFIG_FILE
        if not path.is_file():
            return None
        try:
            data = json.loads(path.read_text(encoding="utf-8"))
        except (OSError, UnicodeDecodeError, json.JSONDecodeError) as error:
            raise ResultsFormatError(f"{path}: not valid JSON: {error}") from error
        if not isinstance(data, dict):
            raise ResultsFormatError(f"{path}: expected a JSON object at the top level")
        return data

    @cached_property
    def summary(self) -> CsvTable | None:
        """summary.csv, or None when absent."""
        path = self.path / SUMMARY_FILE
        if not path.is_file():
            return None
        table = read_csv(path, SUMMARY_COLUMNS, text_columns=("estimator",), finite_only=True)
        if table.rows == 0:
            raise ResultsFormatError(
                f"{path}: header only, no group rows (an interrupted or truncated write; "
                f"'phdslam run' or 'phdslam merge' with the same --out rewrites it)")
        for i, value in enumerate(table.num("particles")):
            _as_int(value, path, "particles", i + 1)
        self._check_no_duplicate_rows(table)
        self._check_summary_covers_runs(table)
        return table

    @staticmethod
    def _check_no_duplicate_rows(summary: CsvTable) -> None:
        """One row per group: a duplicated row would be drawn twice."""
        first_line: dict[tuple[str, int], int] = {}
        for i, (estimator, particles) in enumerate(zip(summary.str("estimator"),
                                                       summary.num("particles"))):
            key = (estimator, int(particles))
            if key in first_line:
                raise ResultsFormatError(
                    f"{summary.path}, line {summary.line(i)}: the row of {estimator} "
                    f"N={int(particles)} appears twice (first on line {first_line[key]}); "
                    f"'phdslam run' or 'phdslam merge' with the same --out rewrites the file")
            first_line[key] = summary.line(i)

    def _check_summary_covers_runs(self, summary: CsvTable) -> None:
        """Every group of runs.csv must have its summary.csv row (else the file was cut short)."""
        runs = self.runs_table
        if runs is None:
            return
        listed = set(zip(summary.str("estimator"), (int(n) for n in summary.num("particles"))))
        for estimator, particles in zip(runs.str("estimator"), runs.num("particles")):
            if math.isfinite(particles) and (estimator, int(particles)) not in listed:
                raise ResultsFormatError(
                    f"{self.path / SUMMARY_FILE}: no row for {estimator} N={int(particles)}, "
                    f"which {RUNS_TABLE_FILE} has (a truncated file; 'phdslam run' or "
                    f"'phdslam merge' with the same --out rewrites it)")

    @cached_property
    def runs_table(self) -> CsvTable | None:
        """runs.csv, or None when absent."""
        path = self.path / RUNS_TABLE_FILE
        if not path.is_file():
            return None
        return read_csv(path, RUNS_COLUMNS, text_columns=("estimator",), finite_only=True)

    @cached_property
    def truth_map(self) -> CsvTable | None:
        """truth_map.csv, or None when the scenario has no true map."""
        path = self.path / TRUTH_MAP_FILE
        return read_csv(path, MAP_COLUMNS) if path.is_file() else None

    def gps(self, seed: int) -> CsvTable | None:
        """``truth/seed-<seed>/gps.csv`` (t, x, y: GPS fixes of real data), or None when absent."""
        path = self.path / TRUTH_FOLDER / f"seed-{seed}" / GPS_FILE
        return read_csv(path, GPS_COLUMNS) if path.is_file() else None

    @cached_property
    def parent_weights(self) -> CsvTable | None:
        """parent_weights.csv (``phdslam parent-weights``), validated, or None when absent."""
        path = self.path / PARENT_WEIGHTS_FILE
        if not path.is_file():
            return None
        return _validate_parent_weights(
            read_csv(path, PARENT_WEIGHTS_COLUMNS, allow_infinite=True))

    @cached_property
    def parent_weights_meta(self) -> dict[str, Any] | None:
        """parent_weights.json, validated against parent_weights.csv, or None when absent."""
        path = self.path / PARENT_WEIGHTS_META_FILE
        table = self.parent_weights
        if table is None or not path.is_file():
            return None
        try:
            data = json.loads(path.read_text(encoding="utf-8"))
        except (OSError, UnicodeDecodeError, json.JSONDecodeError) as error:
            raise ResultsFormatError(f"{path}: not valid JSON: {error}") from error
        return _validate_parent_weights_meta(data, path, table.rows)

    def optional_table(self, name: str, required: tuple[str, ...]) -> CsvTable | None:
        """A CSV file at the folder's top level (scaling.csv, sweep.csv), or None."""
        path = self.path / name
        return read_csv(path, required, text_columns=("estimator",)) if path.is_file() else None

    # --- configuration ------------------------------------------------------------------------

    @property
    def scenario_name(self) -> str | None:
        """The scenario name from config.json."""
        scenario = (self.config or {}).get("scenario")
        return scenario.get("name") if isinstance(scenario, dict) else None

    @property
    def scenario_options(self) -> dict[str, Any]:
        """The resolved scenario options from config.json (empty when unknown)."""
        scenario = (self.config or {}).get("scenario")
        options = scenario.get("options") if isinstance(scenario, dict) else None
        return options if isinstance(options, dict) else {}

    def estimator_parameters(self, group: Group) -> dict[str, Any]:
        """The resolved parameters of ``group`` from config.json (empty when unknown)."""
        estimators = (self.config or {}).get("estimators")
        entry = estimators.get(group.estimator) if isinstance(estimators, dict) else None
        parameters = entry.get("parameters") if isinstance(entry, dict) else None
        if not isinstance(parameters, dict):
            return {}
        value = parameters.get(str(group.particles))
        return value if isinstance(value, dict) else {}

    # --- groups and runs ----------------------------------------------------------------------

    def groups(self) -> list[Group]:
        """Every (estimator, particles) of summary.csv and of runs/, sorted."""
        found: set[Group] = set()
        if self.summary is not None:
            for name, n in zip(self.summary.str("estimator"), self.summary.num("particles")):
                found.add(Group(name, int(n)))
        runs = self.path / RUNS_FOLDER
        if runs.is_dir():
            for child in runs.iterdir():
                match = _GROUP_FOLDER.match(child.name)
                if child.is_dir() and match:
                    found.add(Group(match["estimator"], int(match["particles"])))
        return sorted(found)

    def summary_row(self, group: Group) -> dict[str, object] | None:
        """The summary.csv row of ``group``, or None."""
        if self.summary is None:
            return None
        for row in self.summary.records():
            if row["estimator"] == group.estimator and int(row["particles"]) == group.particles:
                return row
        return None

    def runs_rows(self, group: Group) -> list[dict[str, object]]:
        """The runs.csv rows of ``group`` (empty without runs.csv)."""
        if self.runs_table is None:
            return []
        return [
            row for row in self.runs_table.records()
            if row["estimator"] == group.estimator and int(row["particles"]) == group.particles
        ]

    def run_folder(self, group: Group, seed: int) -> Path:
        """``runs/<estimator>-N<particles>/seed-<seed>``."""
        return self.path / RUNS_FOLDER / group.folder_name / f"seed-{seed}"

    def seeds(self, group: Group) -> list[int]:
        """Seeds of ``group`` whose steps.csv exists, in increasing order."""
        folder = self.path / RUNS_FOLDER / group.folder_name
        if not folder.is_dir():
            return []
        seeds = []
        for child in folder.iterdir():
            match = _SEED_FOLDER.match(child.name)
            if match and (child / STEPS_FILE).is_file():
                seeds.append(int(match["seed"]))
        return sorted(seeds)

    def steps(self, group: Group, seed: int) -> CsvTable:
        """steps.csv of one run."""
        key = (group, seed)
        if key not in self._steps_cache:
            self._steps_cache[key] = read_csv(
                self.run_folder(group, seed) / STEPS_FILE, STEPS_COLUMNS
            )
        return self._steps_cache[key]

    def forget_steps(self) -> None:
        """Drops the cached steps.csv tables (they can be large)."""
        self._steps_cache.clear()

    def run_map(self, group: Group, seed: int) -> CsvTable | None:
        """map.csv of one run, or None."""
        path = self.run_folder(group, seed) / MAP_FILE
        return read_csv(path, MAP_COLUMNS) if path.is_file() else None

    def particle_files(self) -> list[tuple[Group, int, Path]]:
        """Every run folder's particles.csv as (group, seed, path), sorted."""
        found = []
        for group in self.groups():
            folder = self.path / RUNS_FOLDER / group.folder_name
            if not folder.is_dir():
                continue
            for child in folder.iterdir():
                match = _SEED_FOLDER.match(child.name)
                if match and (child / PARTICLES_FILE).is_file():
                    found.append((group, int(match["seed"]), child / PARTICLES_FILE))
        return sorted(found, key=lambda item: (item[0], item[1]))

    def particles(self, path: Path) -> CsvTable:
        """A particles.csv file: step, particle, x, y and log_weight (or weight)."""
        table = read_csv(path, PARTICLES_COLUMNS)
        if not any(table.has(c) for c in PARTICLE_WEIGHT_COLUMNS):
            raise ResultsFormatError(
                f"{path}: required column 'log_weight' (or 'weight') is missing "
                f"(header: {','.join(table.header)})")
        return table
