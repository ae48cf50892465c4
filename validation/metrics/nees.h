// Normalised estimation error squared (NEES) and its chi-square consistency bounds.
#pragma once

#include <vector>

#include "src/core/types.h"
#include "validation/metrics/chi_square.h"
#include "validation/metrics/gospa.h"

namespace phdslam::validation {

/// e' P^-1 e with e = truth - estimate; the heading difference is NOT wrapped (headings never are).
/// Throws std::invalid_argument when cov is not symmetric positive definite or an input is not
/// finite (a zero covariance, as at the first step of a run, has no NEES).
double PoseNees(const Pose& truth, const Pose& estimate, const Mat3& cov);
double LandmarkNees(const Landmark& truth, const Landmark& estimate, const Mat2& cov);

/// chi-square_dim quantile at `level`: a NEES at or below it puts the truth inside the
/// estimator's `level` confidence ellipsoid. Throws std::invalid_argument unless dim >= 1 and
/// 0 < level < 1.
double EllipsoidThreshold(int dim, double level = 0.95);

struct NeesBounds {
  double lower = 0.0;
  double upper = 0.0;
};

/// Two-sided (1 - alpha) bounds for the NEES of a dim-dimensional state averaged over `runs`
/// runs: the chi-square_{dim * runs} quantiles at alpha / 2 and 1 - alpha / 2, divided by runs.
/// Throws std::invalid_argument unless dim >= 1, runs >= 1 and 0 < alpha < 1.
NeesBounds AveragedNeesBounds(int dim, int runs, double alpha = 0.05);

struct NeesConsistency {
  std::vector<double> mean_nees;  ///< per step, averaged over the runs
  NeesBounds bounds;              ///< AveragedNeesBounds(dim, number of runs, alpha)
  double fraction_inside = 0.0;   ///< fraction of steps with lower <= mean_nees <= upper
};

/// nees_per_run_per_step[r][k] is the NEES of run r at step k; every run must have the same
/// (non-zero) number of steps. Throws std::invalid_argument otherwise, or on no runs.
NeesConsistency SummariseNees(const std::vector<std::vector<double>>& nees_per_run_per_step,
                              int dim, double alpha = 0.05);

/// Landmark NEES of a final map, one value per GOSPA pair (truth index, estimate index), in the
/// order of gospa.pairs; estimate_covs[j] is the covariance of estimate[j]. Throws
/// std::invalid_argument when the sizes disagree or a pair index is out of range.
std::vector<double> MatchedLandmarkNees(const std::vector<Landmark>& truth,
                                        const std::vector<Landmark>& estimate,
                                        const std::vector<Mat2>& estimate_covs,
                                        const GospaResult& gospa);

}  // namespace phdslam::validation
