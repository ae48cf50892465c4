"""Table content shared by the HTML report and table.md: paper-style tables and cell text."""

from __future__ import annotations

import math

from .bound_efficiency import BOUNDS, row_name
from .comparison import Comparison, ComparisonRow, format_value
from .paper import PRIMARY_TABLES, PaperTable, PaperValues, option_mismatches
from .results import ResultsFolder
from .table_efficiency import (
    BOUND_ROW_METRICS,
    Efficiencies,
    efficiency_cells,
    efficiency_headers,
    efficiency_position,
)


def ours_with_se(ours: float, se: float) -> str:
    """"12.3 ± 0.45", or just the value when the standard error is unknown."""
    if ours is None or not math.isfinite(ours):
        return "\u2014"
    if se is None or not math.isfinite(se):
        return format_value(ours)
    return f"{format_value(ours)} \u00b1 {format_value(se, 2)}"


def matched_paper_tables(
    results: ResultsFolder, paper: PaperValues, comparison: Comparison
) -> list[PaperTable]:
    """Tables I/II/III whose exact configuration the results hold.

    A table matches when some summary row was compared with it, the folder's scenario options
    equal the table's (steps, pD, clutter rate) and at least one (estimator, N) of the table is
    present.
    """
    matched = []
    for table_id in PRIMARY_TABLES:
        rows = [r for r in comparison.rows if r.table is not None and r.table.id == table_id]
        if not rows:
            continue
        table = rows[0].table
        steps = rows[0].steps
        if option_mismatches(table, results.scenario_options, steps):
            continue
        if any(table.values.get(r.group.estimator, {}).get(str(r.group.particles)) for r in rows):
            matched.append(table)
    return matched


def paper_table_rows(
    table: PaperTable, comparison: Comparison, paper: PaperValues,
    efficiencies: Efficiencies | None = None,
) -> tuple[list[str], list[list[str]]]:
    """The table in the paper's layout: one row per (filter, N) we have, "ours ± SE (paper)".

    With ``efficiencies`` (the folder holds a bound's rows: table_efficiency.py) each row also
    gets its efficiency, in columns right after the RMSEs, the folder's estimators the paper lacks
    follow with "(—)", and the bound rows come last, labelled as bounds.
    """
    headers = ["Filter", "N"] + [paper.metric_label(m) for m in table.metrics]
    at = efficiency_position(table.metrics)
    if efficiencies is not None:
        headers[at:at] = efficiency_headers(table.metrics)
    rows = []
    for row in _rows_in_table_order(table, comparison, efficiencies is not None):
        estimator, n = row.group.estimator, row.group.particles
        name = row_name(paper.display_name(estimator), estimator)
        cells = [name, str(n)] + [_paper_cell(row, table, metric) for metric in table.metrics]
        if efficiencies is not None:
            cells[at:at] = efficiency_cells(efficiencies, estimator, n, table.metrics)
        rows.append(cells)
    return headers, rows


def _rows_in_table_order(table: PaperTable, comparison: Comparison,
                         with_others: bool) -> list[ComparisonRow]:
    """The rows of the table's (filter, N) in its order; with ``with_others`` then the other
    estimators' rows and the bounds' rows last."""
    mine = [r for r in comparison.rows if r.table is table]
    ordered = []
    for estimator in table.estimators():
        for n in table.particle_counts():
            ordered += [r for r in mine if r.group.estimator == estimator
                        and str(r.group.particles) == n][:1]
    if with_others:
        ordered += [r for r in mine if r not in ordered and r.group.estimator not in BOUNDS]
        ordered += [r for r in comparison.rows if r.group.estimator in BOUNDS]
    return ordered


def _paper_cell(row: ComparisonRow, table: PaperTable, metric: str) -> str:
    """"ours ± SE (paper)", with ⚠ beyond the tolerance; a bound's cell has no paper part."""
    cell = row.cell(metric)
    ours = ours_with_se(cell.ours, cell.se) if cell else "\u2014"
    if row.group.estimator in BOUNDS:
        return ours if metric in BOUND_ROW_METRICS else "\u2014"
    published = format_value(table.value(row.group.estimator, row.group.particles, metric))
    mark = " \u26a0" if cell and cell.flagged else ""
    return f"{ours} ({published}){mark}"
