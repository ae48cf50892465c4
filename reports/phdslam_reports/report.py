"""Builds the HTML report of one or more results folders: sections, figures, tables."""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Sequence

import numpy as np

from .authors_comparison import MARGIN, METRICS, authors_rows
from .comparison import (
    OPTIONAL_METRICS,
    Comparison,
    compare,
    format_relative,
    format_value,
    paper_sources,
    secondary_references,
)
from .bound_efficiency import cell as efficiency_cell
from .bound_efficiency import BOUNDS, efficiency_rows, read_batch_estimators, read_runs, row_name
from .csv_table import ResultsFormatError
from .figures.filter_vs_smoother import (
    ceiling_comparison,
    ceiling_sentence,
    plot_filter_vs_smoothers,
)
from .figures.glmb_paper import plot_mean_std_per_rate, plot_rmse_over_time
from .figures.map_scaling import map_scaling_ratios, plot_map_scaling
from .figures.metrics_over_time import BOUND_ESTIMATORS, collect_series, plot_metrics_over_time
from .figures.nees import nees_series, plot_nees
from .figures.nis import nis_series, plot_nis
from .figures.parent_weights import (
    LOG_WEIGHT_RANGE,
    parent_weights_data,
    plot_parent_weights,
    pose_error,
)
from .figures.particle_paths import MAX_PANELS, ParticlePanel, plot_particle_paths
from .figures.scaling import plot_scaling, scaling_fits
from .figures.sensitivity import (
    CLUTTER_COLUMNS,
    PD_COLUMNS,
    SweepPoint,
    first_column,
    plot_sensitivity,
    points_from_table,
)
from .figures.sweep_heat_map import plot_sweep_heat_maps
from .figures.sweep_lines import plot_sweep_lines
from .figures.trajectory_map import (
    TrajectoryPanel,
    gps_in_span,
    has_true_trajectory,
    plot_trajectory_maps,
)
from .glmb_paper import ClutterPoint, MeanStd, glmb_points, map_ospa_cutoff
from .html_page import Section, escape, figure_html, note_html, render_page, table_html
from .paper import PaperValues
from .results import (
    GPS_FILE,
    MAP_SCALING_COLUMNS,
    MAP_SCALING_FILE,
    PARENT_WEIGHTS_FILE,
    PARENT_WEIGHTS_META_FILE,
    SCALING_COLUMNS,
    SCALING_FILE,
    SWEEP_FILE,
    TRUTH_FOLDER,
    Group,
    ResultsFolder,
)
from .smoother_posterior import posterior_gaps, posterior_sentence
from .stats import nan_mean, relative_difference, stack_ragged, standard_error_of_values
from .style import save_figure
from .sweep_table import SweepTable, read_sweep_table, sweep_point_of, sweep_root_of
from .table_efficiency import folder_efficiencies
from .tables_shared import matched_paper_tables, ours_with_se, paper_table_rows

#: Estimators whose pose covariances are the Ceres batch smoother's marginals: the consistency
#: reference the particle filters' NEES is read against.
REFERENCE_SMOOTHER = "smoother-"

BOUND_CAPTION = (" Position RMSE, dashed: the posterior Cram\u00e9r-Rao bound at each point (a "
                 "bound, not an estimator; docs/algorithms/pcrb.md).")

FOLDER_SECTIONS = ("summary", "paper-tables", "efficiency", "authors", "fig1", "fig2", "fig3",
                   "smoothers",
                   "nees", "scaling", "map-scaling", "parent-weights")
"""Section ids of each results folder (prefixed by ``d<index>-`` when there are several)."""


@dataclass
class ReportOptions:
    """Settings of one report."""

    title: str = "PHD-SLAM validation report"
    paper_table: str | None = None  # a table id, "none", or None for automatic matching


@dataclass
class Report:
    """The built report: the page, its sections and the PNG files written beside it."""

    html: str
    sections: list[Section]
    figure_files: list[Path] = field(default_factory=list)

    def section(self, section_id: str) -> Section:
        """The section with ``section_id`` (KeyError when absent)."""
        for s in self.sections:
            if s.id == section_id:
                return s
        raise KeyError(section_id)


