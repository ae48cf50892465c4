"""The efficiency column of the paper-layout tables and the bound rows in them."""

import csv
import math
import tempfile
import unittest
from pathlib import Path

from fixture import FixtureSpec, make_results_folder
from phdslam_reports.comparison import compare
from phdslam_reports.markdown import report_markdown
from phdslam_reports.paper import PaperValues
from phdslam_reports.report import build_report
from phdslam_reports.results import ResultsFolder

GROUPS = (("phd3", 10), ("oracle", 10), ("smoother-known", 1), ("pcrb", 1),
          ("pcrb-smoother", 1))
SCALES = {"oracle": 0.8, "smoother-known": 0.3, "pcrb": 0.05, "pcrb-smoother": 0.04}


def runs_by_group(results: Path) -> dict[str, dict[int, dict[str, str]]]:
    with (results / "runs.csv").open(newline="") as f:
        out: dict[str, dict[int, dict[str, str]]] = {}
        for row in csv.DictReader(f):
            out.setdefault(row["estimator"], {})[int(row["seed"])] = row
        return out


def expected_ratio(runs, estimator: str, bound: str, column: str) -> float:
    """sqrt(mean of the estimator's squared run RMSEs / the bound's), on the same seeds."""
    seeds = sorted(set(runs[estimator]) & set(runs[bound]))
    a = [float(runs[estimator][s][column]) ** 2 for s in seeds]
    b = [float(runs[bound][s][column]) ** 2 for s in seeds]
    return math.sqrt(sum(a) / sum(b))


def table_lines(markdown: str, title: str) -> list[str]:
    """The lines of the Markdown table under the heading that starts with ``title``."""
    part = markdown[markdown.index(f"## {title}"):].split("\n\n")[1]
    return [line for line in part.splitlines() if line.startswith("|")]


class PaperTableEfficiencyTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        root = Path(cls.tmp.name)
        cls.results = make_results_folder(root / "r", FixtureSpec(
            steps=20, steps_option=4000, groups=GROUPS, error_scale=SCALES))
        folder = ResultsFolder(cls.results)
        paper = PaperValues.load()
        cls.markdown = report_markdown(folder, paper, compare(folder, paper))
        cls.lines = table_lines(cls.markdown, "Table II")
        cls.report = build_report([cls.results], root / "report")
        cls.runs = runs_by_group(cls.results)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def row(self, name: str) -> list[str]:
        line = next(x for x in self.lines if x.startswith(f"| {name} |"))
        return [c.strip() for c in line.strip("|").split("|")]

    def test_efficiency_columns_follow_the_rmses(self):
        header = [c.strip() for c in self.lines[0].strip("|").split("|")]
        self.assertEqual(header[2:7], ["Position RMSE (m)", "Heading RMSE (deg)",
                                       "Position efficiency (RMSE / bound)",
                                       "Heading efficiency (RMSE / bound)", "GOSPA (m)"])

    def test_a_filters_efficiency_is_its_rmse_over_pcrb(self):
        cells = self.row("PHD 3.0")
        for cell, column in zip(cells[4:6], ("pos_rmse_m", "heading_rmse_deg")):
            ratio = expected_ratio(self.runs, "phd3", "pcrb", column)
            self.assertTrue(cell.startswith(f"{ratio:.3g} \u00b1 "), (cell, ratio))
            self.assertIn("few seeds: 3", cell)

    def test_a_smoothers_efficiency_is_against_the_smoothing_bound(self):
        cell = self.row("smoother-known")[4]
        ratio = expected_ratio(self.runs, "smoother-known", "pcrb-smoother", "pos_rmse_m")
        self.assertNotAlmostEqual(
            ratio, expected_ratio(self.runs, "smoother-known", "pcrb", "pos_rmse_m"), places=2)
        self.assertTrue(cell.startswith(f"{ratio:.3g} \u00b1 "), (cell, ratio))

    def test_bound_rows_come_last_labelled_and_unranked(self):
        names = [self.row_name(x) for x in self.lines[2:]]
        self.assertEqual(names[-2:], ["PCRB filtering bound", "PCRB smoothing bound"])
        for name in names[-2:]:
            cells = self.row(name)
            self.assertEqual(cells[4:6], ["\u2014", "\u2014"])  # no efficiency of a bound
            self.assertTrue(all("(" not in c and "\u26a0" not in c and "**" not in c
                                for c in cells[2:]), cells)
            self.assertEqual(cells[6], "\u2014")  # GOSPA has no meaning for a bound
        bound = float(self.row("PCRB filtering bound")[2].split(" ")[0])
        self.assertAlmostEqual(bound, math.sqrt(sum(
            float(r["pos_rmse_m"]) ** 2 for r in self.runs["pcrb"].values()) / 3), places=3)

    @staticmethod
    def row_name(line: str) -> str:
        return line.strip("|").split("|")[0].strip()

    def test_html_table_has_the_column_the_note_and_no_flag_on_a_bound(self):
        body = self.report.section("paper-tables").body
        self.assertIn("Position efficiency (RMSE / bound)", body)
        self.assertIn("no result to rank", body)
        bound_row = body[body.index("PCRB filtering bound"):]
        bound_row = bound_row[:bound_row.index("</tr>")]
        self.assertNotIn("\u26a0", bound_row)
        self.assertNotIn("flag", bound_row)

    def test_table_iii_layout_gets_the_position_column_only(self):
        folder = ResultsFolder(self.results)
        paper = PaperValues.load()
        text = report_markdown(folder, paper, compare(folder, paper, "table3"))
        header = [c.strip() for c in table_lines(text, "Table III")[0].strip("|").split("|")]
        self.assertEqual(header[2:4], ["Position RMSE (m)", "Position efficiency (RMSE / bound)"])
        self.assertNotIn("Heading efficiency (RMSE / bound)", header)


class NoBoundTest(unittest.TestCase):
    def test_without_a_bound_the_table_is_unchanged(self):
        with tempfile.TemporaryDirectory() as tmp:
            results = make_results_folder(Path(tmp) / "r", FixtureSpec(
                steps=20, steps_option=4000, groups=(("phd3", 10), ("smoother-known", 1))))
            folder = ResultsFolder(results)
            paper = PaperValues.load()
            lines = table_lines(report_markdown(folder, paper, compare(folder, paper)),
                                "Table II")
        self.assertNotIn("efficiency", lines[0])
        self.assertEqual(len(lines), 3)  # header, rule, PHD 3.0: no row the paper lacks
        self.assertTrue(lines[2].startswith("| PHD 3.0 | 10 |"))


if __name__ == "__main__":
    unittest.main()
