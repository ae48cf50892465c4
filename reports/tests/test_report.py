"""The HTML report: built from fixture folders, every section present, self-contained."""

import base64
import contextlib
import io
import re
import tempfile
import unittest
from pathlib import Path

from fixture import REPORTS_DIR, FixtureSpec, make_results_folder
from phdslam_reports.report import FOLDER_SECTIONS, build_report

import make_report  # noqa: E402  (reports/ is on sys.path through fixture)

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def section_status(html: str, section_id: str) -> str | None:
    """'shown', 'skipped' or None when the page has no such section."""
    match = re.search(rf'<section id="{re.escape(section_id)}" data-status="(\w+)">', html)
    return match.group(1) if match else None


class FullReportTest(unittest.TestCase):
    """A folder with every optional input: NEES, particles.csv, scaling.csv, paper config."""

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        root = Path(cls.tmp.name)
        cls.results = make_results_folder(root / "results", FixtureSpec(
            nees=True, particles_file=True, scaling=True, parent_weights=True, steps=40,
            steps_option=4000,
            groups=(("phd3", 1), ("phd3", 10), ("odometry", 1), ("smoother-known", 1),
                    ("authors-phd3", 10), ("pcrb", 1)),
            error_scale={"odometry": 4.0, "smoother-known": 0.2, "pcrb": 0.1}))
        cls.out = root / "report"
        cls.report = build_report([cls.results], cls.out)
        cls.html = (cls.out / "index.html").read_text(encoding="utf-8")

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_every_folder_section_is_shown(self):
        for section_id in FOLDER_SECTIONS:
            self.assertEqual(section_status(self.html, section_id), "shown", section_id)

    def test_sensitivity_is_skipped_with_a_note_for_one_setting(self):
        self.assertEqual(section_status(self.html, "sensitivity"), "skipped")
        self.assertIn("Skipped: no sweep", self.html)

    def test_figures_are_written_and_embedded(self):
        names = sorted(p.name for p in self.report.figure_files)
        self.assertEqual(names, ["fig1-trajectory-map.png", "fig2-metrics-over-time.png",
                                 "fig3-particle-paths.png", "map-scaling.png", "nees.png",
                                 "nis.png", "parent-weights.png", "scaling.png",
                                 "smoothers.png"])
        for path in self.report.figure_files:
            self.assertTrue(path.read_bytes().startswith(PNG_MAGIC), path)
        embedded = re.findall(r'<img src="data:image/png;base64,([A-Za-z0-9+/=]+)"', self.html)
        self.assertEqual(len(embedded), 9)
        for data in embedded:
            self.assertTrue(base64.b64decode(data).startswith(PNG_MAGIC))
        png_files = {p.read_bytes() for p in self.report.figure_files}
        self.assertEqual({base64.b64decode(d) for d in embedded}, png_files)

    def test_page_is_self_contained(self):
        self.assertNotIn("<script", self.html.lower())
        self.assertNotIn("<link", self.html.lower())
        self.assertNotRegex(self.html, r'src="(?!data:)')
        for href in re.findall(r'href="([^"]*)"', self.html):
            self.assertTrue(href.startswith("#"), href)
        self.assertNotIn("http://", self.html)
        self.assertNotIn("https://", self.html)

    def test_synthetic_fig1_has_truth_and_no_gps(self):
        body = self.report.section("fig1").body
        self.assertIn("True trajectory (black), estimate (dashed), true landmarks (+)", body)
        self.assertNotIn("GPS", body)

    def test_summary_shows_paper_values_and_flags(self):
        summary = self.report.section("summary").body
        self.assertIn("PHD 3.0", summary)
        self.assertIn("Odometry", summary)
        self.assertIn("paper 2.66", summary)  # Table II, PHD 3.0, N = 10
        self.assertIn('class="flag"', summary)
        self.assertIn("Authors&#x27; 100-seed rerun", summary)

    def test_paper_table_in_paper_layout(self):
        body = self.report.section("paper-tables").body
        self.assertIn("Table II", body)
        self.assertIn("(3.45)", body)  # PHD 3.0, N = 1 position RMSE
        self.assertNotIn("Table III", body)

    def test_nees_section_states_bounds_for_three_runs(self):
        body = self.report.section("nees").body
        # chi2.ppf(0.025 / 0.975, 9) / 3 = 2.700 / 3 and 19.023 / 3
        self.assertIn("[0.900, 6.341]", body)
        self.assertIn("<th>coverage</th>", body)
        self.assertIn("<th>median</th>", body)

    def test_nees_section_pools_nis_with_its_bounds(self):
        body = self.report.section("nees").body
        self.assertIn("NIS per measurement (pooled)", body)
        self.assertIn("nis.png", body)

    def test_map_scaling_growth_and_table(self):
        body = self.report.section("map-scaling").body
        # 0.01 N (1 + 0.1 i) over i = 0 .. 2: x1.20 from the smallest to the largest map.
        self.assertIn("N = 1: \u00d71.20", body)
        self.assertIn("N = 10: \u00d71.20", body)
        self.assertNotIn("N = 1000:", body)  # one map size only
        self.assertIn("map-scaling.png", body)

    def test_scaling_exponents(self):
        body = self.report.section("scaling").body
        self.assertIn("1.000", body)  # phd3 built with n^1
        self.assertIn("3.000", body)  # phd2b built with n^3


