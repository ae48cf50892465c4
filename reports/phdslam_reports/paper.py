"""The paper's published numbers (reports/paper_values.yaml) and which of them fit the results."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import yaml

from .csv_table import ResultsFormatError

DEFAULT_PAPER_VALUES = Path(__file__).resolve().parent.parent / "paper_values.yaml"

PRIMARY_TABLES = ("table2", "table1", "table3")
"""Tables whose values stand beside ours in the summary table, in order of preference."""


@dataclass
class PaperTable:
    """One published table: the configuration it belongs to and its values."""

    id: str
    title: str
    source: str
    scenario: str
    resampling: bool
    runs: int
    scenario_options: dict[str, Any]
    metrics: list[str]
    values: dict[str, dict[str, dict[str, float | None]]]
    notes: str = ""

    def value(self, estimator: str, particles: int, metric: str) -> float | None:
        """The published value, or None when the paper gives none."""
        per_n = self.values.get(estimator, {})
        row = per_n.get(str(particles), per_n.get("any", {}))
        value = row.get(metric)
        return None if value is None else float(value)

    def estimators(self) -> list[str]:
        """Estimators of the table, in the file's order."""
        return list(self.values)

    def particle_counts(self) -> list[str]:
        """Particle-count keys of the table (numbers as text, or 'any'), in increasing order."""
        keys = {k for per_n in self.values.values() for k in per_n}
        return sorted(keys, key=lambda k: (k == "any", int(k) if k.isdigit() else 0))


@dataclass
class PaperValues:
    """Every published number, estimator display names and metric labels."""

    estimator_names: dict[str, str]
    metric_labels: dict[str, tuple[str, str]]
    tables: dict[str, PaperTable] = field(default_factory=dict)

    @staticmethod
    def load(path: Path | str = DEFAULT_PAPER_VALUES) -> "PaperValues":
        """Reads and checks paper_values.yaml; errors name the file and the offending entry."""
        path = Path(path)
        try:
            data = yaml.safe_load(path.read_text(encoding="utf-8"))
        except (OSError, yaml.YAMLError) as error:
            raise ResultsFormatError(f"{path}: cannot read YAML: {error}") from error
        if not isinstance(data, dict):
            raise ResultsFormatError(f"{path}: expected a mapping at the top level")
        names = {str(k): str(v) for k, v in (data.get("estimator_names") or {}).items()}
        labels = {}
        for metric, entry in (data.get("metrics") or {}).items():
            if not isinstance(entry, dict) or "label" not in entry:
                raise ResultsFormatError(f"{path}: metrics.{metric}: expected {{label, unit}}")
            labels[str(metric)] = (str(entry["label"]), str(entry.get("unit", "")))
        tables = {}
        for index, entry in enumerate(data.get("tables") or []):
            table = _parse_table(path, index, entry)
            tables[table.id] = table
        return PaperValues(estimator_names=names, metric_labels=labels, tables=tables)

    def display_name(self, estimator: str) -> str:
        """The paper's name of an estimator ("PHD 3.0" for phd3), else the registry name."""
        return self.estimator_names.get(estimator, estimator)

    def metric_label(self, metric: str, with_unit: bool = True) -> str:
        """A metric's label, e.g. "Position RMSE (m)"."""
        label, unit = self.metric_labels.get(metric, (metric, ""))
        return f"{label} ({unit})" if with_unit and unit else label


