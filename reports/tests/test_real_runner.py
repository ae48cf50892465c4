"""End to end with the real phdslam program (PHDSLAM_BINARY, set by CTest): run, then report."""

import contextlib
import io
import os
import subprocess
import tempfile
import unittest
from pathlib import Path

from fixture import REPORTS_DIR  # noqa: F401  (puts reports/ on sys.path)
from phdslam_reports.report import build_report

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


if __name__ == "__main__":
    unittest.main()
