"""Markdown tables: our values with standard errors beside the paper's."""

from __future__ import annotations

from typing import Sequence

from .comparison import (
    Comparison,
    format_relative,
    format_value,
    paper_sources,
    secondary_references,
)
from .paper import PaperValues
from .results import ResultsFolder
from .stats import relative_difference
from .table_efficiency import folder_efficiencies
from .tables_shared import matched_paper_tables, ours_with_se, paper_table_rows

FLAG_MARK = "\u26a0"


def markdown_table(headers: Sequence[str], rows: Sequence[Sequence[str]]) -> str:
    """A GitHub-flavoured Markdown table (pipes in cells escaped)."""
    def clean(cell: str) -> str:
        return str(cell).replace("|", "\\|").replace("\n", " ")

    lines = ["| " + " | ".join(clean(h) for h in headers) + " |",
             "|" + "|".join("---" for _ in headers) + "|"]
    lines += ["| " + " | ".join(clean(c) for c in row) + " |" for row in rows]
    return "\n".join(lines)


def comparison_markdown(comparison: Comparison, paper: PaperValues) -> str:
    """The summary comparison: per metric "ours ± SE", "paper", "Δ" (flagged beyond 15 %)."""
    headers = ["Estimator", "N", "runs", "steps"]
    for metric in comparison.metrics:
        label = paper.metric_label(metric)
        headers += [f"{label} ours \u00b1 SE", "paper", "\u0394"]
    rows = []
    for row in comparison.rows:
        cells = [paper.display_name(row.group.estimator), str(row.group.particles),
                 str(row.runs), format_value(row.steps)]
        for cell in row.cells:
            delta = format_relative(cell.relative)
            if cell.flagged:
                delta = f"**{delta}** {FLAG_MARK}"
            cells += [ours_with_se(cell.ours, cell.se), format_value(cell.paper), delta]
        rows.append(cells)
    return markdown_table(headers, rows)


def report_markdown(results: ResultsFolder, paper: PaperValues, comparison: Comparison) -> str:
    """The whole table.md text of one results folder."""
    parts = [f"# Results of `{results.path}`", ""]
    if results.scenario_name:
        parts += [f"Scenario: `{results.scenario_name}`.", ""]
    parts += [
        "Our values are Monte Carlo means (pooled RMSEs as in the paper) \u00b1 their standard "
        "error: GOSPA std/sqrt(runs); every other metric the spread of its per-run values in "
        "runs.csv / sqrt(runs). \u0394 is (ours \u2212 paper) / paper; "
        f"{FLAG_MARK} marks cells more than 15 % off (a time per step only when it is slower "
        "than the paper's).", "",
    ]
    for note in comparison.notes:
        parts += [f"> {note}", ""]
    if comparison.rows:
        parts += ["## Summary beside the paper", "", comparison_markdown(comparison, paper), ""]
        for table in paper_sources(paper, comparison):
            parts += [f"Paper values: {table.title}; source: {table.source}."
                      + (f" {table.notes}" if table.notes else ""), ""]
    else:
        parts += ["No summary.csv: nothing to tabulate.", ""]
    efficiencies = folder_efficiencies(results)
    for table in matched_paper_tables(results, paper, comparison):
        headers, rows = paper_table_rows(table, comparison, paper, efficiencies)
        parts += [f"## {table.title}", "", markdown_table(headers, rows), ""]
        if table.notes:
            parts += [f"_{table.notes}_", ""]
    secondary = secondary_references(results, paper, comparison)
    if secondary:
        parts += ["## Other published numbers", ""]
        rows = []
        for table, row, metric, value in secondary:
            cell = row.cell(metric)
            ours = ours_with_se(cell.ours, cell.se) if cell else "not in these results"
            delta = format_relative(relative_difference(cell.ours, value)) if cell else ""
            rows.append([table.title, paper.display_name(row.group.estimator),
                         str(row.group.particles), paper.metric_label(metric), ours,
                         format_value(value), delta])
        parts += [markdown_table(["Reference", "Estimator", "N", "Metric", "ours \u00b1 SE",
                                  "published", "\u0394"], rows), ""]
    return "\n".join(parts)