def _parse_table(path: Path, index: int, entry: Any) -> PaperTable:
    where = f"{path}: tables[{index}]"
    if not isinstance(entry, dict):
        raise ResultsFormatError(f"{where}: expected a mapping")
    for key in ("id", "title", "scenario", "metrics", "values"):
        if key not in entry:
            raise ResultsFormatError(f"{where}: missing key '{key}'")
    metrics = [str(m) for m in entry["metrics"]]
    values: dict[str, dict[str, dict[str, float | None]]] = {}
    for estimator, per_n in (entry["values"] or {}).items():
        if not isinstance(per_n, dict):
            raise ResultsFormatError(f"{where}.values.{estimator}: expected a mapping by N")
        values[str(estimator)] = {}
        for n, row in per_n.items():
            if not isinstance(row, dict):
                raise ResultsFormatError(f"{where}.values.{estimator}.{n}: expected a mapping")
            clean: dict[str, float | None] = {}
            for metric, value in row.items():
                if metric not in metrics:
                    raise ResultsFormatError(
                        f"{where}.values.{estimator}.{n}: metric '{metric}' is not in the "
                        f"table's metrics {metrics}"
                    )
                if value is not None and not isinstance(value, (int, float)):
                    raise ResultsFormatError(
                        f"{where}.values.{estimator}.{n}.{metric}: '{value}' is not a number"
                    )
                clean[str(metric)] = None if value is None else float(value)
            values[str(estimator)][str(n)] = clean
    return PaperTable(
        id=str(entry["id"]),
        title=str(entry["title"]),
        source=str(entry.get("source", "")),
        scenario=str(entry["scenario"]),
        resampling=bool(entry.get("resampling", True)),
        runs=int(entry.get("runs", 0)),
        scenario_options=dict(entry.get("scenario_options") or {}),
        metrics=metrics,
        values=values,
        notes=str(entry.get("notes", "")).strip(),
    )


def resampling_enabled(parameters: dict[str, Any]) -> bool:
    """False when the resolved estimator parameters switch resampling off, else True.

    Looks for a key containing "resampl" (or ``ess_threshold``) whose value, or a value nested
    under it, is false, 0, "never", "none" or "off".
    """
    off_words = {"never", "none", "off", "false", "no"}

    def is_off(value: Any) -> bool:
        if value is False or (isinstance(value, (int, float)) and value == 0):
            return True
        return isinstance(value, str) and value.lower() in off_words

    def walk(node: Any, inside: bool) -> bool:
        if isinstance(node, dict):
            for key, value in node.items():
                name = str(key).lower()
                here = inside or "resampl" in name or name == "ess_threshold"
                if here and not isinstance(value, (dict, list)) and is_off(value):
                    return False
                if not walk(value, here):
                    return False
        return True

    return walk(parameters, False)


def option_mismatches(
    table: PaperTable, options: dict[str, Any], steps_per_run: float | None
) -> list[str]:
    """The scenario settings of a results folder that differ from the paper's table.

    ``steps`` is compared with the table's step count using the option, or (when the option is 0
    or absent, meaning "all") the mean steps per run of summary.csv.
    """
    mismatches = []
    for key, expected in table.scenario_options.items():
        actual = options.get(key)
        if key == "steps":
            if not actual:
                actual = steps_per_run
            if actual is None or (isinstance(actual, float) and math.isnan(actual)):
                continue
        if key == "detection_probability" and actual is None:
            actual = options.get("detection_probability_nominal")
        if actual is None:
            continue
        try:
            same = math.isclose(float(actual), float(expected), rel_tol=1e-9, abs_tol=1e-12)
        except (TypeError, ValueError):
            same = str(actual) == str(expected)
        if not same:
            mismatches.append(f"{key} = {actual:g} (paper: {expected:g})"
                              if isinstance(actual, (int, float)) else f"{key} = {actual}")
    return mismatches


def primary_table(
    paper: PaperValues, scenario: str | None, resampling: bool, override: str | None = None
) -> PaperTable | None:
    """The published table that matches a scenario and resampling setting.

    ``override`` names a table id to use whatever the configuration, or "none" for no table.
    """
    if override == "none":
        return None
    if override:
        if override not in paper.tables:
            raise ValueError(f"unknown paper table '{override}' (known: {', '.join(paper.tables)})")
        return paper.tables[override]
    for table_id in PRIMARY_TABLES:
        table = paper.tables.get(table_id)
        if table and table.scenario == scenario and table.resampling == resampling:
            return table
    return None
