"""The pooled NIS series against a hand computation."""

import math
import sys
import unittest
from pathlib import Path

import numpy as np
from scipy import stats

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from phdslam_reports.figures.nis import nis_series  # noqa: E402


class NisSeriesTest(unittest.TestCase):
    def test_pools_sums_and_counts_over_runs(self):
        # Two runs, three steps; step 2 has no measurement in either run.
        sums = np.array([[4.0, 1.0, math.nan], [2.0, 5.0, math.nan]])
        counts = np.array([[2.0, 1.0, math.nan], [1.0, 2.0, 0.0]])
        s = nis_series("phd3", 10, sums, counts)
        self.assertEqual(s.runs, 2)
        np.testing.assert_allclose(s.nis[:2], [6.0 / 3.0, 6.0 / 3.0])
        self.assertTrue(math.isnan(s.nis[2]))
        self.assertAlmostEqual(s.low[0], stats.chi2.ppf(0.025, 6) / 3)
        self.assertAlmostEqual(s.high[0], stats.chi2.ppf(0.975, 6) / 3)
        self.assertAlmostEqual(s.pooled_mean, 12.0 / 6.0)
        self.assertAlmostEqual(s.median, 2.0)
        self.assertEqual(s.inside, 1.0)

    def test_step_outside_its_bounds_counts_against(self):
        s = nis_series("x", 1, np.array([[200.0, 2.0]]), np.array([[1.0, 1.0]]))
        self.assertEqual(s.inside, 0.5)  # 200 is far above chi2.ppf(0.975, 2) = 7.38

    def test_consistent_draws_stay_mostly_inside(self):
        rng = np.random.default_rng(3)
        counts = rng.integers(1, 6, size=(20, 400)).astype(float)
        sums = rng.chisquare(2 * counts)
        s = nis_series("x", 1, sums, counts)
        self.assertGreater(s.inside, 0.90)
        self.assertLess(s.inside, 0.99)
        self.assertAlmostEqual(s.pooled_mean, 2.0, delta=0.05)

    def test_no_measurements_gives_none_and_shapes_must_match(self):
        self.assertIsNone(nis_series("x", 1, np.zeros((2, 3)), np.zeros((2, 3))))
        with self.assertRaises(ValueError):
            nis_series("x", 1, np.zeros((2, 3)), np.zeros((2, 4)))


if __name__ == "__main__":
    unittest.main()
