"""The report's filter-against-smoothers section: which estimator is the ceiling."""

import math
import re
import tempfile
import unittest
from pathlib import Path

from fixture import FixtureSpec, make_results_folder
from phdslam_reports.figures.filter_vs_smoother import ceiling_comparison, is_smoother
from phdslam_reports.report import build_report
from phdslam_reports.results import ResultsFolder

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def build(root: Path, groups, error_scale, seeds=(1, 2)):
    results = make_results_folder(root / "results", FixtureSpec(
        groups=groups, error_scale=error_scale, steps=30, seeds=seeds))
    report = build_report([results], root / "report")
    return results, report


class CeilingTest(unittest.TestCase):
    """A filter, a good and a bad smoother and dead reckoning."""

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.results, cls.report = build(
            Path(cls.tmp.name),
            (("phd3", 1), ("phd3", 10), ("smoother-known", 1), ("smoother-unknown", 1),
             ("odometry", 1)),
            {"odometry": 0.05, "smoother-known": 0.2, "smoother-unknown": 8.0, "phd3": 1.0})
        cls.body = cls.report.section("smoothers").body

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_filter_is_the_best_online_estimator_and_not_dead_reckoning(self):
        comparison = ceiling_comparison(ResultsFolder(self.results))
        self.assertIsNotNone(comparison)
        # odometry has the lowest error of all here, but it is a floor, never the filter.
        self.assertEqual(comparison.filter.group.estimator, "phd3")
        self.assertEqual(comparison.filter.group.particles, 10)  # error scale 1 / sqrt(N)
        self.assertEqual([s.group.estimator for s in comparison.smoothers],
                         ["smoother-known", "smoother-unknown"])
        self.assertEqual(comparison.ceiling.group.estimator, "smoother-known")
        self.assertEqual(comparison.seed, 1)

    def test_pooled_rmse_is_the_summary_value(self):
        comparison = ceiling_comparison(ResultsFolder(self.results))
        folder = ResultsFolder(self.results)
        for c in [comparison.filter] + comparison.smoothers:
            row = folder.summary_row(c.group)
            self.assertTrue(math.isclose(c.pos_rmse_m, float(row["pos_rmse_m"])))
        self.assertLess(comparison.smoothers[0].pos_rmse_m, comparison.filter.pos_rmse_m)
        self.assertGreater(comparison.smoothers[1].pos_rmse_m, comparison.filter.pos_rmse_m)

    def test_section_names_the_ceiling_and_each_verdict(self):
        self.assertRegex(self.body, r"The ceiling is smoother-known \(N = 1\)")
        self.assertRegex(self.body, r"smoother-known: [0-9.]+ m, below the filter")
        self.assertRegex(self.body, r"smoother-unknown: [0-9.]+ m, not below the filter")
        self.assertNotIn("No smoother bounds the filter", self.body)

    def test_figure_is_written_and_embedded(self):
        names = [p.name for p in self.report.figure_files]
        self.assertIn("smoothers.png", names)
        path = next(p for p in self.report.figure_files if p.name == "smoothers.png")
        self.assertTrue(path.read_bytes().startswith(PNG_MAGIC))
        self.assertTrue(re.search(r'<img src="data:image/png;base64,', self.body))


class NoCeilingTest(unittest.TestCase):
    def test_smoother_worse_than_the_filter_is_not_called_a_ceiling(self):
        with tempfile.TemporaryDirectory() as tmp:
            _, report = build(Path(tmp), (("phd3", 10), ("smoother-unknown", 1)),
                              {"smoother-unknown": 10.0})
            body = report.section("smoothers").body
            self.assertIn("The ceiling is PHD", body)
            self.assertIn("No smoother bounds the filter here", body)

    def test_skipped_without_a_smoother(self):
        with tempfile.TemporaryDirectory() as tmp:
            _, report = build(Path(tmp), (("phd3", 10), ("odometry", 1)), {})
            section = report.section("smoothers")
            self.assertFalse(section.shown)
            self.assertIn("needs a filter and a smoother", section.render())

    def test_smoother_names(self):
        for name in ("smoother-known", "smoother-unknown", "smoother-filter", "window",
                     "window-known"):
            self.assertTrue(is_smoother(name), name)
        for name in ("phd3", "oracle", "odometry", "fastslam2"):
            self.assertFalse(is_smoother(name), name)


if __name__ == "__main__":
    unittest.main()
