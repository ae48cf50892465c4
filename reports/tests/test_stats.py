"""Monte Carlo arithmetic: standard errors, relative differences, the 15 % flag, NEES bounds."""

import math
import unittest
import warnings

import fixture  # noqa: F401  (first: puts reports/ on sys.path, checks the interpreter)
import numpy as np
from phdslam_reports import stats


class StandardErrorTest(unittest.TestCase):
    def test_gospa_standard_error_is_std_over_sqrt_runs(self):
        self.assertAlmostEqual(stats.standard_error_from_std(2.0, 4), 1.0)
        self.assertAlmostEqual(stats.standard_error_from_std(3.0, 9), 1.0)

    def test_standard_error_undefined_for_one_run_or_missing_std(self):
        self.assertTrue(math.isnan(stats.standard_error_from_std(2.0, 1)))
        self.assertTrue(math.isnan(stats.standard_error_from_std(math.nan, 10)))

    def test_rmse_standard_error_is_spread_of_per_run_values(self):
        # per-run RMSEs 2, 3, 4: sample std 1, so SE = 1 / sqrt(3)
        self.assertAlmostEqual(stats.standard_error_of_values([2.0, 3.0, 4.0]), 1 / math.sqrt(3))
        # 1, 1, 1, 5: mean 2, squared deviations 1+1+1+9 = 12, var 12/3 = 4, std 2, SE 2/2
        self.assertAlmostEqual(stats.standard_error_of_values([1.0, 1.0, 1.0, 5.0]), 1.0)

    def test_rmse_standard_error_ignores_missing_values(self):
        self.assertAlmostEqual(stats.standard_error_of_values([2.0, math.nan, 4.0]),
                               math.sqrt(2.0) / math.sqrt(2.0))
        self.assertTrue(math.isnan(stats.standard_error_of_values([3.0])))


class NanMeanTest(unittest.TestCase):
    def test_mean_of_the_values_that_are_not_nan(self):
        self.assertAlmostEqual(stats.nan_mean(np.array([1.0, math.nan, 3.0])), 2.0)
        self.assertEqual(stats.nan_mean(np.array([1.0, math.inf])), math.inf)

    def test_no_value_gives_nan_without_a_warning(self):
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            self.assertTrue(math.isnan(stats.nan_mean(np.array([math.nan, math.nan]))))
            self.assertTrue(math.isnan(stats.nan_mean(np.array([]))))


class FlagTest(unittest.TestCase):
    def test_relative_difference(self):
        self.assertAlmostEqual(stats.relative_difference(3.0, 2.5), 0.2)
        self.assertAlmostEqual(stats.relative_difference(2.0, 2.5), -0.2)
        self.assertTrue(math.isnan(stats.relative_difference(1.0, 0.0)))
        self.assertTrue(math.isnan(stats.relative_difference(math.nan, 1.0)))

    def test_flag_beyond_fifteen_percent_only(self):
        self.assertFalse(stats.is_flagged(115.0, 100.0))  # exactly 15 %: not flagged
        self.assertFalse(stats.is_flagged(85.0, 100.0))
        self.assertTrue(stats.is_flagged(115.1, 100.0))
        self.assertTrue(stats.is_flagged(84.9, 100.0))
        self.assertFalse(stats.is_flagged(3.0, 2.66))  # +12.8 %
        self.assertTrue(stats.is_flagged(3.1, 2.66))  # +16.5 %

    def test_flag_against_zero_and_missing(self):
        self.assertFalse(stats.is_flagged(0.0, 0.0))
        self.assertTrue(stats.is_flagged(0.5, 0.0))
        self.assertFalse(stats.is_flagged(math.nan, 3.0))
        self.assertFalse(stats.is_flagged(3.0, None))


class NeesBoundsTest(unittest.TestCase):
    def test_one_run_matches_chi_square_table_for_three_dof(self):
        low, high = stats.nees_bounds(1)
        self.assertAlmostEqual(low, 0.2158, places=3)
        self.assertAlmostEqual(high, 9.3484, places=3)

    def test_two_runs_use_six_dof_divided_by_two(self):
        low, high = stats.nees_bounds(2)
        self.assertAlmostEqual(low, 1.2373 / 2, places=3)
        self.assertAlmostEqual(high, 14.4494 / 2, places=3)

    def test_bounds_tighten_around_dof_with_more_runs(self):
        low, high = stats.nees_bounds(100)
        self.assertLess(low, 3.0)
        self.assertGreater(high, 3.0)
        self.assertLess(high - low, 1.0)

    def test_fraction_inside(self):
        self.assertAlmostEqual(stats.fraction_inside(np.array([1, 2, 3, 10, np.nan]), 1.5, 5), 0.5)


class BandAndFitTest(unittest.TestCase):
    def test_percentiles_match_numpy_with_missing_values(self):
        rng = np.random.default_rng(7)
        matrix = rng.normal(size=(9, 40))
        matrix[rng.random(matrix.shape) < 0.25] = np.nan
        matrix[:, 5] = np.nan
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            for pct in (5.0, 50.0, 95.0):
                np.testing.assert_allclose(stats.column_percentile(matrix, pct),
                                           np.nanpercentile(matrix, pct, axis=0))

    def test_band_mean_over_runs(self):
        band = stats.band_over_runs(np.array([[1.0, 2.0, np.nan], [3.0, np.nan, np.nan]]))
        np.testing.assert_allclose(band.mean[:2], [2.0, 2.0])
        self.assertTrue(math.isnan(band.mean[2]))
        np.testing.assert_array_equal(band.count, [2, 1, 0])

    def test_stack_ragged_pads_with_nan(self):
        m = stats.stack_ragged([np.array([1.0, 2.0]), np.array([3.0])])
        self.assertEqual(m.shape, (2, 2))
        self.assertTrue(math.isnan(m[1, 1]))

    def test_power_law_fit_recovers_exponent(self):
        x = np.array([5.0, 10.0, 20.0, 40.0])
        fit = stats.fit_power_law(x, 2.0 * x ** 1.5)
        self.assertAlmostEqual(fit.exponent, 1.5)
        self.assertAlmostEqual(fit.coefficient, 2.0)
        self.assertIsNone(stats.fit_power_law([5.0, 5.0], [1.0, 2.0]))


class LogScaleTest(unittest.TestCase):
    def test_log_scale_only_for_levels_far_apart(self):
        from phdslam_reports.figures.metrics_over_time import needs_log_scale
        flat = np.array([0.0, 1.0, 2.0, 3.0])
        self.assertFalse(needs_log_scale([flat, 5 * flat]))
        self.assertTrue(needs_log_scale([flat, 100 * flat]))
        self.assertFalse(needs_log_scale([flat]))


if __name__ == "__main__":
    unittest.main()
