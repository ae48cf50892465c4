"""reports/pooled_sweep_table.py: runs pooled over the points of a sweep."""

import csv
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


if __name__ == "__main__":
    unittest.main()
