"""Our summary values with their Monte Carlo standard errors beside the paper's values."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from .paper import PaperTable, PaperValues, option_mismatches, primary_table, resampling_enabled
from .results import Group, ResultsFolder
from .stats import (
    is_flagged,
    relative_difference,
    standard_error_from_std,
    standard_error_of_values,
)

SUMMARY_METRICS = (
    "pos_rmse_m", "heading_rmse_deg", "gospa_mean_m", "ess_pct", "resampling_pct",
    "ms_per_step_mean",
)
OPTIONAL_METRICS = ("da_tpr", "da_tnr")

RUNS_COLUMN_OF = {
    "pos_rmse_m": "pos_rmse_m",
    "heading_rmse_deg": "heading_rmse_deg",
    "gospa_mean_m": "gospa_m",
    "ess_pct": "ess_pct",
    "resampling_pct": "resampling_pct",
    "ms_per_step_mean": "ms_per_step_mean",
    "da_tpr": "da_tpr",
    "da_tnr": "da_tnr",
}
"""runs.csv column holding the per-run value of each summary metric."""


@dataclass(frozen=True)
class Cell:
    """One metric of one group: ours, its standard error, the paper's value and the difference."""

    metric: str
    ours: float
    se: float
    paper: float | None
    relative: float
    flagged: bool


@dataclass
class ComparisonRow:
    """One summary.csv row compared with a published table."""

    group: Group
    runs: int
    steps: float
    table: PaperTable | None
    cells: list[Cell] = field(default_factory=list)

    def cell(self, metric: str) -> Cell | None:
        """The cell of ``metric``, or None."""
        return next((c for c in self.cells if c.metric == metric), None)


@dataclass
class Comparison:
    """All rows of one results folder and the notes that qualify them."""

    rows: list[ComparisonRow]
    metrics: list[str]
    notes: list[str]


def _number(value: object) -> float:
    try:
        return float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        return math.nan


def metric_standard_error(
    metric: str, summary_row: dict[str, object], runs_rows: list[dict[str, object]]
) -> float:
    """Monte Carlo standard error of a summary metric.

    GOSPA: gospa_std_m / sqrt(runs) of summary.csv. Every other metric (including the pooled
    RMSEs): sample std of the per-run values in runs.csv / sqrt(runs).
    """
    if metric == "gospa_mean_m":
        return standard_error_from_std(
            _number(summary_row.get("gospa_std_m")), _number(summary_row.get("runs"))
        )
    column = RUNS_COLUMN_OF.get(metric, metric)
    return standard_error_of_values([_number(row.get(column)) for row in runs_rows])


def compare(
    results: ResultsFolder, paper: PaperValues, table_override: str | None = None
) -> Comparison:
    """Compares every summary.csv row of ``results`` with the matching published table."""
    notes: list[str] = []
    if results.summary is None:
        return Comparison(rows=[], metrics=list(SUMMARY_METRICS), notes=notes)
    metrics = list(SUMMARY_METRICS) + [m for m in OPTIONAL_METRICS if results.summary.has(m)]
    rows: list[ComparisonRow] = []
    mismatch_noted: set[str] = set()
    for record in results.summary.records():
        group = Group(str(record["estimator"]), int(record["particles"]))
        resampling = resampling_enabled(results.estimator_parameters(group))
        table = primary_table(paper, results.scenario_name, resampling, table_override)
        runs_rows = results.runs_rows(group)
        row = ComparisonRow(group=group, runs=int(_number(record["runs"]) or 0),
                            steps=_number(record["steps"]), table=table)
        if table is not None and table.id not in mismatch_noted:
            mismatch_noted.add(table.id)
            mismatches = option_mismatches(table, results.scenario_options, row.steps)
            if mismatches:
                notes.append(
                    f"These results differ from the configuration of {table.title}: "
                    + "; ".join(mismatches) + ". The comparison is indicative only."
                )
        for metric in metrics:
            ours = _number(record.get(metric))
            reference = table.value(group.estimator, group.particles, metric) if table else None
            known = reference is not None
            row.cells.append(Cell(
                metric=metric,
                ours=ours,
                se=metric_standard_error(metric, record, runs_rows),
                paper=reference,
                relative=relative_difference(ours, reference) if known else math.nan,
                flagged=is_flagged(ours, reference) if known else False,
            ))
        rows.append(row)
    if results.runs_table is None:
        notes.append(
            "runs.csv is missing: standard errors of the pooled metrics are not available.")
    return Comparison(rows=rows, metrics=metrics, notes=notes)


def secondary_references(
    results: ResultsFolder, paper: PaperValues, comparison: Comparison
) -> list[tuple[PaperTable, ComparisonRow, str, float | None]]:
    """Other published numbers (authors' rerun, DA accuracy) that concern our groups.

    Returns (table, our row, metric, published value) for every such number; our value may be
    missing (e.g. DA rates that the results do not hold).
    """
    out = []
    for table_id in ("authors_rerun", "da_accuracy"):
        table = paper.tables.get(table_id)
        if table is None or table.scenario != results.scenario_name:
            continue
        for row in comparison.rows:
            for metric in table.metrics:
                value = table.value(row.group.estimator, row.group.particles, metric)
                if value is not None:
                    out.append((table, row, metric, value))
    return out


def format_value(value: float | None, digits: int = 4) -> str:
    """A number with ``digits`` significant digits, or an em dash when missing."""
    if value is None or not math.isfinite(value):
        return "\u2014"
    return f"{value:.{digits}g}"


def format_relative(relative: float) -> str:
    """A relative difference as a signed percentage, or an em dash."""
    if not math.isfinite(relative):
        return "\u2014"
    return f"{100.0 * relative:+.1f} %"