class ReportBuilder:
    """Turns results folders into sections; figures go to ``out_dir``."""

    def __init__(self, folders: Sequence[ResultsFolder], out_dir: Path, paper: PaperValues,
                 options: ReportOptions) -> None:
        self.folders = list(folders)
        self.out_dir = Path(out_dir)
        self.paper = paper
        self.options = options
        self.figure_files: list[Path] = []

    # --- helpers ------------------------------------------------------------------------------

    def _prefix(self, index: int) -> str:
        return f"d{index}-" if len(self.folders) > 1 else ""

    def _figure(self, fig, file_name: str, caption: str) -> str:
        path = self.out_dir / file_name
        png = save_figure(fig, path)
        self.figure_files.append(path)
        return figure_html(png, file_name, caption, alt=caption)

    def _name(self, estimator: str) -> str:
        return self.paper.display_name(estimator)

    # --- sections of one folder ---------------------------------------------------------------

    def summary_section(self, sid: str, folder: ResultsFolder, comparison: Comparison) -> Section:
        """Summary table with the paper's values, standard errors and the 15 % flags."""
        title = "Summary and comparison with the paper"
        if folder.summary is None:
            return Section(sid, title, skipped_note=f"no summary.csv in {folder.path}")
        headers = ["Estimator", "N", "runs", "steps"] + [
            self.paper.metric_label(m) for m in comparison.metrics]
        rows = []
        flagged = 0
        for row in comparison.rows:
            cells = [(self._name(row.group.estimator), "name"), (str(row.group.particles), ""),
                     (str(row.runs), ""), (format_value(row.steps), "")]
            for cell in row.cells:
                css = "flag" if cell.flagged else ("ok" if cell.agrees else "")
                flagged += int(cell.flagged)
                second = ""
                if cell.paper is not None:
                    second = (f"paper {format_value(cell.paper)}, "
                              f"\u0394 {format_relative(cell.relative)}")
                cells.append((ours_with_se(cell.ours, cell.se), css, second))
            rows.append(cells)
        parts = [
            "<p>Our values: Monte Carlo means (position and heading RMSE pooled over every step "
            "of every run, as in the paper) \u00b1 their Monte Carlo standard error (GOSPA: "
            "std / \u221aruns; the other metrics: spread of the per-run values in runs.csv / "
            "\u221aruns). Second line: the paper's value and \u0394 = (ours \u2212 paper) / paper. "
            "Red cells differ from the paper by more than 15 %; green cells are within 15 %. A time "
            "per step is red only when it is more than 15 % slower than the paper's: a faster time "
            "is no deviation (the paper's times are MATLAB + C on another machine) and is left "
            "uncoloured.</p>",
            table_html(headers, rows),
            f"<p class=\"meta\">{flagged} cell(s) flagged.</p>",
        ]
        if any(m in comparison.metrics for m in OPTIONAL_METRICS):
            parts.insert(1, (
                "<p>DA true-positive / true-negative rates: pooled over every scored measurement "
                "of every run (summary.csv); \u2014 where the data association is not scored "
                "(e.g. PHD 1.0, odometry). The paper's rates (its data-association accuracy "
                "paragraph) state no particle count and stand beside every N.</p>"))
        parts += [note_html(n) for n in comparison.notes]
        tables = paper_sources(self.paper, comparison)
        for table in tables:
            parts.append(f"<p class=\"meta\">Paper values: {escape(table.title)}; source: "
                         f"{escape(table.source)}. {escape(table.notes)}</p>")
        if not tables:
            parts.append(note_html(
                f"No published table matches scenario '{folder.scenario_name}': paper columns "
                "are empty."))
        secondary = secondary_references(folder, self.paper, comparison)
        if secondary:
            sec_rows = []
            absent_listed: set[tuple[str, str, str]] = set()
            for table, row, metric, value in secondary:
                cell = row.cell(metric)
                if cell is None:
                    key = (table.id, row.group.estimator, metric)
                    if key in absent_listed:
                        continue
                    absent_listed.add(key)
                ours = ours_with_se(cell.ours, cell.se) if cell else "not in these results"
                rel = format_relative(relative_difference(cell.ours, value)) if cell else ""
                sec_rows.append([(table.title, "name"), (self._name(row.group.estimator), "name"),
                                 (str(row.group.particles), ""),
                                 (self.paper.metric_label(metric), "name"), (ours, ""),
                                 (format_value(value), ""), (rel, "")])
            parts.append("<h3>Other published numbers</h3>")
            parts.append(table_html(["Reference", "Estimator", "N", "Metric", "ours \u00b1 SE",
                                     "published", "\u0394"], sec_rows))
            sources = {t.id: t for t, *_ in secondary}
            parts += [f"<p class=\"meta\">{escape(t.title)}: {escape(t.source)}. "
                      f"{escape(t.notes)}</p>" for t in sources.values()]
        return Section(sid, title, body="\n".join(parts))

    def paper_tables_section(self, sid: str, folder: ResultsFolder,
                             comparison: Comparison) -> Section:
        """Tables I/II/III in the paper's layout, when the results hold their configuration."""
        title = "Tables I / II / III in the paper's layout"
        tables = matched_paper_tables(folder, self.paper, comparison)
        if not tables:
            return Section(sid, title, skipped_note=(
                "these results do not hold the configuration of Table I, II or III "
                "(same scenario, 4000 steps, pD and clutter rate of the paper, and the paper's "
                "filters and particle counts)"))
        parts = ["<p>Each cell: ours \u00b1 SE (paper); \u26a0 marks a difference beyond "
                 "15 % (a time per step only when it is slower than the paper's).</p>"]
        efficiencies = folder_efficiencies(folder)
        if efficiencies is not None:
            parts.append(note_html(
                "The bound rows hold the posterior Cramér-Rao bound, not an estimator's error: "
                "they are no result to rank. Efficiency = RMSE / bound on the same seeds "
                "\u00b1 delta-method Monte Carlo SE; filters against pcrb, smoothers against "
                "pcrb-smoother. The estimators the paper lacks follow its rows, with (\u2014)."))
        for table in tables:
            headers, rows = paper_table_rows(table, comparison, self.paper, efficiencies)
            parts.append(f"<h3>{escape(table.title)}</h3>")
            parts.append(table_html(headers, [[(c, "name" if i < 1 else "") for i, c in
                                               enumerate(r)] for r in rows]))
            if table.notes:
                parts.append(f"<p class=\"meta\">{escape(table.notes)}</p>")
        return Section(sid, title, body="\n".join(parts))

    def efficiency_section(self, sid: str, folder: ResultsFolder) -> Section:
        """Each estimator's RMSE over the posterior Cramer-Rao bounds of the same seeds, when the
        folder holds the bound rows (docs/algorithms/pcrb.md section 6)."""
        title = "Efficiency against the posterior Cramér-Rao bounds"
        if not (folder.path / "runs.csv").is_file():
            return Section(sid, title, skipped_note=f"no runs.csv in {folder.path}")
        rows = efficiency_rows(read_runs(folder.path), read_batch_estimators(folder.path))
        if not any(e["bound"] for e in rows):
            return Section(sid, title, skipped_note="no pcrb or pcrb-smoother rows in runs.csv")
        headers = ["estimator", "N", "runs", "position RMSE (m)", "/ pcrb", "/ pcrb-smoother",
                   "heading RMSE (deg)", "/ pcrb", "/ pcrb-smoother"]
        body_rows = []
        for e in rows:
            name = row_name(self._name(e["estimator"]), e["estimator"])
            cells = [name, str(e["particles"]), str(e["runs"])]
            for label in ("position", "heading"):
                cells += [efficiency_cell(e[f"{label}_rmse"]),
                          efficiency_cell(e.get(f"{label}_ratio_pcrb")),
                          efficiency_cell(e.get(f"{label}_ratio_pcrb-smoother"))]
            body_rows.append([(c, "") for c in cells])
        note = note_html(
            "Bound rows hold the bound, not an error. Efficiency = RMSE / bound on the same seeds "
            "± delta-method Monte Carlo SE; filters against pcrb, smoothers against "
            "pcrb-smoother; ⚠ below: more than 2 SE under 1.")
        return Section(sid, title, body=table_html(headers, body_rows) + note)

    def authors_section(self, sid: str, folder: ResultsFolder) -> Section:
        """phdslam against the authors' release on the same seeds (authors_comparison.py)."""
        title = "Against the authors' implementation"
        rows = authors_rows(folder)
        if not rows:
            return Section(sid, title, skipped_note=(
                "no authors-<variant> runs (reference/authors/) beside phdslam's <variant> or "
                "<variant>-replay on two or more common seeds"))
        labels = dict(METRICS)

        def p_text(p: float) -> str:
            if not math.isfinite(p):
                return "\u2014"
            return "< 1e-4" if p < 1e-4 else format_value(p, 2)

        def pct(x: float) -> str:
            return f"{x:+.2f}" if abs(x) >= 0.1 else f"{x:+.2g}"

        cells = [[(self._name(r.ours.removesuffix("-replay")), ""), (r.draws, ""),
                  (str(r.particles), ""), (labels[r.metric], ""), (str(r.n), ""),
                  (format_value(r.mean_authors), ""), (format_value(r.mean_ours), ""),
                  (f"{pct(r.diff_pct)} %", ""),
                  (f"[{pct(r.ci_low_pct)}, {pct(r.ci_high_pct)}] %", ""),
                  ("equivalent" if r.equivalent else "not shown", ""),
                  (p_text(r.p_wilcoxon), ""), (p_text(r.p_ttest), "")] for r in rows]
        body = ("<p>Paired by seed over the seeds both have: the difference is ours \u2212 the "
                "authors', in % of the authors' mean, with its 90 % t interval; "
                f"\u00b1{100 * MARGIN:g} %: the two-one-sided test of equivalence (\u03b1 = "
                "0.05; <code>ci/equivalence.py</code>); two-sided Wilcoxon signed-rank and paired "
                "t p-values. With its own random draws phdslam's filter is a different random "
                "sample of the same algorithm; replaying the authors' recorded draws it should "
                "repeat their run up to rounding.</p>"
                + table_html(["phdslam", "random draws", "N", "metric", "seeds",
                              "authors' mean", "phdslam mean", "difference", "90 % interval",
                              f"\u00b1{100 * MARGIN:g} %", "Wilcoxon p", "paired t p"], cells))
        return Section(sid, title, body=body)

    def trajectory_panels(self, folder: ResultsFolder) -> list[TrajectoryPanel]:
        """Fig. 1 panels: one run per estimator (its largest N, its first seed).

        A run without a true trajectory gets its seed's GPS fixes (truth/seed-<s>/gps.csv) when
        the folder has them (real data with GPS: the paper's Fig. 4).
        """
        chosen: dict[str, tuple[Group, int]] = {}
        for group in folder.groups():
            if group.estimator in BOUND_ESTIMATORS:
                continue  # a bound's trajectory and map are the truth: nothing to draw
            seeds = folder.seeds(group)
            if seeds and (group.estimator not in chosen
                          or group.particles > chosen[group.estimator][0].particles):
                chosen[group.estimator] = (group, seeds[0])
        panels = []
        for g, seed in chosen.values():
            steps = folder.steps(g, seed)
            panels.append(TrajectoryPanel(
                title=f"{self._name(g.estimator)}, N = {g.particles}, seed {seed}",
                estimator=g.estimator, steps=steps, estimated_map=folder.run_map(g, seed),
                truth_map=folder.truth_map,
                gps=None if has_true_trajectory(steps) else folder.gps(seed)))
        return panels

    def trajectory_section(self, sid: str, prefix: str, folder: ResultsFolder) -> Section:
        """Fig. 1 analogue: one run per estimator (its largest N, its first seed)."""
        title = "Fig. 1 analogue: trajectory and map"
        panels = self.trajectory_panels(folder)
        if not panels:
            return Section(sid, title, skipped_note="no run folder with steps.csv")
        notes = []
        for panel in panels:
            notes += undrawn_notes(panel)
            if panel.gps is not None:
                drawn = gps_in_span(panel.gps, panel.steps.num("t"))[0].size
                notes.append(f"{panel.title}: {drawn} of the {panel.gps.rows} GPS fixes in "
                             f"{TRUTH_FOLDER}/{panel.gps.path.parent.name}/{GPS_FILE} lie in "
                             "the run's time span and are drawn.")
            elif not has_true_trajectory(panel.steps):
                notes.append(f"{panel.title}: no true trajectory and no {TRUTH_FOLDER}/seed-*/"
                             f"{GPS_FILE} for this seed: only the estimate is drawn.")
        fig = plot_trajectory_maps(panels, [p.estimator for p in panels], self._name)
        folder.forget_steps()
        if any(p.gps is not None for p in panels):
            caption = ("GPS fixes (grey dots; the data have no true poses and no true map, as "
                       "in the paper's Fig. 4), estimate (dashed), true trajectory (black) where "
                       "known, and the final estimated map (circles, 3σ ellipses) of one run "
                       "per estimator.")
        else:
            caption = ("True trajectory (black), estimate (dashed), true landmarks (+) and the "
                       "final estimated map (circles, 3σ ellipses) of one run per "
                       "estimator.")
        body = self._figure(fig, f"{prefix}fig1-trajectory-map.png", caption)
        body += "".join(f"<p class=\"meta\">{escape(n)}</p>" for n in notes)
        if folder.truth_map is None:
            body += note_html("No truth_map.csv: true landmarks are not shown.")
        return Section(sid, title, body=body)

    def metrics_over_time_section(self, sid: str, prefix: str, folder: ResultsFolder) -> Section:
        """Fig. 2 analogue: per-step metrics pooled over seeds."""
        title = "Fig. 2 analogue: metrics over time"
        series = [collect_series(folder, g) for g in folder.groups()]
        fig = plot_metrics_over_time([s for s in series if s is not None], self._name,
                                     map_ospa_cutoff(folder))
        if fig is None:
            return Section(sid, title, skipped_note="no run folder with steps.csv")
        return Section(sid, title, body=self._figure(
            fig, f"{prefix}fig2-metrics-over-time.png",
            "Position error, heading error, ESS/N and map size per step: mean over runs and the "
            "5\u201395 % band over runs, per estimator and particle count."))

    def smoothers_section(self, sid: str, prefix: str, folder: ResultsFolder) -> Section:
        """A filter against the graph-optimisation smoothers: which one is the ceiling."""
        title = "Filter against the smoothers: the ceiling"
        comparison = ceiling_comparison(folder)
        posterior = posterior_sentence(posterior_gaps(folder), self._name)
        posterior_html = f"<p>{escape(posterior)}</p>" if posterior else ""
        needs = ("the folder needs a filter and a smoother (smoother-*, window*) with a finite "
                 "pooled position RMSE and a seed with steps.csv in common")
        if comparison is None:
            if posterior:  # the smoothers' scores without a filter to draw against
                return Section(sid, title, body=posterior_html + note_html(
                    f"No trajectory comparison: {needs}."))
            return Section(sid, title, skipped_note=needs)
        fig = plot_filter_vs_smoothers(folder, comparison, self._name)
        body = f"<p>{escape(ceiling_sentence(comparison, self._name))}</p>" + posterior_html
        body += self._figure(
            fig, f"{prefix}smoothers.png",
            f"Seed {comparison.seed}: position error per step (left) and the trajectories "
            "(right; truth in black, or the GPS fixes in grey) of the filter with the lowest "
            "pooled position RMSE (solid) and of every smoother (dashed). The pooled RMSE over "
            "all runs decides the ceiling.")
        return Section(sid, title, body=body)

    def particles_section(self, sid: str, prefix: str, folder: ResultsFolder) -> Section:
        """Fig. 3 analogue: particle trajectories from particles.csv files, one run (the first
        seed) per estimator and particle count."""
        title = "Fig. 3 analogue: particle trajectories"
        runs = first_run_of_each_group(folder.particle_files())
        if not runs:
            return Section(sid, title, skipped_note=(
                "no run folder holds particles.csv (step,particle,x,y,log_weight): run "
                "'phdslam run' with --particles-trace to write it"))
        shown = runs if len(runs) <= MAX_PANELS else sorted(
            sorted(runs, key=lambda r: -r[0].particles)[:MAX_PANELS],
            key=lambda r: (r[0], r[1]))
        panels = []
        for group, seed, path in shown:
            steps_path = folder.run_folder(group, seed) / "steps.csv"
            panels.append(ParticlePanel(
                title=f"{self._name(group.estimator)}, N = {group.particles}, seed {seed}",
                particles=folder.particles(path),
                steps=folder.steps(group, seed) if steps_path.is_file() else None))
        fig = plot_particle_paths(panels)
        resampled = any(p.steps is not None and np.nansum(p.steps.num("resampled")) > 0
                        for p in panels)
        folder.forget_steps()
        caption = ("Path of every particle (darker: larger final weight) and the true "
                   "trajectory (black), one run per estimator and particle count.")
        if resampled:
            caption += (" These runs resample (the paper's Fig. 3 does not): after a resampling "
                        "step a particle continues from the state it was copied from, so its "
                        "line can jump there.")
        body = self._figure(fig, f"{prefix}fig3-particle-paths.png", caption)
        if len(runs) > MAX_PANELS:
            body += note_html(f"{len(runs)} estimator and particle-count pairs hold "
                              f"particles.csv; the {MAX_PANELS} with the most particles are "
                              "shown.")
        return Section(sid, title, body=body)

    def _nees_series(self, folder: ResultsFolder, column: str) -> list:
        """Run-averaged series of one NEES column of steps.csv, per group that has it."""
        series = []
        for group in folder.groups():
            seeds = folder.seeds(group)
            if not seeds or not folder.steps(group, seeds[0]).has(column):
                continue
            matrix_rows = []
            for seed in seeds:
                steps = folder.steps(group, seed)
                if not steps.has(column):
                    raise ResultsFormatError(
                        f"{steps.path}: column '{column}' is missing (seed {seeds[0]} of the "
                        "same group has it)")
                matrix_rows.append(steps.num(column))
            folder.forget_steps()
            width = max(len(r) for r in matrix_rows)
            matrix = np.full((len(matrix_rows), width), np.nan)
            for i, r in enumerate(matrix_rows):
                matrix[i, : len(r)] = r
            s = nees_series(group.estimator, group.particles, matrix)
            if s is not None:
                series.append(s)
        return series

    def _nis_series(self, folder: ResultsFolder) -> list:
        """Pooled NIS series (nis_sum / nis_count of steps.csv) per group that reports any."""
        series = []
        for group in folder.groups():
            seeds = folder.seeds(group)
            if not seeds or not folder.steps(group, seeds[0]).has("nis_count"):
                continue
            sums, counts = [], []
            for seed in seeds:
                steps = folder.steps(group, seed)
                for column in ("nis_sum", "nis_count"):
                    if not steps.has(column):
                        raise ResultsFormatError(
                            f"{steps.path}: column '{column}' is missing (seed {seeds[0]} of "
                            "the same group has it)")
                sums.append(steps.num("nis_sum"))
                counts.append(steps.num("nis_count"))
            folder.forget_steps()
            s = nis_series(group.estimator, group.particles, stack_ragged(sums),
                           stack_ragged(counts))
            if s is not None:
                series.append(s)
        return series

    def _nis_table(self, series: list) -> str:
        rows = [[(self._name(s.estimator), "name"), (str(s.particles), ""), (str(s.runs), ""),
                 (format_value(s.pooled_mean), ""), (format_value(s.median), ""),
                 (f"{100 * s.inside:.1f} %", "")]
                for s in series]
        return table_html(["Estimator", "N", "runs", "NIS per measurement (pooled)",
                           "median over steps", "steps inside"], rows)

    def _nees_table(self, series: list) -> str:
        rows = [[(self._name(s.estimator) + (" (reference: batch marginals)"
                                             if s.estimator.startswith(REFERENCE_SMOOTHER) else ""),
                  "name"), (str(s.particles), ""), (str(s.runs), ""),
                 (f"[{s.low:.3f}, {s.high:.3f}]", ""),
                 (format_value(nan_mean(s.mean)), ""),
                 (format_value(s.median), ""),
                 (f"{100 * s.inside:.1f} %", ""),
                 (f"{100 * s.coverage:.1f} %" if np.isfinite(s.coverage) else "-", "")]
                for s in series]
        return table_html(["Estimator", "N", "runs", "95 % bounds", "mean NEES", "median",
                           "steps inside", "coverage"], rows)

    def nees_section(self, sid: str, prefix: str, folder: ResultsFolder) -> Section:
        """Run-averaged pose NEES with 95 % chi-square bounds: the particle-spread NEES ('nees'
        of steps.csv) and, when present, the Rao-Blackwellised one ('nees_rb')."""
        title = "Pose NEES and NIS (consistency)"
        series = self._nees_series(folder, "nees")
        series_rb = self._nees_series(folder, "nees_rb")
        series_nis = self._nis_series(folder)
        if not series and not series_rb and not series_nis:
            return Section(sid, title, skipped_note="steps.csv has no 'nees' column")
        body = ("<p>Pose NEES averaged over runs at each step (steps where every run has a "
                "value). Bounds: chi2.ppf(0.025 and 0.975, 3 \u00d7 runs) / runs. Coverage: "
                "fraction of all steps of all runs whose NEES is at most chi2.ppf(0.95, 3), "
                "i.e. the true pose lies inside the 95 % ellipsoid (0.95 expected).</p>")
        if series:
            body += ("<h4>Particle-spread covariance</h4>" + self._nees_table(series)
                     + self._figure(plot_nees(series, self._name), f"{prefix}nees.png",
                                    "Run-averaged pose NEES and its two-sided 95 % chi-square "
                                    "bounds."))
        if series_rb:
            body += ("<h4>Rao-Blackwellised covariance (mixture of the particles' proposals)</h4>"
                     + self._nees_table(series_rb)
                     + self._figure(plot_nees(series_rb, self._name), f"{prefix}nees-rb.png",
                                    "Run-averaged Rao-Blackwellised pose NEES and its two-sided "
                                    "95 % chi-square bounds."))
        if series_nis:
            body += ("<h4>NIS of the associated measurements (no ground truth needed)</h4>"
                     "<p>At each step the runs' NIS sums and measurement counts C are pooled; "
                     "bounds chi2.ppf(0.025 and 0.975, 2C) / C (2 expected).</p>"
                     + self._nis_table(series_nis)
                     + self._figure(plot_nis(series_nis, self._name), f"{prefix}nis.png",
                                    "NIS per measurement pooled over runs, with its two-sided "
                                    "95 % chi-square band."))
        return Section(sid, title, body=body)

    def scaling_section(self, sid: str, prefix: str, folder: ResultsFolder) -> Section:
        """Log-log time per call against landmarks in view, from scaling.csv."""
        title = "Scaling with the number of landmarks in view"
        table = folder.optional_table(SCALING_FILE, SCALING_COLUMNS)
        if table is None:
            return Section(sid, title, skipped_note=f"no {SCALING_FILE} in the results folder")
        fig = plot_scaling(table, self._name)
        if fig is None:
            return Section(sid, title, skipped_note=f"{SCALING_FILE} has no rows")
        fits = scaling_fits(table)
        rows = [[(self._name(e), "name"),
                 (f"{f.exponent:.3f}" if f else "\u2014", ""),
                 (format_value(f.coefficient) if f else "\u2014", ""),
                 (str(f.points) if f else "\u2014", "")] for e, f in fits.items()]
        body = (table_html(["Estimator", "exponent b", "coefficient a (\u00b5s)", "points"], rows)
                + self._figure(fig, f"{prefix}scaling.png",
                               "Time per call against landmarks in view (log-log) with the "
                               "least-squares fit a \u00b7 n^b."))
        return Section(sid, title, body=body)

    def map_scaling_section(self, sid: str, prefix: str, folder: ResultsFolder) -> Section:
        """Time per step and map bytes against the size of the map, from map_scaling.csv."""
        title = "Cost against the size of the map"
        table = folder.optional_table(MAP_SCALING_FILE, MAP_SCALING_COLUMNS)
        if table is None:
            return Section(sid, title, skipped_note=(
                f"no {MAP_SCALING_FILE} in the results folder (written by "
                f"benchmarks/map_scaling_benchmark --csv=FILE)"))
        fig = plot_map_scaling(table)
        if fig is None:
            return Section(sid, title, skipped_note=f"{MAP_SCALING_FILE} has no rows")
        rows = [[(str(int(n)), ""), (str(int(m)), ""), (format_value(t), ""),
                 (format_value(b / 1e6), "")]
                for m, n, t, b in sorted(zip(table.num("landmarks"), table.num("particles"),
                                             table.num("ms_per_step"), table.num("map_bytes")),
                                         key=lambda r: (r[1], r[0]))]
        ratios = map_scaling_ratios(table)
        growth = "; ".join(f"N = {n}: \u00d7{r:.2f}" for n, r in ratios.items())
        body = ("<p>Time per step from the smallest to the largest map"
                + (f": {growth}." if growth else ": fewer than two map sizes per N.")
                + " Bytes: heap bytes held by all particles' maps after the last step, storage "
                "shared between particles counted once.</p>"
                + table_html(["N", "landmarks", "ms per step", "map MB"], rows)
                + self._figure(fig, f"{prefix}map-scaling.png",
                               "Time per step (left) and bytes of all particles' maps (right) "
                               "against the number of landmarks in the map, per particle "
                               "count N."))
        return Section(sid, title, body=body)

    def parent_weights_section(self, sid: str, prefix: str, folder: ResultsFolder) -> Section:
        """Lee, Clark & Salvi (2012) Fig. 4 analogue, from parent_weights.csv/.json."""
        title = ("Single-cluster vs RB-PHD parent weighting (Lee, Clark & Salvi 2012, "
                 "Fig. 4)")
        table = folder.parent_weights
        if table is None:
            return Section(sid, title, skipped_note=(
                f"no {PARENT_WEIGHTS_FILE} in the results folder (written by phdslam "
                "parent-weights --out DIR)"))
        meta = folder.parent_weights_meta
        data = parent_weights_data(table, meta)
        parts = []
        if meta is not None:
            where = "".join(f"{k} {meta[k]}, " for k in ("scenario", "seed") if k in meta)
            where += f"step {meta['step']}"
            spread = (f" (standard deviations scaled by {format_value(data.spread)})"
                      if data.spread is not None else "")
            parts.append(
                f"<p>{escape(where[:1].upper() + where[1:])}: "
                f"{data.parents} parent poses drawn from the predicted pose Gaussian{spread}, "
                f"{meta['measurements']} measurements, a predicted map of "
                f"{meta['map_components']} components.</p>")
        else:
            parts.append(note_html(
                f"No {PARENT_WEIGHTS_META_FILE}: the predicted mean, the previous pose and the "
                "true pose are not shown."))

        def pose_cells(pose: tuple[float, float, float]) -> list[tuple[str, str]]:
            cells = [(f"{pose[0]:.3f}", ""), (f"{pose[1]:.3f}", ""),
                     (f"{math.degrees(pose[2]):.2f}", "")]
            if data.true_pose is None:
                return cells + [("\u2014", ""), ("\u2014", "")]
            distance, heading = pose_error(pose, data.true_pose)
            return cells + [(f"{distance:.3f}", ""), (f"{heading:.2f}", "")]

        missed = data.missed_mass is not None
        rows = []
        for w in data.weightings:
            row = [(w.title, "name"), (f"{w.ess:.1f} of {data.parents}", ""),
                   (f"{float(np.max(w.weights)):.3g}", "")] + pose_cells(w.mean)
            if missed:
                row.append((f"{w.mean_missed_mass:.4g}", ""))
            rows.append(row)
        if data.predicted_mean is not None:
            rows.append([("predicted mean (before the scan)", "name"), ("\u2014", ""),
                         ("\u2014", "")] + pose_cells(data.predicted_mean)
                        + ([("\u2014", "")] if missed else []))
        headers = ["Weighting", "ESS = 1/\u03a3w\u00b2", "largest weight", "weighted mean x (m)",
                   "y (m)", "\u03b8 (deg)", "distance to true pose (m)", "heading error (deg)"]
        if missed:
            headers.append("weighted mean of \u03a3 pD w")
        parts.append(table_html(headers, rows))
        if data.true_pose is None:
            parts.append(note_html("No true pose (real data): distances are not available."))
        facts = [[("parents drawn", "name"), (str(data.parents), "")],
                 [("spread (scale of the draws' standard deviations)", "name"),
                  (format_value(data.spread) if data.spread is not None else "\u2014", "")]]
        if missed:
            low, high = float(np.min(data.missed_mass)), float(np.max(data.missed_mass))
            facts.append([("missed-detection mass \u03a3 pD w per parent, min\u2013max", "name"),
                          (f"{low:.4g}\u2013{high:.4g}", "")])
        gaps = [float(np.max(w.log_weights)) - float(np.min(w.log_weights))
                for w in data.weightings]
        if data.log_weights_in_file:
            facts.append([("log-weight range over the parents, single-cluster / RB-PHD (nats)",
                           "name"), (" / ".join(f"{g:.4g}" for g in gaps), "")])
        parts.append(table_html(["Draws", "value"], facts))
        colours = ("normalised log-weight (sc_log_weight, rb_log_weight)"
                   if data.log_weights_in_file else
                   "log of the normalised weight (no log-weight columns in the file)")
        caption = (
            "The same predicted state and map, one scan: parent poses drawn from the predicted "
            f"pose Gaussian, point area = normalised weight, colour = {colours} on one scale "
            f"for both weighting panels, clipped below at {LOG_WEIGHT_RANGE:g} nats under the "
            "largest; \u00d7 predicted mean, \u25c7 weighted mean of each weighting, \u2605 "
            "true pose (when known). "
            "The single-cluster likelihood keeps the missed-detection term exp(\u2212\u03a3 pD w), "
            "which penalises poses that put map mass in the field of view without detections; "
            "the RB-PHD-SLAM weighting (46) lacks it.")
        if missed:
            caption += (
                " Right: the missed-detection mass \u03a3 pD w of each parent (colour; area = "
                "RB-PHD weight): the single-cluster log-weight is the RB-PHD one minus it, up to "
                "a constant, so parents with the larger \u03a3 pD w are the ones it penalises.")
        parts.append(self._figure(plot_parent_weights(data), f"{prefix}parent-weights.png",
                                  caption))
        return Section(sid, title, body="\n".join(parts))

    # --- sections across folders --------------------------------------------------------------

    def sweep_points(self) -> tuple[list[SweepPoint], list[str]]:
        """Sensitivity points from summary/sweep columns or from each folder's config.json."""
        points: list[SweepPoint] = []
        notes: list[str] = []
        for folder in self.folders:
            options = folder.scenario_options
            pd = options.get("detection_probability", options.get("detection_probability_nominal"))
            clutter = options.get("clutter_rate")
            pd = float(pd) if isinstance(pd, (int, float)) else math.nan
            clutter = float(clutter) if isinstance(clutter, (int, float)) else math.nan
            sweep = folder.optional_table(SWEEP_FILE, ("estimator", "particles"))
            if sweep is not None:
                points += points_from_table(sweep, pd, clutter)
                continue
            summary = folder.summary
            if summary is None:
                continue
            if first_column(summary, PD_COLUMNS) or first_column(summary, CLUTTER_COLUMNS):
                points += points_from_table(summary, pd, clutter)
                continue
            if math.isnan(pd) and math.isnan(clutter):
                notes.append(f"{folder.path}: config.json states no detection probability or "
                             "clutter rate")
                continue
            for point in points_from_table(summary, pd, clutter):
                group = Group(point.estimator, point.particles)
                se = standard_error_of_values(
                    [float(r["pos_rmse_m"]) for r in folder.runs_rows(group)])
                points.append(SweepPoint(**{**point.__dict__, "pos_rmse_se": se}))
        return points, notes

    def sweep_tables(self) -> list[SweepTable]:
        """The sweep roots the folders belong to (or are), each once, in folder order."""
        tables: list[SweepTable] = []
        for folder in self.folders:
            root = folder.path if (folder.path / "sweep.json").is_file() else \
                sweep_root_of(folder.path)
            if root is None or any(t.root == root for t in tables):
                continue
            table = read_sweep_table(root)
            if table is not None:
                tables.append(table)
        return tables

    def general_sweep_figures(self, tables: list[SweepTable]) -> tuple[str, list[str]]:
        """Line plots of one-parameter sweeps and heat maps of two-parameter sweeps."""
        body, drawn = "", []
        for index, table in enumerate(tables):
            names = " \u00d7 ".join(table.parameters)
            if len(table.parameters) == 2:
                fig = plot_sweep_heat_maps(table, self._name)
                rows = "estimator" if "particles" in table.parameters else \
                    "estimator and particle count"
                caption = (f"Sweep over {names} ({table.root.name}): final-map GOSPA and "
                           f"position RMSE at every grid point, one row of panels per {rows}; "
                           f"rows {table.parameters[0]}, columns {table.parameters[1]}.")
                file_name = f"sweep{index + 1}-heat-map.png"
            else:
                fig = plot_sweep_lines(table, self._name)
                caption = (f"Sweep over {names} ({table.root.name}): final-map GOSPA (\u00b1 SE) "
                           f"and position RMSE against {names}.")
                if any(r.estimator in BOUNDS for r in table.rows):
                    caption += BOUND_CAPTION
                file_name = f"sweep{index + 1}-lines.png"
            if fig is None:
                body += note_html(f"{table.root}: a sweep over {len(table.parameters)} "
                                  "parameters is not drawn (one or two only)")
                continue
            body += self._figure(fig, file_name, caption)
            drawn.append(names)
        return body, drawn

    def sensitivity_section(self) -> Section:
        """Fig. 5 analogue (GOSPA and position RMSE against pD and clutter rate), and any other
        sweep: lines for one swept parameter, heat maps for two."""
        title = "Fig. 5 analogue: sensitivity to pD and clutter rate"
        general = [t for t in self.sweep_tables()
                   if len(t.parameters) != 1 or t.parameters[0] not in ("pd", "clutter_rate")]
        general_body, drawn = self.general_sweep_figures(general)
        if general:
            title = "Sensitivity: parameter sweeps"
        points, notes = self.sweep_points()
        fig = plot_sensitivity(points, self._name) if not general else None
        if fig is None and not general_body:
            return Section("sensitivity", title, skipped_note=(
                "no sweep: the results hold a single detection probability and clutter rate "
                "(give several results folders with different --pd / --clutter-rate, or a "
                "sweep.csv / summary.csv with pd or clutter_rate columns)"))
        body = general_body
        if fig is not None:
            caption = ("Final-map GOSPA and position RMSE (\u00b1 SE) against the detection "
                       "probability and the clutter rate.")
            if any(p.estimator in BOUNDS for p in points):
                caption += BOUND_CAPTION
            body += self._figure(fig, "fig5-sensitivity.png", caption)
            body += "".join(note_html(n) for n in notes)
        return Section("sensitivity", title, body=body)

    def _glmb_table(self, points: list[ClutterPoint]) -> str:
        def cell(v: MeanStd) -> str:
            if v.count == 0:
                return "\u2014"
            return f"{format_value(v.mean)} \u00b1 {format_value(v.std)}"

        rows = []
        for p in points:
            rows.append([(format_value(p.clutter_rate), ""), (self._name(p.group.estimator), "name"),
                         (str(p.group.particles), ""), (str(p.rmse.runs), "")]
                        + [(format_value(nan_mean(a)), "")
                           for a in (p.rmse.x, p.rmse.y, p.rmse.heading_deg)]
                        + [(cell(p.ospa), ""), (cell(p.step_ms), ""), (cell(p.false_landmarks), "")])
        return table_html(["clutter rate", "Estimator", "N", "runs", "RMSE x (m)", "RMSE y (m)",
                           "RMSE heading (deg)", "map OSPA (m)", "time per step (ms)",
                           "false landmarks (final map)"], rows)

    def _glmb_trajectories(self, points: list[ClutterPoint]) -> str:
        rates = sorted({p.clutter_rate for p in points})
        shown = [rates[0]] + ([rates[-1]] if len(rates) > 1 else [])
        panels = []
        for rate in shown:
            largest: dict[str, ClutterPoint] = {}
            for p in points:
                if p.clutter_rate == rate and (p.group.estimator not in largest or p.group.particles
                                               > largest[p.group.estimator].group.particles):
                    largest[p.group.estimator] = p
            for p in largest.values():
                seed = p.folder.seeds(p.group)[0]
                panels.append(TrajectoryPanel(
                    title=(f"{self._name(p.group.estimator)}, N = {p.group.particles}, clutter "
                           f"{rate:g}, seed {seed}"),
                    estimator=p.group.estimator, steps=p.folder.steps(p.group, seed),
                    estimated_map=p.folder.run_map(p.group, seed),
                    truth_map=p.folder.truth_map))
        fig = plot_trajectory_maps(panels, sorted({p.estimator for p in panels}), self._name)
        for p in points:
            p.folder.forget_steps()
        rates_text = " and ".join(f"{r:g}" for r in shown)
        return self._figure(fig, "glmb-trajectory-map.png",
                            f"Clutter rate {rates_text}: true trajectory (black), estimate "
                            "(dashed), true landmarks (+) and the final estimated map of one run "
                            "(the first seed) per estimator (the paper's Figs. 2-4, maps).")

    def glmb_section(self) -> Section | None:
        """The delta-GLMB-SLAM paper's figures, when the results hold scenario glmb-sim."""
        points = glmb_points(self.folders)
        if not points:
            return None
        cutoffs = sorted({map_ospa_cutoff(p.folder) for p in points if p.ospa.count > 0})
        cutoff = cutoffs[0] if len(cutoffs) == 1 else None
        parts = [
            "<p>Scenario glmb-sim (the simulation of Moratuwage, Adams &amp; Inostroza 2019). "
            "RMSE per step: \u221a(mean over runs of the squared error) in x, y and the wrapped "
            "heading; the table gives its mean over the steps. Map OSPA: the mean over the steps "
            "of each run's per-step map OSPA (p = 1, landmarks detected so far; "
            + (f"c = {cutoff:g} m" if cutoff is not None else "cut-offs differ between folders")
            + "), then mean \u00b1 std over runs. Time per step: every step of every run. False "
            "landmarks: the final map's estimates without a true landmark within c (optimal "
            "assignment), mean \u00b1 std over runs."
            "</p>",
            self._glmb_table(points),
        ]
        fig = plot_rmse_over_time(points, self._name)
        parts.append(self._figure(fig, "glmb-rmse-over-time.png",
                                  "RMSE in x, y and heading per step over the runs, one column "
                                  "per clutter rate (the paper's Figs. 2-4)."))
        if any(p.ospa.count > 0 for p in points):
            parts.append(self._figure(
                plot_mean_std_per_rate(points, self._name, cutoff), "glmb-ospa-time.png",
                "Map OSPA and time per step, mean \u00b1 std, against the clutter rate (the "
                "paper's Figs. 5 and 6)."))
        else:
            parts.append(note_html("steps.csv has no map_ospa_m (run with --map-ospa or the "
                                   "experiment key map_ospa): the OSPA figure is not drawn."))
        parts.append(self._glmb_trajectories(points))
        return Section("glmb-paper", "\u03b4-GLMB-SLAM paper (Moratuwage et al. 2019): RMSE, "
                       "OSPA, time per step, trajectories", body="\n".join(parts))

    # --- whole report -------------------------------------------------------------------------

    def folder_intro(self, folder: ResultsFolder) -> str:
        """A short description of a results folder from its config.json."""
        config = folder.config or {}
        options = folder.scenario_options
        shown = ", ".join(
            ([steps_text(options["steps"], folder)] if "steps" in options else [])
            + [f"{k} = {options[k]}" for k in
               ("detection_probability", "detection_probability_nominal", "clutter_rate")
               if k in options])
        counts = options.get("counts")
        if isinstance(counts, dict):  # real data (mrclam): what the steps are made of
            shown = ", ".join(x for x in (shown, counts_text(counts)) if x)
        seeds = config.get("seeds") or []
        program = config.get("program") or {}
        point = ", ".join(f"{name} = {value}" for name, value in sweep_point_of(folder.path))
        return (f"<p class=\"meta\">Results folder <code>{escape(folder.path)}</code>: scenario "
                f"<b>{escape(folder.scenario_name or 'unknown')}</b>"
                f"{' (' + escape(shown) + ')' if shown else ''}; "
                f"{'sweep point ' + escape(point) + '; ' if point else ''}"
                f"{len(seeds)} seed(s); estimators "
                f"{escape(', '.join(sorted((config.get('estimators') or {}).keys())) or '?')}; "
                f"experiment {escape(config.get('experiment', '?'))}; program "
                f"{escape(program.get('name', '?'))} {escape(program.get('version', ''))}.</p>")

    def build(self) -> Report:
        """Every section, the page, and the figure files."""
        sections: list[Section] = []
        intro = ["<p>Built from results files only (summary.csv, runs.csv, config.json and the "
                 "per-run files of each results folder).</p>"]
        for index, folder in enumerate(self.folders):
            prefix = self._prefix(index)
            level = 2
            if len(self.folders) > 1:
                sections.append(Section(f"d{index}", f"Results folder {index + 1}: "
                                        f"{folder.path.name}", body=self.folder_intro(folder)))
                level = 3
            else:
                intro.append(self.folder_intro(folder))
            comparison = compare(folder, self.paper, self.options.paper_table)
            built = [
                self.summary_section(f"{prefix}summary", folder, comparison),
                self.paper_tables_section(f"{prefix}paper-tables", folder, comparison),
                self.efficiency_section(f"{prefix}efficiency", folder),
                self.authors_section(f"{prefix}authors", folder),
                self.trajectory_section(f"{prefix}fig1", prefix, folder),
                self.metrics_over_time_section(f"{prefix}fig2", prefix, folder),
                self.particles_section(f"{prefix}fig3", prefix, folder),
                self.smoothers_section(f"{prefix}smoothers", prefix, folder),
                self.nees_section(f"{prefix}nees", prefix, folder),
                self.scaling_section(f"{prefix}scaling", prefix, folder),
                self.map_scaling_section(f"{prefix}map-scaling", prefix, folder),
                self.parent_weights_section(f"{prefix}parent-weights", prefix, folder),
            ]
            for s in built:
                s.level = level
            sections += built
        glmb = self.glmb_section()
        if glmb is not None:
            sections.append(glmb)
        sections.append(self.sensitivity_section())
        html = render_page(self.options.title, "\n".join(intro), sections)
        return Report(html=html, sections=sections, figure_files=self.figure_files)


