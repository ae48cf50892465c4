"""End to end with the real phdslam program (PHDSLAM_BINARY, set by CTest): run, then report."""

import contextlib
import io
import math
import os
import subprocess
import tempfile
import unittest
from pathlib import Path

from fixture import REPORTS_DIR  # noqa: F401  (puts reports/ on sys.path)
from phdslam_reports.comparison import compare
from phdslam_reports.figures.parent_weights import parent_weights_data
from phdslam_reports.paper import PaperValues
from phdslam_reports.report import build_report
from phdslam_reports.results import ResultsFolder

import tables

PHDSLAM = os.environ.get("PHDSLAM_BINARY", "")


@unittest.skipUnless(PHDSLAM and Path(PHDSLAM).is_file(),
                     "PHDSLAM_BINARY does not name a built phdslam program (CTest sets it)")
class RealRunnerTest(unittest.TestCase):
    def test_report_of_a_real_results_folder(self):
        with tempfile.TemporaryDirectory() as tmp:
            results = Path(tmp) / "results"
            done = subprocess.run(
                [PHDSLAM, "run", "--scenario", "generated", "--estimator", "odometry",
                 "--particles", "1", "--seeds", "1-3", "--steps", "80", "--out", str(results),
                 "--quiet", "--jobs", "1"], capture_output=True, text=True, timeout=300)
            self.assertEqual(done.returncode, 0, done.stderr)
            report = build_report([results], Path(tmp) / "report")
            for section_id in ("summary", "fig1", "fig2"):
                self.assertTrue(report.section(section_id).shown, section_id)
            self.assertFalse(report.section("paper-tables").shown)  # no paper table: generated
            self.assertIn("Odometry", report.section("summary").body)
            with contextlib.redirect_stdout(io.StringIO()):
                self.assertEqual(tables.main([str(results)]), 0)
            self.assertIn("| Odometry | 1 | 3 |", (results / "table.md").read_text())

    def test_data_association_rates_beside_the_papers(self):
        with tempfile.TemporaryDirectory() as tmp:
            results = Path(tmp) / "results"
            done = subprocess.run(
                [PHDSLAM, "run", "--scenario", "paper-synthetic", "--estimator", "phd3,phd1",
                 "--particles", "1", "--seeds", "1-2", "--steps", "150", "--out", str(results),
                 "--quiet", "--jobs", "1"], capture_output=True, text=True, timeout=300)
            self.assertEqual(done.returncode, 0, done.stderr)
            comparison = compare(ResultsFolder(results), PaperValues.load())
            rows = {r.group.estimator: r for r in comparison.rows}
            for metric, paper in (("da_tpr", 0.9829), ("da_tnr", 0.9984)):
                cell = rows["phd3"].cell(metric)
                self.assertTrue(0.0 <= cell.ours <= 1.0, cell)
                self.assertEqual((cell.paper, cell.source), (paper, "da_accuracy"))
                self.assertTrue(math.isnan(rows["phd1"].cell(metric).ours))  # not scored
            body = build_report([results], Path(tmp) / "report").section("summary").body
            self.assertIn("paper 0.9829", body)

    def test_particle_traces_are_drawn_as_fig3(self):
        with tempfile.TemporaryDirectory() as tmp:
            results = Path(tmp) / "results"
            done = subprocess.run(
                [PHDSLAM, "run", "--scenario", "paper-synthetic", "--estimator", "phd3",
                 "--particles", "5", "--seeds", "1", "--steps", "60", "--particles-trace",
                 "--out", str(results), "--quiet", "--jobs", "1"],
                capture_output=True, text=True, timeout=300)
            self.assertEqual(done.returncode, 0, done.stderr)
            report = build_report([results], Path(tmp) / "report")
            self.assertTrue(report.section("fig3").shown, report.section("fig3").skipped_note)
            self.assertTrue((Path(tmp) / "report" / "fig3-particle-paths.png").is_file())

    def test_parent_weights_report(self):
        with tempfile.TemporaryDirectory() as tmp:
            results = Path(tmp) / "pw"
            done = subprocess.run([PHDSLAM, "parent-weights", "--out", str(results),
                                   "--parents", "60"], capture_output=True, text=True,
                                  timeout=300)
            self.assertEqual(done.returncode, 0, done.stderr)
            folder = ResultsFolder(results)
            data = parent_weights_data(folder.parent_weights, folder.parent_weights_meta)
            self.assertEqual(data.parents, 60)
            self.assertTrue(data.log_weights_in_file)
            self.assertIsNotNone(data.missed_mass)
            self.assertIsNotNone(data.spread)
            report = build_report([results], Path(tmp) / "report")
            self.assertTrue(report.section("parent-weights").shown)
            self.assertIn("missed-detection mass", report.section("parent-weights").body)


if __name__ == "__main__":
    unittest.main()
