"""tables.py: table.md and table.csv with our values ± SE beside the paper's."""

import contextlib
import csv
import io
import math
import tempfile
import unittest
from pathlib import Path

from fixture import FixtureSpec, make_results_folder

import tables


class TablesTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.results = make_results_folder(Path(cls.tmp.name) / "r", FixtureSpec(
            steps=20, steps_option=4000))
        with contextlib.redirect_stdout(io.StringIO()):
            cls.code = tables.main([str(cls.results)])
        cls.markdown = (cls.results / "table.md").read_text(encoding="utf-8")
        with (cls.results / "table.csv").open() as f:
            cls.rows = list(csv.DictReader(f))

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_exit_code(self):
        self.assertEqual(self.code, 0)

    def test_markdown_has_summary_and_paper_table(self):
        self.assertIn("## Summary beside the paper", self.markdown)
        self.assertIn("## Table II", self.markdown)
        self.assertIn("| PHD 3.0 | 10 | 3 |", self.markdown)
        self.assertIn("\u00b1", self.markdown)
        self.assertIn("\u26a0", self.markdown)  # fixture values are far from the paper's

    def test_csv_rows_match_hand_computed_standard_error(self):
        self.assertEqual(len(self.rows), 3 * 6)  # three groups x six metrics
        with (self.results / "runs.csv").open() as f:
            runs = list(csv.DictReader(f))
        per_run = [float(r["pos_rmse_m"]) for r in runs
                   if r["estimator"] == "phd3" and r["particles"] == "10"]
        mean = sum(per_run) / len(per_run)
        std = math.sqrt(sum((v - mean) ** 2 for v in per_run) / (len(per_run) - 1))
        row = next(r for r in self.rows if r["estimator"] == "phd3" and r["particles"] == "10"
                   and r["metric"] == "pos_rmse_m")
        self.assertAlmostEqual(float(row["se"]), std / math.sqrt(3), places=8)
        self.assertEqual(float(row["paper"]), 2.66)
        ours = float(row["ours"])
        self.assertAlmostEqual(float(row["relative_difference"]), (ours - 2.66) / 2.66, places=8)
        self.assertEqual(row["flagged"], "1" if abs(ours - 2.66) / 2.66 > 0.15 else "0")
        self.assertEqual(row["paper_table"], "table2")
        odometry = next(r for r in self.rows if r["estimator"] == "odometry"
                        and r["metric"] == "gospa_mean_m")
        self.assertEqual(odometry["paper"], "")
        self.assertEqual(odometry["flagged"], "0")


if __name__ == "__main__":
    unittest.main()