class MinimalReportTest(unittest.TestCase):
    """A folder without the optional inputs and another configuration than the paper's."""

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.results = make_results_folder(Path(cls.tmp.name) / "results",
                                          FixtureSpec(groups=(("phd3", 10),), steps=30,
                                                      seeds=(1, 2)))
        stdout = io.StringIO()
        with contextlib.redirect_stdout(stdout):
            cls.code = make_report.main([str(cls.results), "--title", "Minimal"])
        cls.stdout = stdout.getvalue()
        cls.html = (cls.results / "report" / "index.html").read_text(encoding="utf-8")

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_cli_writes_default_location(self):
        self.assertEqual(self.code, 0)
        self.assertIn("report/index.html", self.stdout)
        self.assertIn("<title>Minimal</title>", self.html)

    def test_sections_without_data_are_skipped_with_notes(self):
        for section_id in ("paper-tables", "fig3", "smoothers", "nees", "scaling", "map-scaling",
                           "parent-weights", "sensitivity"):
            self.assertEqual(section_status(self.html, section_id), "skipped", section_id)
        for section_id in ("summary", "fig1", "fig2"):
            self.assertEqual(section_status(self.html, section_id), "shown", section_id)
        self.assertIn("no run folder holds particles.csv", self.html)
        self.assertIn("steps.csv has no &#x27;nees&#x27; column", self.html)
        self.assertIn("no scaling.csv", self.html)
        self.assertIn("no map_scaling.csv", self.html)
        self.assertIn("Skipped: no parent_weights.csv in the results folder (written by phdslam "
                      "parent-weights --out DIR)", self.html)

    def test_configuration_mismatch_is_noted(self):
        self.assertIn("steps = 30 (paper: 4000)", self.html)

    def test_help_describes_arguments(self):
        stdout = io.StringIO()
        with contextlib.redirect_stdout(stdout), self.assertRaises(SystemExit) as exit_:
            make_report.main(["--help"])
        self.assertEqual(exit_.exception.code, 0)
        for word in ("RESULTS_DIR", "--out", "--title", "--paper-table", "Exit codes"):
            self.assertIn(word, stdout.getvalue())


class SweepReportTest(unittest.TestCase):
    """Several folders, each with its own pD in config.json: the sensitivity figure appears."""

    def test_sensitivity_from_several_folders(self):
        with tempfile.TemporaryDirectory() as tmp:
            folders = [
                make_results_folder(Path(tmp) / f"pd{pd}", FixtureSpec(
                    groups=(("phd3", 1),), steps=12, seeds=(1, 2), pd=pd))
                for pd in (0.7, 0.8, 0.95)
            ]
            folders.append(make_results_folder(Path(tmp) / "lambda20", FixtureSpec(
                groups=(("phd3", 1),), steps=12, seeds=(1, 2), clutter_rate=20.0)))
            out = Path(tmp) / "report"
            report = build_report(folders, out)
            html = (out / "index.html").read_text(encoding="utf-8")
            self.assertEqual(section_status(html, "sensitivity"), "shown")
            self.assertTrue((out / "fig5-sensitivity.png").is_file())
            for index in range(4):
                self.assertEqual(section_status(html, f"d{index}-summary"), "shown")
                self.assertTrue((out / f"d{index}-fig1-trajectory-map.png").is_file())
            self.assertIn("fig5-sensitivity.png", [p.name for p in report.figure_files])


if __name__ == "__main__":
    unittest.main()
