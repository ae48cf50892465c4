"""reports/pooled_sweep_table.py: runs pooled over the points of a sweep."""

import contextlib
import csv
import io
import json
import math
import tempfile
import unittest
from pathlib import Path

import fixture  # noqa: F401  (puts reports/ on sys.path)
import pooled_sweep_table

RUNS = ["estimator", "particles", "seed", "pos_rmse_m", "heading_rmse_deg", "pos_err_count",
        "gospa_m", "n_missed", "n_false", "map_size", "coverage", "coverage_rb",
        "nis_mean", "nis_count", "ms_per_step_mean"]
SUMMARY = ["estimator", "particles", "da_tpr", "da_tnr", "da_positives", "da_negatives"]


def write(path: Path, header: list[str], rows: list[list]) -> None:
    with path.open("w", newline="", encoding="utf-8") as out:
        writer = csv.writer(out)
        writer.writerow(header)
        writer.writerows(rows)


class PooledSweepTableTest(unittest.TestCase):
    def test_pools_errors_by_count_and_rates_by_measurements(self):
        with tempfile.TemporaryDirectory() as tmp:
            root = Path(tmp)
            folders = ["sweep-robot-1", "sweep-robot-2"]
            (root / "sweep.json").write_text(json.dumps({"folders": folders}))
            for i, folder in enumerate(folders):
                (root / folder).mkdir()
                # robot 1: RMSE 1 m over 100 steps; robot 2: RMSE 2 m over 300 steps
                write(root / folder / "runs.csv", RUNS,
                      [["phd3", 10, 1, 1.0 + i, 10.0, 100 + 200 * i, 1.0 + i, i, 2 * i, 15,
                        0.5 + 0.5 * i, "", 2.0 + 2 * i, 10 + 30 * i, 0.5]])
                write(root / folder / "summary.csv", SUMMARY,
                      [["phd3", 10, 0.5 + 0.5 * i, 1.0, 10 * (1 + i), 5]])
            folders_read, pools = pooled_sweep_table.pool_sweep(root)
            self.assertEqual(folders_read, folders)
            p = pools[("phd3", 10)]
            self.assertEqual(p.runs, 2)
            self.assertAlmostEqual(p.rms("pos"), math.sqrt((100 * 1 + 300 * 4) / 400))
            self.assertAlmostEqual(p.rms("pos:sweep-robot-2"), 2.0)
            self.assertAlmostEqual(p.weighted("tpr"), (10 * 0.5 + 20 * 1.0) / 30)
            self.assertAlmostEqual(p.weighted("nis"), (10 * 2 + 40 * 4) / 50)
            self.assertAlmostEqual(p.mean("gospa_m"), 1.5)
            self.assertAlmostEqual(p.weighted("coverage"), (100 * 0.5 + 300 * 1.0) / 400)
            self.assertIsNone(p.weighted("coverage_rb"))
            table = pooled_sweep_table.markdown(folders_read, pools)
            self.assertIn("| pos RMSE robot-1 | pos RMSE robot-2 |", table)
            self.assertIn("| phd3 | 10 | 2 | 1.80 | 10.0 | 1.00 | 2.00 | 1.50 |", table)

    def test_efficiency_against_the_bound_of_the_same_robot_and_seed(self):
        with tempfile.TemporaryDirectory() as tmp:
            root = Path(tmp)
            folders = ["sweep-robot-1", "sweep-robot-2"]
            (root / "sweep.json").write_text(json.dumps({"folders": folders}))
            blank = [""] * (len(RUNS) - 6)
            for i, folder in enumerate(folders):
                (root / folder).mkdir()
                steps = 100 + 200 * i
                rows = [["pcrb", 1, 1, 0.5 + 0.5 * i, 1.0, steps] + blank,
                        ["pcrb-smoother", 1, 1, 0.25, 0.5, steps] + blank]
                # the oracle on seeds 1 and 2; the bound only on seed 1: one pair per robot
                rows += [["oracle", 10, seed, 2.0 + i, 3.0, steps] + blank for seed in (1, 2)]
                rows += [["smoother-known", 1, 1, 0.5, 1.0, steps] + blank]
                write(root / folder / "runs.csv", RUNS, rows)
                write(root / folder / "summary.csv", SUMMARY, [])
            folders_read, pools = pooled_sweep_table.pool_sweep(root)
            table = pooled_sweep_table.markdown(folders_read, pools)
            oracle = pooled_sweep_table.efficiency(pools, "oracle", 10, "pos")
            smoother = pooled_sweep_table.efficiency(pools, "smoother-known", 1, "pos")
        # summed squared errors: oracle 4 * 100 + 9 * 300, pcrb 0.25 * 100 + 1 * 300
        self.assertAlmostEqual(oracle[0], math.sqrt((400 + 2700) / (25 + 300)))
        self.assertEqual(oracle[2], 2)
        self.assertAlmostEqual(smoother[0], 2.0)  # against pcrb-smoother, not pcrb
        self.assertIsNone(pooled_sweep_table.efficiency(pools, "pcrb", 1, "pos"))
        self.assertIn("| pos RMSE m | heading RMSE deg | pos efficiency | heading efficiency |",
                      table)
        self.assertIn(f"| oracle | 10 | 4 | {math.sqrt((2 * 400 + 2 * 2700) / 800):.2f} | 3.0 | "
                      f"{oracle[0]:.3g} \u00b1 ", table)
        self.assertIn("| pcrb (bound) | 1 | 2 | ", table)
        self.assertRegex(table, r"\| pcrb \(bound\) \| 1 \| 2 \| [0-9.]+ \| [0-9.]+ \| "
                                r"— \| — \|")

    def test_without_a_bound_there_is_no_efficiency_column(self):
        with tempfile.TemporaryDirectory() as tmp:
            root = Path(tmp)
            (root / "sweep.json").write_text(json.dumps({"folders": ["sweep-robot-1"]}))
            (root / "sweep-robot-1").mkdir()
            write(root / "sweep-robot-1" / "runs.csv", RUNS,
                  [["oracle", 10, 1, 2.0, 3.0, 100] + [""] * (len(RUNS) - 6)])
            write(root / "sweep-robot-1" / "summary.csv", SUMMARY, [])
            table = pooled_sweep_table.markdown(*pooled_sweep_table.pool_sweep(root))
        self.assertNotIn("efficiency", table)

    def test_a_malformed_seed_is_one_line_naming_the_file_and_line(self):
        with tempfile.TemporaryDirectory() as tmp:
            root = Path(tmp)
            (root / "sweep.json").write_text(json.dumps({"folders": ["sweep-robot-1"]}))
            (root / "sweep-robot-1").mkdir()
            write(root / "sweep-robot-1" / "runs.csv", RUNS,
                  [["pcrb", 1, "first", 0.2, 3.0, 100] + [""] * (len(RUNS) - 6)])
            write(root / "sweep-robot-1" / "summary.csv", SUMMARY, [])
            stderr = io.StringIO()
            with contextlib.redirect_stderr(stderr):
                code = pooled_sweep_table.main([str(root)])
        self.assertEqual(code, 1)
        message = stderr.getvalue()
        self.assertEqual(message.count("\n"), 1)
        self.assertIn("sweep-robot-1/runs.csv, line 2: ", message)
        self.assertIn("'first'", message)


if __name__ == "__main__":
    unittest.main()