def first_run_of_each_group(
        files: list[tuple[Group, int, Path]]) -> list[tuple[Group, int, Path]]:
    """The run of the smallest seed of each (estimator, N) among sorted particles.csv files."""
    first: dict[Group, tuple[Group, int, Path]] = {}
    for group, seed, path in files:
        first.setdefault(group, (group, seed, path))
    return list(first.values())


def steps_text(limit: object, folder: ResultsFolder) -> str:
    """The step limit of config.json in words: 0 (or none) is every step of the scenario, given
    with the steps per run of summary.csv when all its rows agree."""
    if isinstance(limit, (int, float)) and not isinstance(limit, bool) and limit > 0:
        return f"first {limit:g} steps"
    if isinstance(limit, (int, float)) and not isinstance(limit, bool) and limit == 0:
        summary = folder.summary
        per_run = set(summary.num("steps").tolist()) if summary is not None else set()
        if len(per_run) == 1 and math.isfinite(next(iter(per_run))):
            return f"all {next(iter(per_run)):g} steps"
        return "all steps"
    return f"steps = {limit}"


def counts_text(counts: dict) -> str:
    """The scenario's counts (config.json scenario.options.counts of real data) as a sentence."""
    def n(key: str) -> str:
        value = counts.get(key)
        return "?" if value is None else str(value)
    dropped = counts.get("non_landmarks_dropped")
    text = (f"{n('steps')} steps ({n('unscored_steps')} without truth: left out of the pose "
            f"metrics), {n('landmark_detections')} landmark detections, "
            f"{n('other_robot_detections')} of other robots and "
            f"{n('unknown_barcode_detections')} of unknown barcodes "
            f"({'dropped' if dropped else 'kept as clutter'})")
    if counts.get("images_skipped"):
        text += f", {n('images_skipped')} images outside the commands or the truth left out"
    return text


