"""Our values beside the paper's: standard errors from the results files, table matching, flags."""

import json
import math
import tempfile
import unittest
from pathlib import Path

import fixture  # noqa: F401  (puts reports/ on sys.path)
from phdslam_reports.comparison import compare
from phdslam_reports.paper import PaperValues, resampling_enabled
from phdslam_reports.results import RUNS_COLUMNS, SUMMARY_COLUMNS, ResultsFolder

PAPER = PaperValues.load()


def write_folder(root: Path, scenario: str = "paper-synthetic", steps_option: int = 0,
                 parameters: dict | None = None) -> Path:
    """phd3 N=10, 3 runs of 4000 steps; per-run pos RMSE 2, 3, 4; GOSPA std 3."""
    root.mkdir(parents=True, exist_ok=True)
    summary = dict.fromkeys(SUMMARY_COLUMNS, "")
    summary.update(estimator="phd3", particles="10", runs="3", steps="4000", pos_rmse_m="3.0",
                   heading_rmse_deg="0.30", gospa_mean_m="44.1", gospa_std_m="3.0",
                   ess_pct="49.34", resampling_pct="5.0", ms_per_step_mean="2.0")
    (root / "summary.csv").write_text(",".join(summary) + "\n" + ",".join(summary.values())
                                      + "\n")
    lines = [",".join(RUNS_COLUMNS)]
    for seed, rmse in ((1, 2.0), (2, 3.0), (3, 4.0)):
        run = dict.fromkeys(RUNS_COLUMNS, "")
        run.update(estimator="phd3", particles="10", seed=str(seed), steps="4000",
                   pos_rmse_m=str(rmse), heading_rmse_deg="0.3", gospa_m="44",
                   ess_pct=str(49 + seed), resampling_pct="5", ms_per_step_mean="2")
        lines.append(",".join(run.values()))
    (root / "runs.csv").write_text("\n".join(lines) + "\n")
    config = {"scenario": {"name": scenario, "options": {
                  "steps": steps_option, "detection_probability": 0.95, "clutter_rate": 5.0}},
              "estimators": {"phd3": {"parameters": {"10": parameters or {}}}}}
    (root / "config.json").write_text(json.dumps(config))
    return root


class ComparisonTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.root = Path(self.tmp.name)

    def tearDown(self):
        self.tmp.cleanup()

    def test_standard_errors_come_from_runs_and_summary(self):
        row = compare(ResultsFolder(write_folder(self.root / "r")), PAPER).rows[0]
        self.assertAlmostEqual(row.cell("pos_rmse_m").se, 1 / math.sqrt(3))  # std of 2,3,4 = 1
        self.assertAlmostEqual(row.cell("gospa_mean_m").se, 3.0 / math.sqrt(3))
        self.assertAlmostEqual(row.cell("ess_pct").se, 1 / math.sqrt(3))  # 50, 51, 52
        self.assertEqual(row.cell("resampling_pct").se, 0.0)

    def test_paper_values_relative_differences_and_flags(self):
        comparison = compare(ResultsFolder(write_folder(self.root / "r")), PAPER)
        row = comparison.rows[0]
        self.assertEqual(row.table.id, "table2")
        pos = row.cell("pos_rmse_m")
        self.assertEqual(pos.paper, 2.66)
        self.assertAlmostEqual(pos.relative, (3.0 - 2.66) / 2.66)
        self.assertFalse(pos.flagged)  # +12.8 %
        gospa = row.cell("gospa_mean_m")
        self.assertEqual(gospa.paper, 38.27)
        self.assertTrue(gospa.flagged)  # +15.2 %

    def test_heading_within_tolerance_is_not_flagged(self):
        row = compare(ResultsFolder(write_folder(self.root / "r")), PAPER).rows[0]
        heading = row.cell("heading_rmse_deg")
        self.assertAlmostEqual(heading.relative, 0.30 / 0.34 - 1)
        self.assertFalse(heading.flagged)
        self.assertFalse(row.cell("ess_pct").flagged)  # equal to the paper

    def test_no_resampling_parameter_selects_table_one(self):
        folder = write_folder(self.root / "r", parameters={"resampling": False})
        row = compare(ResultsFolder(folder), PAPER).rows[0]
        self.assertEqual(row.table.id, "table1")
        self.assertEqual(row.cell("pos_rmse_m").paper, 2.4)
        self.assertIsNone(row.cell("heading_rmse_deg").paper)

    def test_resampling_detection(self):
        self.assertTrue(resampling_enabled({}))
        self.assertTrue(resampling_enabled({"resample": True, "ess_threshold": 0.2}))
        self.assertFalse(resampling_enabled({"resampling": {"mode": "never"}}))
        self.assertFalse(resampling_enabled({"ess_threshold": 0}))

    def test_victoria_park_uses_table_three_and_other_scenarios_none(self):
        vp = compare(ResultsFolder(write_folder(self.root / "vp", scenario="victoria-park")),
                     PAPER).rows[0]
        self.assertEqual(vp.table.id, "table3")
        self.assertEqual(vp.cell("pos_rmse_m").paper, 3.36)
        self.assertEqual(vp.cell("ess_pct").paper, 13.88)
        gen = compare(ResultsFolder(write_folder(self.root / "g", scenario="generated")),
                      PAPER).rows[0]
        self.assertIsNone(gen.table)
        self.assertFalse(any(c.flagged for c in gen.cells))

    def test_other_configuration_is_noted(self):
        comparison = compare(ResultsFolder(write_folder(self.root / "r", steps_option=500)), PAPER)
        self.assertTrue(any("steps = 500 (paper: 4000)" in n for n in comparison.notes))
        full = compare(ResultsFolder(write_folder(self.root / "f", steps_option=0)), PAPER)
        self.assertEqual(full.notes, [])  # steps 0 = all: summary.csv says 4000

    def test_paper_values_file_holds_every_published_number(self):
        t2, t1, t3 = PAPER.tables["table2"], PAPER.tables["table1"], PAPER.tables["table3"]
        self.assertEqual(t2.value("phd1", 1, "pos_rmse_m"), 254.21)
        self.assertEqual(t2.value("oracle", 100, "gospa_mean_m"), 23.52)
        self.assertEqual(t2.value("phd2b", 100, "ms_per_step_mean"), 22.16)
        self.assertIsNone(t2.value("phd3", 1, "ess_pct"))
        count = sum(v is not None for per_n in t2.values.values() for row in per_n.values()
                    for v in row.values())
        self.assertEqual(count, 5 * 3 * 6 - 5 - 3)  # N/A ESS at N = 1; no Oracle times
        self.assertEqual(t1.value("phd2b", 100, "gospa_mean_m"), 175.3)
        self.assertEqual(sum(len(p) for p in t1.values.values()), 12)
        self.assertEqual(t3.value("phd1", 5, "resampling_pct"), 40.54)
        self.assertEqual(sum(len(p) for p in t3.values.values()), 12)
        self.assertEqual(PAPER.tables["authors_rerun"].value("phd3", 10, "gospa_mean_m"), 34.4)
        self.assertEqual(PAPER.tables["da_accuracy"].value("phd2b", 7, "da_tpr"), 0.9223)
        self.assertEqual(PAPER.tables["da_accuracy"].value("phd3", 1, "da_tnr"), 0.9984)
        self.assertEqual(PAPER.display_name("phd2a"), "PHD 2.0a")


if __name__ == "__main__":
    unittest.main()
