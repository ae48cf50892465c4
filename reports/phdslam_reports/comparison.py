"""Our summary values with their Monte Carlo standard errors beside the paper's values."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

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
"""Compared when summary.csv has the column with at least one value (the data-association rates
are empty where they are not scored: PHD-SLAM 1.0, odometry, real data without a true map)."""

ONLY_SLOWER_IS_FLAGGED = ("ms_per_step_mean", "ms_run_mean")
"""Times: flagged only when ours is slower than the paper's beyond the tolerance. A faster time is
no deviation from the paper (its times are MATLAB + C on another machine) and is left uncoloured."""

SUPPLEMENTARY_TABLES = ("da_accuracy",)
"""Published tables whose values fill the cells of metrics the primary table lacks, when they hold
the primary table's scenario and resampling setting (the paper's DA rates beside Table II)."""

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
    source: str | None = None  # the id of the table that gave ``paper`` (None without a value)

    @property
    def agrees(self) -> bool:
        """True when the paper gives a value and ours is within the tolerance of it either way
        (a time far below the paper's is neither flagged nor in agreement)."""
        return (self.paper is not None and math.isfinite(self.ours)
                and not is_flagged(self.ours, self.paper))


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


def _has_values(results: ResultsFolder, metric: str) -> bool:
    """True when summary.csv has the column ``metric`` with at least one value."""
    summary = results.summary
    return (summary is not None and summary.has(metric)
            and bool(np.any(np.isfinite(summary.num(metric)))))


def published_value(
    paper: PaperValues, table: PaperTable | None, group: Group, metric: str
) -> tuple[PaperTable | None, float | None]:
    """The paper's value of ``metric`` for ``group`` and the table it comes from.

    The primary ``table`` when it covers the metric, else a supplementary table (DA accuracy) of
    the same scenario and resampling setting; (None, None) when the paper gives no value.
    """
    if table is None:
        return None, None
    if metric in table.metrics:
        return table, table.value(group.estimator, group.particles, metric)
    for table_id in SUPPLEMENTARY_TABLES:
        extra = paper.tables.get(table_id)
        if (extra is None or metric not in extra.metrics or extra.scenario != table.scenario
                or extra.resampling != table.resampling):
            continue
        value = extra.value(group.estimator, group.particles, metric)
        if value is not None:
            return extra, value
    return None, None


def compare(
    results: ResultsFolder, paper: PaperValues, table_override: str | None = None
) -> Comparison:
    """Compares every summary.csv row of ``results`` with the matching published table."""
    notes: list[str] = []
    if results.summary is None:
        return Comparison(rows=[], metrics=list(SUMMARY_METRICS), notes=notes)
    metrics = list(SUMMARY_METRICS) + [m for m in OPTIONAL_METRICS if _has_values(results, m)]
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
            source, reference = published_value(paper, table, group, metric)
            known = reference is not None
            row.cells.append(Cell(
                metric=metric,
                ours=ours,
                se=metric_standard_error(metric, record, runs_rows),
                paper=reference,
                relative=relative_difference(ours, reference) if known else math.nan,
                flagged=is_flagged(ours, reference,
                                   only_above=metric in ONLY_SLOWER_IS_FLAGGED) if known else False,
                source=source.id if known and source is not None else None,
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

    Returns (table, our row, metric, published value) for every such number that the summary
    table does not already show beside ours; our value may be missing (e.g. DA rates that the
    results do not hold).
    """
    out = []
    for table_id in ("authors_rerun", "da_accuracy"):
        table = paper.tables.get(table_id)
        if table is None or table.scenario != results.scenario_name:
            continue
        for row in comparison.rows:
            for metric in table.metrics:
                value = table.value(row.group.estimator, row.group.particles, metric)
                cell = row.cell(metric)
                if value is not None and not (cell is not None and cell.source == table.id):
                    out.append((table, row, metric, value))
    return out


def paper_sources(paper: PaperValues, comparison: Comparison) -> list[PaperTable]:
    """The published tables that gave the summary table its paper values, primary ones first."""
    ids = [r.table.id for r in comparison.rows if r.table is not None]
    ids += [c.source for r in comparison.rows for c in r.cells if c.source is not None]
    return [paper.tables[i] for i in dict.fromkeys(ids) if i in paper.tables]


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
