"""GPS fixes in Fig. 1 for GPS-only data; the single-cluster vs RB-PHD parent-weights section."""

import base64
import json
import math
import re
import tempfile
import unittest
from pathlib import Path

from fixture import (  # first: puts reports/ on sys.path, checks the interpreter
    PARENT_WEIGHTS_SPREAD,
    FixtureSpec,
    make_results_folder,
    write_gps,
    write_parent_weights,
)

import numpy as np  # noqa: E402  (after fixture, which checks the interpreter)
from phdslam_reports.figures.parent_weights import (  # noqa: E402
    LOG_WEIGHT_RANGE,
    MISSED_MASS_TITLE,
    WEIGHTINGS,
    parent_weights_data,
    plot_parent_weights,
)
from phdslam_reports.figures.trajectory_map import plot_trajectory_maps  # noqa: E402
from phdslam_reports.paper import PaperValues  # noqa: E402
from phdslam_reports.report import ReportBuilder, ReportOptions, build_report  # noqa: E402
from phdslam_reports.results import ResultsFolder  # noqa: E402

import matplotlib.pyplot as plt  # noqa: E402  (after phdslam_reports.style chose Agg)

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def section_status(html: str, section_id: str) -> str | None:
    """'shown', 'skipped' or None when the page has no such section."""
    match = re.search(rf'<section id="{re.escape(section_id)}" data-status="(\w+)">', html)
    return match.group(1) if match else None


def embedded_pngs(html: str) -> list[bytes]:
    """The decoded base64 PNG images of an HTML fragment."""
    return [base64.b64decode(d) for d in
            re.findall(r'<img src="data:image/png;base64,([A-Za-z0-9+/=]+)"', html)]


def lines_labelled(fig, label: str) -> list:
    """Every Line2D of the figure's axes with this label."""
    return [line for ax in fig.axes for line in ax.get_lines() if line.get_label() == label]


def legend_texts(fig) -> set[str]:
    """The texts of every axes legend of the figure."""
    return {t.get_text() for ax in fig.axes if ax.get_legend() is not None
            for t in ax.get_legend().get_texts()}


def parent_panels(fig) -> list:
    """The data panels of a parent-weights figure (colour bars left out)."""
    return [ax for ax in fig.axes if ax.get_label() != "<colorbar>"]


def colour_bars(fig) -> list:
    """The colour-bar axes of a figure."""
    return [ax for ax in fig.axes if ax.get_label() == "<colorbar>"]


def parent_scatter(ax, parents: int):
    """The scatter of the parents in a panel (the one collection with a value per parent)."""
    found = [c for c in ax.collections if c.get_array() is not None
             and len(c.get_array()) == parents]
    assert len(found) == 1, found
    return found[0]


def parent_figure(results: Path):
    """The data and the figure of the parent-weights section of a results folder."""
    folder = ResultsFolder(results)
    data = parent_weights_data(folder.parent_weights, folder.parent_weights_meta)
    return folder, data, plot_parent_weights(data)


def trajectory_figure(results: Path, out: Path):
    """The Fig. 1 panels of a results folder and their figure, as the report builds them."""
    folder = ResultsFolder(results)
    builder = ReportBuilder([folder], out, PaperValues.load(), ReportOptions())
    panels = builder.trajectory_panels(folder)
    return panels, plot_trajectory_maps(panels, [p.estimator for p in panels])


