"""Table content shared by the HTML report and table.md: paper-style tables and cell text."""

from __future__ import annotations

import math

from .comparison import Comparison, format_value
from .paper import PRIMARY_TABLES, PaperTable, PaperValues, option_mismatches
from .results import ResultsFolder


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
    table: PaperTable, comparison: Comparison, paper: PaperValues
) -> tuple[list[str], list[list[str]]]:
    """The table in the paper's layout: one row per (filter, N) we have, "ours ± SE (paper)"."""
    headers = ["Filter", "N"] + [paper.metric_label(m) for m in table.metrics]
    rows = []
    for estimator in table.estimators():
        for n in table.particle_counts():
            row = next((r for r in comparison.rows if r.table is table
                        and r.group.estimator == estimator and str(r.group.particles) == n), None)
            if row is None:
                continue
            cells = [paper.display_name(estimator), n]
            for metric in table.metrics:
                cell = row.cell(metric)
                published = format_value(table.value(estimator, int(n), metric))
                ours = ours_with_se(cell.ours, cell.se) if cell else "\u2014"
                mark = " \u26a0" if cell and cell.flagged else ""
                cells.append(f"{ours} ({published}){mark}")
            rows.append(cells)
    return headers, rows