def build_report(results_dirs: Sequence[Path | str], out_dir: Path | str,
                 paper: PaperValues | None = None,
                 options: ReportOptions | None = None) -> Report:
    """Builds the report of ``results_dirs`` into ``out_dir`` (index.html and PNG files)."""
    out = Path(out_dir)
    folders = [ResultsFolder(p) for p in results_dirs]  # checks them before creating anything
    out.mkdir(parents=True, exist_ok=True)
    builder = ReportBuilder(folders, out, paper or PaperValues.load(), options or ReportOptions())
    report = builder.build()
    write_text_atomically(out / "index.html", report.html)
    return report


def write_text_atomically(path: Path, text: str) -> None:
    """Writes ``text`` to a temporary file beside ``path`` and renames it over ``path``, so that
    ``path`` is either the old file or the whole new one. Characters that UTF-8 cannot encode
    (the undecodable bytes of a non-UTF-8 path, held as surrogates) are written as escapes."""
    temporary = path.with_name(f".{path.name}.tmp-{os.getpid()}")
    try:
        with open(temporary, "w", encoding="utf-8", errors="backslashreplace") as stream:
            stream.write(text)
        os.replace(temporary, path)
    finally:
        if temporary.exists():
            temporary.unlink()


def undrawn_notes(panel: TrajectoryPanel) -> list[str]:
    """What of a Fig. 1 panel's run could not be drawn, and why (never an empty panel unnoted)."""
    notes = []
    if panel.steps.rows == 0:
        notes.append(f"{panel.title}: {panel.steps.path} holds only its header (no step): no "
                     "trajectory is drawn.")
    if panel.estimated_map is None:
        notes.append(f"{panel.title}: no {panel.steps.path.parent / 'map.csv'}: no estimated "
                     "map is drawn.")
    return notes
