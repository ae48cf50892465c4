"""reports/pcrb_efficiency.py: estimators' RMSE over the posterior Cramer-Rao bounds."""

import csv
import json
import math
import tempfile
import unittest
from pathlib import Path

import fixture  # noqa: F401  (puts reports/ on sys.path)
import pcrb_efficiency

HEADER = ["estimator", "particles", "seed", "pos_rmse_m", "heading_rmse_deg"]


def write_runs(folder: Path, rows: list[list]) -> None:
    with (folder / "runs.csv").open("w", newline="", encoding="utf-8") as out:
        writer = csv.writer(out)
        writer.writerow(HEADER)
        writer.writerows(rows)


class PcrbEfficiencyTest(unittest.TestCase):
    def test_ratio_of_pooled_mean_squared_errors_on_common_seeds(self):
        rows = [["pcrb", 1, s, 1.0, 0.1] for s in (1, 2, 3)]
        rows += [["pcrb-smoother", 1, s, 0.5, 0.05] for s in (1, 2, 3)]
        # seed 4 has no bound: it counts for the RMSE but not for the ratio
        rows += [["phd3", 10, 1, 2.0, 0.2], ["phd3", 10, 2, 2.0, 0.2], ["phd3", 10, 3, 2.0, 0.2],
                 ["phd3", 10, 4, 10.0, 1.0]]
        with tempfile.TemporaryDirectory() as tmp:
            write_runs(Path(tmp), rows)
            entries = {(e["estimator"], e["particles"]): e
                       for e in pcrb_efficiency.efficiency_rows(
                           pcrb_efficiency.read_runs(Path(tmp)))}
        phd3 = entries[("phd3", 10)]
        self.assertAlmostEqual(phd3["position_rmse"], math.sqrt((3 * 4.0 + 100.0) / 4))
        r, se, seeds, applies = phd3["position_ratio_pcrb"]
        self.assertTrue(applies)  # no config.json: nothing is batch
        self.assertEqual(seeds, 3)  # the seeds with both runs
        self.assertAlmostEqual(r, 2.0)
        self.assertAlmostEqual(se, 0.0)
        self.assertAlmostEqual(phd3["position_ratio_pcrb-smoother"][0], 4.0)
        self.assertAlmostEqual(phd3["heading_ratio_pcrb"][0], 2.0)
        self.assertTrue(entries[("pcrb", 1)]["bound"])
        self.assertNotIn("position_ratio_pcrb", entries[("pcrb", 1)])

    def test_delta_method_error_and_the_flag_below_the_bound(self):
        a = [0.5, 0.6, 0.4, 0.55, 0.45, 0.5, 0.52, 0.48]
        b = [1.0, 1.1, 0.9, 1.0, 1.05, 0.95, 1.0, 1.0]
        r, se = pcrb_efficiency.ratio_with_error(a, b)
        self.assertAlmostEqual(r, math.sqrt(sum(a) / sum(b)))
        self.assertGreater(se, 0.0)
        self.assertLess(se, 0.05)
        enough = pcrb_efficiency.MIN_FLAG_SEEDS
        efficiency = pcrb_efficiency.Efficiency
        self.assertIn("below", pcrb_efficiency.cell(efficiency(r, se, enough)))
        self.assertNotIn("below", pcrb_efficiency.cell(efficiency(1.2, 0.05, enough)))
        # A batch estimator against the filtering bound: shown, never flagged.
        batch = pcrb_efficiency.cell(efficiency(r, se, enough, bound_applies=False))
        self.assertNotIn("below", batch)
        self.assertIn("not binding", batch)
        # On fewer seeds a heavy-tailed mean and its error are low together: marked, not flagged.
        few = pcrb_efficiency.cell(efficiency(r, se, enough - 1))
        self.assertNotIn("below", few)
        self.assertIn(f"few seeds: {enough - 1}", few)

    def test_batch_estimators_are_not_held_to_the_filtering_bound(self):
        rows = [["pcrb", 1, s, 1.0, 0.1] for s in (1, 2)]
        rows += [["pcrb-smoother", 1, s, 0.5, 0.05] for s in (1, 2)]
        rows += [["smoother-known", 1, s, 0.6, 0.06] for s in (1, 2)]
        with tempfile.TemporaryDirectory() as tmp:
            folder = Path(tmp)
            write_runs(folder, rows)
            (folder / "config.json").write_text(json.dumps({"estimators": {
                "smoother-known": {"batch": True}, "pcrb": {"batch": True}}}), encoding="utf-8")
            batch = pcrb_efficiency.read_batch_estimators(folder)
            entry = [e for e in pcrb_efficiency.efficiency_rows(
                pcrb_efficiency.read_runs(folder), batch) if e["estimator"] == "smoother-known"][0]
        self.assertEqual(batch, frozenset({"smoother-known", "pcrb"}))
        self.assertFalse(entry["position_ratio_pcrb"].bound_applies)
        self.assertTrue(entry["position_ratio_pcrb-smoother"].bound_applies)
        self.assertAlmostEqual(entry["position_ratio_pcrb-smoother"].ratio, 1.2)

    def test_markdown_labels_the_bound_rows(self):
        rows = [["pcrb", 1, 1, 1.0, 0.1], ["oracle", 10, 1, 2.0, 0.3]]
        with tempfile.TemporaryDirectory() as tmp:
            write_runs(Path(tmp), rows)
            text = pcrb_efficiency.markdown(
                pcrb_efficiency.efficiency_rows(pcrb_efficiency.read_runs(Path(tmp))))
        self.assertIn("| pcrb (bound) |", text)
        self.assertIn("| oracle | 10 |", text)


if __name__ == "__main__":
    unittest.main()
