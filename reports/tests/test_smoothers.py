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
from phdslam_reports.smoother_posterior import posterior_gaps

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


def add_posterior_column(results: Path, scores: dict[str, dict[int, float]]) -> None:
    """Appends runs.csv's neg_log_posterior column: scores[estimator][seed], empty elsewhere."""
    path = results / "runs.csv"
    lines = path.read_text(encoding="utf-8").splitlines()
    header = lines[0].split(",")
    est, seed = header.index("estimator"), header.index("seed")
    out = [lines[0] + ",neg_log_posterior"]
    for line in lines[1:]:
        cells = line.split(",")
        value = scores.get(cells[est], {}).get(int(cells[seed]))
        out.append(line + "," + ("" if value is None else repr(value)))
    path.write_text("\n".join(out) + "\n", encoding="utf-8")


class PosteriorTest(unittest.TestCase):
    """The smoothers' negative log posterior, paired with the known association's."""

    def test_gaps_are_paired_over_the_common_seeds(self):
        with tempfile.TemporaryDirectory() as tmp:
            results, _ = build(Path(tmp), (("phd3", 10), ("smoother-known", 1),
                                           ("smoother-unknown", 1), ("smoother-filter", 1)),
                               {"smoother-unknown": 8.0}, seeds=(1, 2, 3))
            add_posterior_column(results, {
                "smoother-known": {1: -500.0, 2: -800.0, 3: -100.0},
                "smoother-unknown": {1: 3900.0, 2: 7000.0, 3: -200.0},
                "smoother-filter": {2: -700.0},  # one seed only
            })
            gaps = {g.estimator: g for g in posterior_gaps(ResultsFolder(results))}
            self.assertEqual(sorted(gaps), ["smoother-filter", "smoother-unknown"])
            unknown = gaps["smoother-unknown"]
            self.assertEqual(unknown.seeds, 3)
            self.assertAlmostEqual(unknown.mean_difference, (4400.0 + 7800.0 - 100.0) / 3)
            self.assertEqual(unknown.less_probable, 2)
            self.assertEqual((gaps["smoother-filter"].seeds,
                              gaps["smoother-filter"].less_probable), (1, 1))
            body = build_report([results], Path(tmp) / "again").section("smoothers").body
            self.assertRegex(body, r"smoother-unknown is \+4,033 nats on average over 3 seeds, "
                                   r"less probable on 2\.")
            self.assertIn("search, not the model, is what falls short", body)

    def test_scores_are_shown_without_a_filter_to_draw_against(self):
        with tempfile.TemporaryDirectory() as tmp:
            results, _ = build(Path(tmp), (("smoother-known", 1), ("smoother-unknown", 1),
                                           ("odometry", 1)), {})
            add_posterior_column(results, {"smoother-known": {1: 0.0, 2: 0.0},
                                           "smoother-unknown": {1: -5.0, 2: -7.0}})
            section = build_report([results], Path(tmp) / "r").section("smoothers")
            self.assertTrue(section.shown)
            self.assertIn("smoother-unknown is -6 nats on average over 2 seeds, less probable "
                          "on 0.", section.body)
            self.assertNotIn("falls short", section.body)
            self.assertIn("No trajectory comparison", section.body)

    def test_no_sentence_without_the_known_association_or_the_column(self):
        with tempfile.TemporaryDirectory() as tmp:
            results, report = build(Path(tmp), (("phd3", 10), ("smoother-known", 1),
                                                ("smoother-unknown", 1)), {})
            self.assertEqual(posterior_gaps(ResultsFolder(results)), [])  # no column
            self.assertNotIn("Negative log posterior", report.section("smoothers").body)
            add_posterior_column(results, {"smoother-unknown": {1: 10.0, 2: 20.0}})
            self.assertEqual(posterior_gaps(ResultsFolder(results)), [])  # no known scores


class NoCeilingTest(unittest.TestCase):
    def test_smoother_worse_than_the_filter_is_not_called_a_ceiling(self):
        with tempfile.TemporaryDirectory() as tmp:
            _, report = build(Path(tmp), (("phd3", 10), ("smoother-unknown", 1)),
                              {"smoother-unknown": 10.0})
            body = report.section("smoothers").body
            self.assertIn("The ceiling is PHD", body)
            self.assertIn("No smoother bounds the filter here", body)

    def test_a_bound_is_neither_the_filter_nor_the_ceiling(self):
        # The bounds have the lowest errors of all (error scale 0.01), but they hold a bound.
        with tempfile.TemporaryDirectory() as tmp:
            results, report = build(
                Path(tmp), (("phd3", 10), ("smoother-known", 1), ("pcrb", 1),
                            ("pcrb-smoother", 1)),
                {"smoother-known": 0.2, "pcrb": 0.01, "pcrb-smoother": 0.01})
            comparison = ceiling_comparison(ResultsFolder(results))
            body = report.section("smoothers").body
        self.assertEqual(comparison.filter.group.estimator, "phd3")
        self.assertEqual([s.group.estimator for s in comparison.smoothers], ["smoother-known"])
        self.assertEqual(comparison.ceiling.group.estimator, "smoother-known")
        self.assertRegex(body, r"The ceiling is smoother-known \(N = 1\)")
        self.assertNotIn("PCRB", body)

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
