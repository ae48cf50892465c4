// Evaluation of result files outside a Monte Carlo run (`phdslam evaluate`): a map CSV against a
// true map CSV, and a TUM trajectory against a true TUM trajectory.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <vector>

#include "datasets/map_io.h"
#include "datasets/trajectory_io.h"

namespace phdslam::validation {

struct TimeMatchedPoses {
  std::vector<double> times;  ///< the truth time stamps that found a partner
  std::vector<Pose> truth;
  std::vector<Pose> estimate;
};

/// Pairs each truth pose with the estimate pose nearest to it in time (the earlier one on a tie),
/// when |t_estimate - t_truth| <= tolerance (0: identical time stamps only). An estimate pose may
/// serve several truth poses. Throws std::invalid_argument when tolerance is negative or NaN or
/// a time stamp is not finite.
TimeMatchedPoses MatchByTime(const std::vector<datasets::StampedPose>& truth,
                             const std::vector<datasets::StampedPose>& estimate, double tolerance);

/// {"gospa", "localisation", "missed", "false", "n_missed", "n_false", "ospa",
///  "ospa_localisation", "ospa_cardinality", "truth_size", "estimate_size", "c", "p"}
/// of the estimate map's positions against the truth map's (weights and covariances unused).
/// Throws std::invalid_argument when c^p or a result overflows (e.g. c = 1e308, p = 1000).
nlohmann::json CompareMaps(const std::vector<datasets::MapPoint>& truth,
                           const std::vector<datasets::MapPoint>& estimate, double c, double p);

/// {"pos_rmse_m", "pos_err_std_m", "heading_rmse_deg", "heading_err_std_deg", "matched",
///  "truth_poses", "estimate_poses", "time_tolerance_s"}; RMSE values are null when nothing
/// matched. Headings are compared unwrapped, as stored (ReadTumTrajectory unwraps them).
/// Throws std::invalid_argument when either trajectory is empty or no true pose finds an
/// estimate within the tolerance (no time overlap), naming both time spans.
nlohmann::json CompareTrajectories(const std::vector<datasets::StampedPose>& truth,
                                   const std::vector<datasets::StampedPose>& estimate,
                                   double tolerance);

}  // namespace phdslam::validation
