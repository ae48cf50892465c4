// Adaptive measurement-driven births with the two-level birth probability
// (docs/algorithms/glmb-slam.md section 5): after the update at step k every measurement of Z_k
// becomes a birth Bernoulli for step k + 1, labelled (k + 1, j), placed by the inverse model at the
// pose the scan was taken from.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "src/core/types.h"
#include "src/glmb/joint_update.h"

namespace phdslam::glmb {

/// How r_B of a measurement is chosen between the "new" and "existing" levels
/// (docs/algorithms/glmb-slam.md section 5).
enum class BirthRule {
  kThresholded,  ///< (a) r_new when r_U(z) < threshold, else r_existing (default)
  kGatesBest,    ///< (b) r_existing when z gates with an entry of the best prior hypothesis
  kContinuous,   ///< (c) r_existing (2 - r_U(z))
};

struct BirthSettings {
  BirthRule rule = BirthRule::kThresholded;
  double new_probability = 1e-4;       ///< r_B of a measurement no mapped landmark explains
  double existing_probability = 5e-5;  ///< r_B of one a mapped landmark explains
  double assigned_threshold = 0.5;     ///< reading (a)'s threshold on r_U
};

/// r_B of one measurement with posterior assignment probability r_u.
double BirthProbability(const BirthSettings& settings, double r_u, bool gates_best_prior);

/// The births of scan `measurements` taken at pose x: mean by the inverse model, covariance
/// G R G', existence by the rule from `update` (its measurement_assigned and
/// measurement_gates_best_prior), labels (label_step, j), ids from next_id.
std::vector<BirthTrack> MakeBirths(const Pose& x, std::span<const Measurement> measurements,
                                   const Mat2& noise_cov, const UpdateResult& update,
                                   const BirthSettings& settings, int label_step,
                                   std::uint64_t& next_id);

}  // namespace phdslam::glmb
