"""The report's comparison with the authors' implementation, on runs of known differences."""

import csv
import math
import tempfile
import unittest
from pathlib import Path

import numpy as np
from fixture import FixtureSpec, make_results_folder
from phdslam_reports.authors_comparison import authors_rows
from phdslam_reports.report import build_report
from phdslam_reports.results import ResultsFolder
from scipy import stats

SEEDS = tuple(range(1, 13))
AUTHORS_RMSE = np.array([2.0, 2.5, 1.8, 3.1, 2.2, 2.9, 1.6, 2.4, 2.7, 2.0, 3.3, 1.9])


def set_column_values(folder: Path, values: dict[tuple[str, int], np.ndarray]) -> None:
    """Overwrites pos_rmse_m and gospa_m (= 20 x the RMSE) of the given groups in runs.csv."""
    path = folder / "runs.csv"
    with path.open(encoding="utf-8", newline="") as stream:
        rows = list(csv.DictReader(stream))
    for row in rows:
        key = (row["estimator"], int(row["particles"]))
        if key in values:
            value = values[key][int(row["seed"]) - 1]
            row["pos_rmse_m"] = f"{value:.12g}"
            row["gospa_m"] = f"{20 * value:.12g}"
    with path.open("w", encoding="utf-8", newline="") as stream:
        writer = csv.DictWriter(stream, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)


class AuthorsComparison(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        root = Path(cls.tmp.name)
        cls.folder = make_results_folder(root / "results", FixtureSpec(
            groups=(("authors-phd3", 10), ("phd3", 10), ("phd3-replay", 10), ("phd1", 10)),
            seeds=SEEDS, steps=20))
        # phd3 on its own draws: 20 % higher with a seed-to-seed spread; the replay: rounding.
        spread = np.array([0.1, -0.2, 0.15, 0.05, -0.1, 0.2, 0.0, -0.05, 0.1, -0.15, 0.05, 0.0])
        cls.own = AUTHORS_RMSE * (1.2 + spread)
        cls.replayed = AUTHORS_RMSE * (1 + 1e-9 * np.arange(12))
        set_column_values(cls.folder, {("authors-phd3", 10): AUTHORS_RMSE,
                                       ("phd3", 10): cls.own, ("phd3-replay", 10): cls.replayed})
        cls.rows = authors_rows(ResultsFolder(cls.folder))

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def row(self, ours: str, metric: str):
        return next(r for r in self.rows if r.ours == ours and r.metric == metric)

    def test_pairs_only_the_authors_variant(self):
        self.assertEqual(sorted((r.ours, r.metric) for r in self.rows),
                         [("phd3", "gospa_m"), ("phd3", "pos_rmse_m"),
                          ("phd3-replay", "gospa_m"), ("phd3-replay", "pos_rmse_m")])

    def test_own_draws_row_by_hand(self):
        row = self.row("phd3", "pos_rmse_m")
        d = self.own - AUTHORS_RMSE
        reference = AUTHORS_RMSE.mean()
        half = 1.795885 * d.std(ddof=1) / math.sqrt(12)  # t(0.95, 11)
        self.assertEqual(row.n, 12)
        self.assertAlmostEqual(row.mean_authors, reference, places=9)
        self.assertAlmostEqual(row.diff_pct, 100 * d.mean() / reference, places=6)
        self.assertAlmostEqual(row.ci_low_pct, 100 * (d.mean() - half) / reference, places=4)
        self.assertAlmostEqual(row.ci_high_pct, 100 * (d.mean() + half) / reference, places=4)
        self.assertFalse(row.equivalent)  # about +20 %
        t = d.mean() / (d.std(ddof=1) / math.sqrt(12))
        self.assertAlmostEqual(row.p_ttest, 2 * stats.t.sf(t, 11), places=12)
        self.assertLess(row.p_ttest, 1e-3)
        # Seed 2's difference is 0 (left out); the other 11 are all positive, so the exact
        # two-sided Wilcoxon p is 2 / 2^11.
        self.assertAlmostEqual(row.p_wilcoxon, 2 / 2048, places=9)
        self.assertEqual(row.draws, "own random draws")

    def test_replayed_draws_are_equivalent(self):
        for metric in ("pos_rmse_m", "gospa_m"):
            row = self.row("phd3-replay", metric)
            self.assertTrue(row.equivalent, metric)
            self.assertLess(abs(row.ci_high_pct), 1e-5)
            self.assertEqual(row.draws, "the authors' recorded draws")

    def test_section_in_the_report(self):
        out = Path(self.tmp.name) / "report"
        build_report([self.folder], out)
        html = (out / "index.html").read_text(encoding="utf-8")
        self.assertIn('<section id="authors" data-status="shown">', html)
        self.assertIn("the authors&#x27; recorded draws", html)
        self.assertIn("not shown", html)

    def test_without_authors_runs_the_section_is_skipped(self):
        with tempfile.TemporaryDirectory() as tmp:
            folder = make_results_folder(Path(tmp) / "r", FixtureSpec(groups=(("phd3", 1),)))
            self.assertEqual(authors_rows(ResultsFolder(folder)), [])
            build_report([folder], Path(tmp) / "report")
            html = (Path(tmp) / "report" / "index.html").read_text(encoding="utf-8")
            self.assertIn('<section id="authors" data-status="skipped">', html)

    def test_one_common_seed_gives_no_row(self):
        with tempfile.TemporaryDirectory() as tmp:
            folder = make_results_folder(Path(tmp) / "r", FixtureSpec(
                groups=(("authors-phd3", 1), ("phd3", 1)), seeds=(1,)))
            self.assertEqual(authors_rows(ResultsFolder(folder)), [])


if __name__ == "__main__":
    unittest.main()