class GpsOnlyReportTest(unittest.TestCase):
    """Victoria-Park-like results: empty truth columns, truth/seed-<s>/gps.csv, no true map."""

    STEPS = 40

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        root = Path(cls.tmp.name)
        cls.results = make_results_folder(root / "vp", FixtureSpec(
            groups=(("phd3", 10), ("odometry", 1)), seeds=(1, 2), steps=cls.STEPS,
            scenario="victoria-park", gps_only=True))
        cls.out = root / "report"
        cls.report = build_report([cls.results], cls.out)
        cls.html = (cls.out / "index.html").read_text(encoding="utf-8")
        gps = np.loadtxt(cls.results / "truth" / "seed-1" / "gps.csv", delimiter=",",
                         skiprows=1, ndmin=2)
        cls.gps_total = gps.shape[0]
        cls.gps_in_span = gps[(gps[:, 0] >= 0) & (gps[:, 0] <= cls.STEPS - 1)]

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_fixture_has_no_truth(self):
        steps = (self.results / "runs" / "phd3-N10" / "seed-1" / "steps.csv").read_text()
        header = steps.splitlines()[0].split(",")
        first = steps.splitlines()[1].split(",")
        self.assertEqual(first[header.index("x_true")], "")
        self.assertFalse((self.results / "truth_map.csv").exists())
        self.assertGreater(self.gps_total, len(self.gps_in_span))  # some fixes after the run

    def test_fig1_is_shown_with_a_figure(self):
        self.assertEqual(section_status(self.html, "fig1"), "shown")
        body = self.report.section("fig1").body
        pngs = embedded_pngs(body)
        self.assertEqual(len(pngs), 1)
        self.assertTrue(pngs[0].startswith(PNG_MAGIC))
        self.assertEqual((self.out / "fig1-trajectory-map.png").read_bytes(), pngs[0])
        self.assertIn("GPS fixes (grey dots", body)
        self.assertIn("paper&#x27;s Fig. 4", body)
        self.assertIn(f"PHD 3.0, N = 10, seed 1: {len(self.gps_in_span)} of the "
                      f"{self.gps_total} GPS fixes in truth/seed-1/gps.csv", body)

    def test_gps_is_drawn_in_every_panel(self):
        panels, fig = trajectory_figure(self.results, Path(self.tmp.name) / "unused")
        try:
            self.assertEqual([p.estimator for p in panels], ["odometry", "phd3"])
            self.assertTrue(all(p.gps is not None for p in panels))
            gps_lines = lines_labelled(fig, "GPS")
            self.assertEqual(len(gps_lines), 2)  # one per panel
            for line in gps_lines:
                self.assertEqual(line.get_linestyle(), "None")  # dots: outages stay gaps
                np.testing.assert_allclose(line.get_xdata(), self.gps_in_span[:, 1])
                np.testing.assert_allclose(line.get_ydata(), self.gps_in_span[:, 2])
            self.assertIn("GPS", legend_texts(fig))
            self.assertNotIn("true trajectory", legend_texts(fig))
            self.assertNotIn("true landmarks", legend_texts(fig))
            # the estimate is drawn above the GPS fixes
            estimate = lines_labelled(fig, "phd3 estimate")[0]
            self.assertGreater(estimate.get_zorder(), gps_lines[0].get_zorder())
        finally:
            plt.close(fig)

    def test_other_sections_cope_with_missing_truth(self):
        self.assertEqual(section_status(self.html, "fig2"), "shown")
        self.assertEqual(section_status(self.html, "summary"), "shown")


class GpsIgnoredWithTruthTest(unittest.TestCase):
    """Synthetic data keep their Fig. 1: a gps.csv beside true poses is not drawn."""

    def test_no_gps_artist_when_the_run_has_a_true_trajectory(self):
        with tempfile.TemporaryDirectory() as tmp:
            results = make_results_folder(Path(tmp) / "r", FixtureSpec(
                groups=(("phd3", 10),), seeds=(1,), steps=20))
            write_gps(results / "truth" / "seed-1" / "gps.csv", 20, np.random.default_rng(1))
            panels, fig = trajectory_figure(results, Path(tmp) / "out")
            try:
                self.assertIsNone(panels[0].gps)
                self.assertEqual(lines_labelled(fig, "GPS"), [])
                self.assertIn("true trajectory", legend_texts(fig))
            finally:
                plt.close(fig)
            body = build_report([results], Path(tmp) / "out").section("fig1").body
            self.assertIn("True trajectory (black)", body)
            self.assertNotIn("GPS", body)


