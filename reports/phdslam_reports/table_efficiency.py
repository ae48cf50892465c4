"""The efficiency column of the paper-layout tables (Tables I / II / III).

When a results folder holds the rows of a posterior Cramer-Rao bound (docs/algorithms/pcrb.md
section 6), each estimator row of a paper-layout table gets its RMSE over the bound of the same
seeds ± the delta-method Monte Carlo SE (bound_efficiency.py): the filters against `pcrb`, the
graph-optimisation smoothers against `pcrb-smoother`. The bound rows follow the estimators',
labelled as bounds: they are no estimator, so they have no efficiency and no published value.
"""

from __future__ import annotations

from .bound_efficiency import efficiency_rows
from .bound_efficiency import cell as efficiency_cell
from .figures.filter_vs_smoother import is_smoother
from .results import ResultsFolder

EFFICIENCY_METRICS = {"pos_rmse_m": "position", "heading_rmse_deg": "heading"}
"""Summary metrics that have a bound, and their label in bound_efficiency's entries."""

BOUND_ROW_METRICS = tuple(EFFICIENCY_METRICS) + ("ms_per_step_mean", "ms_run_mean")
"""The metrics a bound's row shows (the bounds and their cost); its other cells are empty."""

Efficiencies = dict[tuple[str, int], dict]


def bound_of(estimator: str) -> str:
    """The bound an estimator is read against: the smoothing bound for the smoothers."""
    return "pcrb-smoother" if is_smoother(estimator) else "pcrb"


def folder_efficiencies(folder: ResultsFolder) -> Efficiencies | None:
    """bound_efficiency's entries by (estimator, N), or None when runs.csv has no bound row."""
    runs = folder.runs_table
    if runs is None:
        return None
    entries = efficiency_rows(runs.records())
    if not any(e["bound"] for e in entries):
        return None
    return {(e["estimator"], e["particles"]): e for e in entries}


def efficiency_headers(metrics: list[str]) -> list[str]:
    """One column per metric of the table that has a bound."""
    return [f"{EFFICIENCY_METRICS[m].capitalize()} efficiency (RMSE / bound)"
            for m in metrics if m in EFFICIENCY_METRICS]


def efficiency_position(metrics: list[str]) -> int:
    """The column index (after Filter and N) right after the table's last metric with a bound."""
    with_bound = [i for i, m in enumerate(metrics) if m in EFFICIENCY_METRICS]
    return 2 + (with_bound[-1] + 1 if with_bound else len(metrics))


def efficiency_cells(efficiencies: Efficiencies, estimator: str, particles: int,
                     metrics: list[str]) -> list[str]:
    """The efficiency cells of one row: "ratio ± SE", or an em dash (a bound row, no paired
    seeds)."""
    entry = efficiencies.get((estimator, particles), {})
    key = f"_ratio_{bound_of(estimator)}"
    return [efficiency_cell(entry.get(EFFICIENCY_METRICS[m] + key))
            for m in metrics if m in EFFICIENCY_METRICS]
