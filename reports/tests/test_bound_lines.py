"""The posterior Cramer-Rao bound as a line: dashed beneath the estimators in the sweep figures,
and in the error-over-time figure without changing the estimators' line styles."""

import math
import tempfile
import unittest
from pathlib import Path

from fixture import FixtureSpec, make_results_folder
from phdslam_reports.figures.bound_line import BOUND_LINE_STYLE
from phdslam_reports.figures.metrics_over_time import collect_series, plot_metrics_over_time
from phdslam_reports.figures.sensitivity import plot_sensitivity
from phdslam_reports.figures.sweep_lines import plot_sweep_lines
from phdslam_reports.paper import PaperValues
from phdslam_reports.report import ReportBuilder, ReportOptions
from phdslam_reports.results import Group, ResultsFolder
from phdslam_reports.sweep_table import SweepRow, SweepTable

GROUPS = (("phd3", 10), ("oracle", 10), ("pcrb", 1))
SCALES = {"oracle": 0.8, "pcrb": 0.05}


def lines_by_label(ax) -> dict:
    return {line.get_label(): line for line in ax.get_lines()
            if not line.get_label().startswith("_")}


def estimator_lines(ax) -> dict:
    """The data line of each error-bar curve (an estimator), by its legend label."""
    return {c.get_label(): c.lines[0] for c in ax.containers}


class SensitivityBoundTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        root = Path(cls.tmp.name)
        cls.folders = [ResultsFolder(make_results_folder(root / f"pd{pd}", FixtureSpec(
            steps=20, pd=pd, groups=GROUPS, error_scale=SCALES))) for pd in (0.7, 0.9)]
        builder = ReportBuilder(cls.folders, root / "report", PaperValues.load(),
                                ReportOptions())
        cls.points, _ = builder.sweep_points()
        cls.section = builder.sensitivity_section()
        cls.fig = plot_sensitivity(cls.points, PaperValues.load().display_name)
        cls.gospa_ax, cls.rmse_ax = cls.fig.axes[:2]

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_the_bound_is_a_dashed_line_of_its_rmse_at_each_pd(self):
        line = lines_by_label(self.rmse_ax)["PCRB filtering bound"]
        self.assertEqual(line.get_linestyle(), BOUND_LINE_STYLE)
        self.assertEqual(list(line.get_xdata()), [0.7, 0.9])
        expected = [float(f.summary_row(Group("pcrb", 1))["pos_rmse_m"]) for f in self.folders]
        for drawn, value in zip(line.get_ydata(), expected):
            self.assertTrue(math.isclose(drawn, value), (drawn, value))

    def test_the_bound_lies_beneath_the_estimators_and_is_labelled_a_bound(self):
        bound = lines_by_label(self.rmse_ax)["PCRB filtering bound"]
        estimators = estimator_lines(self.rmse_ax)
        self.assertEqual(sorted(estimators), ["Oracle, N = 10", "PHD 3.0, N = 10"])
        estimators = list(estimators.values())
        self.assertTrue(all(line.get_zorder() > bound.get_zorder() for line in estimators))
        # one particle count among the estimators: solid, whatever the bound's N
        self.assertEqual({line.get_linestyle() for line in estimators}, {"-"})
        legend = [t.get_text() for t in self.rmse_ax.get_legend().get_texts()]
        self.assertIn("PCRB filtering bound", legend)
        self.assertNotIn("PCRB filtering bound, N = 1", legend)

    def test_no_bound_line_in_the_gospa_panel(self):
        self.assertFalse(any("bound" in label for label in lines_by_label(self.gospa_ax)))

    def test_the_caption_says_the_bound_is_drawn(self):
        self.assertIn("dashed: the posterior Cram\u00e9r-Rao bound", self.section.body)

    def test_without_a_bound_no_dashed_bound_line(self):
        points = [p for p in self.points if p.estimator != "pcrb"]
        fig = plot_sensitivity(points)
        self.assertEqual(lines_by_label(fig.axes[1]), {})
        self.assertEqual(len(estimator_lines(fig.axes[1])), 2)


class SweepLinesBoundTest(unittest.TestCase):
    def test_a_one_parameter_sweep_draws_the_bound_dashed_under_the_estimators(self):
        rows = []
        for i, robot in enumerate(("1", "2", "3")):
            rows.append(SweepRow((robot,), "oracle", 10,
                                 {"pos_rmse_m": 1.0 + i, "gospa_mean_m": 2.0}))
            rows.append(SweepRow((robot,), "pcrb", 1, {"pos_rmse_m": 0.1 * (i + 1)}))
        table = SweepTable(Path("/tmp/robots"), ("robot",), (("1", "2", "3"),), tuple(rows))
        fig = plot_sweep_lines(table)
        lines = lines_by_label(fig.axes[1])
        bound = lines["pcrb (bound)"]
        self.assertEqual(bound.get_linestyle(), BOUND_LINE_STYLE)
        self.assertEqual([round(v, 9) for v in bound.get_ydata()], [0.1, 0.2, 0.3])
        oracle = estimator_lines(fig.axes[1])["oracle, N = 10"]
        self.assertGreater(oracle.get_zorder(), bound.get_zorder())
        self.assertEqual(oracle.get_linestyle(), "-")
        self.assertNotIn("pcrb (bound)", lines_by_label(fig.axes[0]))


class MetricsOverTimeBoundTest(unittest.TestCase):
    def test_the_bounds_n_does_not_change_the_estimators_line_style(self):
        with tempfile.TemporaryDirectory() as tmp:
            folder = ResultsFolder(make_results_folder(Path(tmp) / "r", FixtureSpec(
                steps=20, groups=(("phd3", 10), ("pcrb", 1)), error_scale={"pcrb": 0.1})))
            fig = plot_metrics_over_time([collect_series(folder, g) for g in folder.groups()])
        lines = lines_by_label(fig.axes[0])
        self.assertEqual(lines["phd3, N = 10 (3 runs)"].get_linestyle(), "-")
        self.assertIn("pcrb (bound, 3 seeds)", lines)


if __name__ == "__main__":
    unittest.main()