class ParentWeightsReportTest(unittest.TestCase):
    """parent_weights.csv/.json at the root of a results folder give the parent-weights section."""

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        root = Path(cls.tmp.name)
        cls.results = make_results_folder(root / "r", FixtureSpec(
            groups=(("phd3", 10),), seeds=(1, 2), steps=12, parent_weights=True))
        cls.out = root / "report"
        cls.report = build_report([cls.results], cls.out)
        cls.html = (cls.out / "index.html").read_text(encoding="utf-8")
        cls.body = cls.report.section("parent-weights").body
        cls.csv = np.loadtxt(cls.results / "parent_weights.csv", delimiter=",", skiprows=1)
        cls.meta = json.loads((cls.results / "parent_weights.json").read_text())

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_section_is_shown_with_an_embedded_png(self):
        self.assertEqual(section_status(self.html, "parent-weights"), "shown")
        self.assertIn("Single-cluster vs RB-PHD parent weighting (Lee, Clark &amp; Salvi 2012, "
                      "Fig. 4)", self.html)
        pngs = embedded_pngs(self.body)
        self.assertEqual(len(pngs), 1)
        self.assertTrue(pngs[0].startswith(PNG_MAGIC))
        self.assertEqual((self.out / "parent-weights.png").read_bytes(), pngs[0])
        self.assertIn("missed-detection term", self.body)
        self.assertIn("Scenario paper-synthetic, seed 1, step 100: 40 parent poses", self.body)

    def test_ess_and_weighted_means_match_hand_computation(self):
        x, y, theta = self.csv[:, 1], self.csv[:, 2], self.csv[:, 3]
        truth = self.meta["true_pose"]
        distances = []
        for column in (4, 5):  # sc_weight, rb_weight
            w = self.csv[:, column]
            self.assertIn(f"{1 / np.sum(w ** 2):.1f} of 40", self.body)
            mx, my = np.sum(w * x), np.sum(w * y)
            heading = math.atan2(np.sum(w * np.sin(theta)), np.sum(w * np.cos(theta)))
            distance = math.hypot(mx - truth[0], my - truth[1])
            distances.append(distance)
            self.assertIn(f"<td>{mx:.3f}</td><td>{my:.3f}</td>"
                          f"<td>{math.degrees(heading):.2f}</td><td>{distance:.3f}</td>",
                          self.body)
        # the fixture's single-cluster weights are the more peaked around the true pose
        self.assertLess(distances[0], distances[1])
        predicted = self.meta["predicted_mean"]
        self.assertIn(f"{math.hypot(predicted[0] - truth[0], predicted[1] - truth[1]):.3f}",
                      self.body)

    def test_missed_mass_range_weighted_means_and_spread_in_the_tables(self):
        missed = self.csv[:, 8]
        self.assertIn(f"<td>{missed.min():.4g}\u2013{missed.max():.4g}</td>", self.body)
        for column in (4, 5):  # the weighted mean of missed_mass under each weighting
            w = self.csv[:, column]
            self.assertIn(f"<td>{np.sum(w * missed):.4g}</td>", self.body)
        self.assertIn("weighted mean of \u03a3 pD w", self.body)
        self.assertIn(f"<td>{PARENT_WEIGHTS_SPREAD:g}</td>", self.body)
        self.assertIn(f"(standard deviations scaled by {PARENT_WEIGHTS_SPREAD:g})", self.body)
        # the fixture's penalty grows with the distance to the true pose: single-cluster favours
        # the parents with less missed mass
        self.assertLess(np.sum(self.csv[:, 4] * missed), np.sum(self.csv[:, 5] * missed))
        self.assertIn("the single-cluster log-weight is the RB-PHD one minus it", self.body)

    def test_figure_has_three_panels_with_shared_axes(self):
        folder, data, fig = parent_figure(self.results)
        try:
            panels = parent_panels(fig)
            self.assertEqual(len(panels), 3)
            for other in panels[1:]:
                self.assertTrue(panels[0].get_shared_x_axes().joined(panels[0], other))
                self.assertTrue(panels[0].get_shared_y_axes().joined(panels[0], other))
            for ax, (column, _, title) in zip(panels, WEIGHTINGS):
                w = folder.parent_weights.num(column)
                self.assertIn(title, ax.get_title())
                self.assertIn(f"ESS = 1/\u03a3w\u00b2 = {1 / np.sum(w ** 2):.1f} of 40",
                              ax.get_title())
            for ax in panels:
                texts = {t.get_text() for t in ax.get_legend().get_texts()}
                self.assertIn("true pose", texts)
                self.assertIn("predicted mean", texts)
            self.assertEqual(panels[2].get_title(), MISSED_MASS_TITLE)
            self.assertIn("the single-cluster penalty", panels[2].get_title())
        finally:
            plt.close(fig)

    def test_weighting_panels_share_one_log_weight_colour_scale(self):
        _, _, fig = parent_figure(self.results)
        try:
            panels = parent_panels(fig)
            scatters = [parent_scatter(ax, 40) for ax in panels[:2]]
            self.assertIs(scatters[0].norm, scatters[1].norm)
            norm = scatters[0].norm
            log_w = self.csv[:, 6:8]  # sc_log_weight, rb_log_weight
            self.assertAlmostEqual(norm.vmax, float(np.max(log_w)), places=8)
            self.assertAlmostEqual(norm.vmin, norm.vmax - LOG_WEIGHT_RANGE)
            for scatter, column in zip(scatters, (6, 7)):
                # the colours are the file's log-weights clipped below, the sizes the weights
                np.testing.assert_allclose(np.sort(scatter.get_array()),
                                           np.sort(np.maximum(self.csv[:, column], norm.vmin)))
                sizes = scatter.get_sizes()
                weights = self.csv[:, column - 2]
                self.assertAlmostEqual(float(np.max(sizes) - np.min(sizes)),
                                       170.0 * float(np.ptp(weights))
                                       / float(np.max(self.csv[:, 4:6])), places=6)
            labels = [bar.get_ylabel() for bar in colour_bars(fig)]
            self.assertEqual(len(labels), 2)
            self.assertTrue(any("log weight (nats)" in label for label in labels), labels)
            # the third panel has its own scale: the missed-detection mass
            missed = parent_scatter(panels[2], 40)
            self.assertIsNot(missed.norm, norm)
            np.testing.assert_allclose(np.sort(missed.get_array()), np.sort(self.csv[:, 8]))
            self.assertAlmostEqual(missed.norm.vmin, float(np.min(self.csv[:, 8])))
            self.assertAlmostEqual(missed.norm.vmax, float(np.max(self.csv[:, 8])))
            self.assertTrue(any("\u03a3 pD w" in label for label in labels), labels)
        finally:
            plt.close(fig)


class ParentWeightsVariantsTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.root = Path(self.tmp.name)

    def tearDown(self):
        self.tmp.cleanup()

    def test_only_parent_weights_files_make_a_report(self):
        results = write_parent_weights(self.root / "pw")
        report = build_report([results], self.root / "out")
        self.assertTrue(report.section("parent-weights").shown)
        for section_id in ("summary", "fig1", "fig2", "scaling"):
            self.assertFalse(report.section(section_id).shown, section_id)
        self.assertEqual([p.name for p in report.figure_files], ["parent-weights.png"])

    def test_without_true_pose(self):
        results = write_parent_weights(self.root / "pw", true_pose=False)
        body = build_report([results], self.root / "out").section("parent-weights").body
        self.assertIn("No true pose (real data)", body)
        self.assertEqual(len(embedded_pngs(body)), 1)
        folder = ResultsFolder(results)
        fig = plot_parent_weights(parent_weights_data(folder.parent_weights,
                                                      folder.parent_weights_meta))
        try:
            self.assertNotIn("true pose", {t.get_text() for ax in fig.axes
                                           if ax.get_legend() is not None
                                           for t in ax.get_legend().get_texts()})
        finally:
            plt.close(fig)

    def test_without_json(self):
        results = write_parent_weights(self.root / "pw", meta=False)
        body = build_report([results], self.root / "out").section("parent-weights").body
        self.assertIn("No parent_weights.json", body)
        self.assertEqual(len(embedded_pngs(body)), 1)

    def test_older_six_columns_give_two_panels_coloured_by_log_of_the_weights(self):
        results = write_parent_weights(self.root / "pw", log_columns=False)
        header = (results / "parent_weights.csv").read_text().splitlines()[0]
        self.assertEqual(header, "parent,x,y,theta,sc_weight,rb_weight")
        folder, data, fig = parent_figure(results)
        try:
            self.assertIsNone(data.missed_mass)
            self.assertFalse(data.log_weights_in_file)
            panels = parent_panels(fig)
            self.assertEqual(len(panels), 2)
            self.assertNotIn(MISSED_MASS_TITLE, [ax.get_title() for ax in panels])
            scatters = [parent_scatter(ax, 40) for ax in panels]
            self.assertIs(scatters[0].norm, scatters[1].norm)
            norm = scatters[0].norm
            weights = [folder.parent_weights.num(c) for c, _, _ in WEIGHTINGS]
            with np.errstate(divide="ignore"):
                logs = [np.log(w) for w in weights]
            self.assertAlmostEqual(norm.vmax, max(float(np.max(v)) for v in logs))
            self.assertAlmostEqual(norm.vmin, norm.vmax - LOG_WEIGHT_RANGE)
            for scatter, log_w in zip(scatters, logs):
                np.testing.assert_allclose(np.sort(scatter.get_array()),
                                           np.sort(np.maximum(log_w, norm.vmin)))
            self.assertEqual(len(colour_bars(fig)), 1)
            self.assertIn("log weight (nats)", colour_bars(fig)[0].get_ylabel())
        finally:
            plt.close(fig)
        body = build_report([results], self.root / "out").section("parent-weights").body
        self.assertEqual(len(embedded_pngs(body)), 1)
        self.assertIn("log of the normalised weight (no log-weight columns in the file)", body)
        self.assertNotIn("min\u2013max", body)
        self.assertNotIn("weighted mean of \u03a3 pD w", body)
        self.assertIn("<td class=\"name\">spread (scale of the draws&#x27; standard deviations)"
                      "</td><td>"
                      "\u2014</td>", body)  # an older parent_weights.json has no spread

    def test_weights_that_underflow_are_coloured_by_their_log_weight(self):
        results = write_parent_weights(self.root / "pw", parents=4)
        path = results / "parent_weights.csv"
        lines = path.read_text().splitlines()
        lines[1:] = [
            "0,100,50,0.3,1,1,0,0,8.5",
            "1,101,50,0.3,0,0,-800,-790,8.9",  # both weights underflow to 0
            "2,102,50,0.3,0,0,-15,-14,8.9",
            "3,103,50,0.3,0,0,-1000,-1000,9",
        ]
        path.write_text("\n".join(lines) + "\n")
        _, data, fig = parent_figure(results)
        try:
            scatter = parent_scatter(parent_panels(fig)[0], 4)
            self.assertEqual(scatter.norm.vmax, 0.0)
            np.testing.assert_allclose(np.sort(scatter.get_array()), [-20, -20, -15, 0])
        finally:
            plt.close(fig)
        self.assertEqual(data.weightings[0].ess, 1.0)
        body = build_report([results], self.root / "out").section("parent-weights").body
        self.assertIn("<td>8.5\u20139</td>", body)

    def test_elongated_cloud_is_not_drawn_to_scale(self):
        folder = ResultsFolder(write_parent_weights(self.root / "pw"))
        data = parent_weights_data(folder.parent_weights, folder.parent_weights_meta)
        for stretched, to_scale in ((1.0, True), (30.0, False)):
            data.x = 100.0 + (folder.parent_weights.num("x") - 100.0) * stretched
            fig = plot_parent_weights(data)
            try:
                ax = fig.axes[0]
                self.assertEqual(ax.get_aspect() == 1.0, to_scale)
                self.assertEqual("not to the scale" in ax.get_ylabel(), not to_scale)
            finally:
                plt.close(fig)

    def test_prefixed_with_several_folders(self):
        first = make_results_folder(self.root / "a", FixtureSpec(
            groups=(("phd3", 1),), seeds=(1,), steps=8))
        second = make_results_folder(self.root / "b", FixtureSpec(
            groups=(("phd3", 1),), seeds=(1,), steps=8, parent_weights=True))
        report = build_report([first, second], self.root / "out")
        self.assertFalse(report.section("d0-parent-weights").shown)
        self.assertTrue(report.section("d1-parent-weights").shown)
        self.assertTrue((self.root / "out" / "d1-parent-weights.png").is_file())


if __name__ == "__main__":
    unittest.main()
