"""tables.py: table.md and table.csv with our values ± SE beside the paper's."""

import contextlib
import csv
import io
import math
import tempfile
import unittest
from pathlib import Path

from fixture import FixtureSpec, da_counts, make_results_folder
from phdslam_reports.comparison import format_relative, format_value
from phdslam_reports.html_page import escape
from phdslam_reports.report import build_report
from phdslam_reports.tables_shared import ours_with_se

import tables

DA_PAPER = {("phd2b", "da_tpr"): 0.9223, ("phd2b", "da_tnr"): 0.9980,
            ("phd3", "da_tpr"): 0.9829, ("phd3", "da_tnr"): 0.9984}
"""The paper's data-association rates (reports/paper_values.yaml, da_accuracy)."""


def write_tables(results: Path) -> tuple[int, str, list[dict[str, str]]]:
    """Runs tables.py on a results folder: exit code, table.md and the rows of table.csv."""
    with contextlib.redirect_stdout(io.StringIO()):
        code = tables.main([str(results)])
    markdown = (results / "table.md").read_text(encoding="utf-8")
    with (results / "table.csv").open() as f:
        return code, markdown, list(csv.DictReader(f))


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

    def test_folder_without_da_columns_lists_the_papers_rates_as_missing(self):
        self.assertNotIn("da_tpr", {r["metric"] for r in self.rows})
        self.assertNotIn("DA true-positive rate ours", self.markdown)
        self.assertIn("| Data-association accuracy (synthetic) | PHD 3.0 | 10 | DA true-positive "
                      "rate | not in these results | 0.9829 |  |", self.markdown)


class DataAssociationTest(unittest.TestCase):
    """summary.csv/runs.csv with da_* columns: our DA rates ± SE beside the paper's (table.md,
    table.csv and the HTML summary)."""

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.seeds = (1, 2, 3)
        cls.results = make_results_folder(Path(cls.tmp.name) / "r", FixtureSpec(
            groups=(("phd3", 1), ("phd3", 10), ("phd2b", 10), ("phd1", 10), ("odometry", 1)),
            seeds=cls.seeds, steps=20, steps_option=4000, da_rates=True))
        cls.code, cls.markdown, cls.rows = write_tables(cls.results)
        cls.report = build_report([cls.results], Path(cls.tmp.name) / "report")
        cls.summary = cls.report.section("summary").body

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def expected(self, estimator: str, metric: str) -> tuple[float, float]:
        """Ours pooled over every measurement of every run and the SE of the per-run rates."""
        counts = [da_counts(estimator, seed) for seed in self.seeds]
        hit, total = (0, 1) if metric == "da_tpr" else (2, 3)
        pooled = sum(c[hit] for c in counts) / sum(c[total] for c in counts)
        per_run = [c[hit] / c[total] for c in counts]
        mean = sum(per_run) / len(per_run)
        se = math.sqrt(sum((v - mean) ** 2 for v in per_run) / (len(per_run) - 1)
                       / len(per_run))
        return pooled, se

    def csv_row(self, estimator: str, particles: int, metric: str) -> dict[str, str]:
        return next(r for r in self.rows if r["estimator"] == estimator
                    and r["particles"] == str(particles) and r["metric"] == metric)

    def test_csv_has_our_rates_with_se_beside_the_papers(self):
        self.assertEqual(self.code, 0)
        self.assertEqual(len(self.rows), 5 * 8)  # five groups x (six metrics + two DA rates)
        for (estimator, metric), paper in DA_PAPER.items():
            for particles in ((1, 10) if estimator == "phd3" else (10,)):
                row = self.csv_row(estimator, particles, metric)
                ours, se = self.expected(estimator, metric)
                self.assertAlmostEqual(float(row["ours"]), ours, places=8)
                self.assertAlmostEqual(float(row["se"]), se, places=8)
                self.assertEqual(float(row["paper"]), paper)
                self.assertAlmostEqual(float(row["relative_difference"]),
                                       (ours - paper) / paper, places=8)
                self.assertEqual(row["paper_table"], "da_accuracy")
        for estimator, particles in (("phd1", 10), ("odometry", 1)):  # not scored
            for metric in ("da_tpr", "da_tnr"):
                row = self.csv_row(estimator, particles, metric)
                self.assertEqual((row["ours"], row["se"], row["paper"]), ("", "", ""))
        self.assertEqual(self.csv_row("phd3", 10, "pos_rmse_m")["paper_table"], "table2")

    def test_markdown_summary_has_the_da_cells_with_the_papers_values(self):
        self.assertIn("DA true-positive rate ours \u00b1 SE | paper | \u0394 | "
                      "DA true-negative rate ours \u00b1 SE | paper | \u0394 |", self.markdown)
        for estimator, name in (("phd3", "PHD 3.0"), ("phd2b", "PHD 2.0b")):
            line = next(x for x in self.markdown.splitlines()
                        if x.startswith(f"| {name} | 10 | 3 |"))
            cells = []
            for metric in ("da_tpr", "da_tnr"):
                ours, se = self.expected(estimator, metric)
                paper = DA_PAPER[(estimator, metric)]
                cells.append(f"{ours_with_se(ours, se)} | {format_value(paper)} | "
                             f"{format_relative((ours - paper) / paper)}")
            self.assertTrue(line.endswith(" | ".join(cells) + " |"), line)
        phd1 = next(x for x in self.markdown.splitlines() if x.startswith("| PHD 1.0 | 10 |"))
        self.assertTrue(phd1.endswith("| \u2014 | \u2014 | \u2014 | \u2014 | \u2014 | \u2014 |"))
        self.assertIn("Paper values: Data-association accuracy (synthetic); source: "
                      "Kaltiokallio et al., IEEE T-RO 2024, text beside Table II", self.markdown)
        # shown in the summary, so not repeated under "Other published numbers"
        self.assertNotIn("| Data-association accuracy (synthetic) |", self.markdown)
        self.assertIn("| Authors' 100-seed rerun of PHD 3.0", self.markdown)

    def test_html_summary_has_the_da_cells_with_the_papers_values(self):
        self.assertIn("<th>DA true-positive rate</th><th>DA true-negative rate</th>",
                      self.summary)
        for (estimator, metric), paper in DA_PAPER.items():
            ours, se = self.expected(estimator, metric)
            self.assertIn(escape(ours_with_se(ours, se)), self.summary)
            self.assertIn(escape(f"paper {format_value(paper)}, \u0394 "
                                 f"{format_relative((ours - paper) / paper)}"), self.summary)
        self.assertIn("Paper values: Data-association accuracy (synthetic)", self.summary)
        self.assertNotIn("<td class=\"name\">Data-association accuracy (synthetic)</td>",
                         self.summary)

    def test_empty_da_columns_are_left_out(self):
        results = make_results_folder(Path(self.tmp.name) / "unscored", FixtureSpec(
            groups=(("phd1", 10), ("odometry", 1)), seeds=(1, 2), steps=12, da_rates=True))
        header = (results / "summary.csv").read_text().splitlines()[0]
        self.assertIn("da_tpr", header)
        code, markdown, rows = write_tables(results)
        self.assertEqual(code, 0)
        self.assertEqual(len(rows), 2 * 6)
        self.assertNotIn("DA true", markdown)
        body = build_report([results], Path(self.tmp.name) / "unscored-report").section(
            "summary").body
        self.assertNotIn("DA true", body)


if __name__ == "__main__":
    unittest.main()
