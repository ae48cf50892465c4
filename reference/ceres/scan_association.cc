#include "reference/ceres/scan_association.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "reference/ceres/joint_compatibility.h"
#include "src/core/angles.h"
#include "src/core/gaussian.h"
#include "src/models/range_bearing_model.h"

namespace phdslam::reference {
namespace {

struct Pair {
  int measurement;
  int landmark;
  double d2;
};

/// Candidate (measurement, landmark) pairs inside the gate.
std::vector<Pair> GatedPairs(const Pose& pose, const Mat3& pose_cov,
                             const std::vector<MapLandmark>& map,
                             const std::vector<Measurement>& scan, const Mat2& r,
                             const ScanAssociationOptions& options) {
  std::vector<Pair> pairs;
  const double max_d2 = options.max_landmark_distance * options.max_landmark_distance;
  std::optional<double> log_intensity;
  if (options.new_landmark_intensity > 0.0)
    log_intensity = std::log(options.new_landmark_intensity);
  for (std::size_t i = 0; i < map.size(); ++i) {
    const Landmark& m = map[i].mean;
    const double q = (m - pose.head<2>()).squaredNorm();
    if (q < 1e-18) continue;  // bearing undefined
    if (options.max_landmark_distance > 0.0 && q > max_d2) continue;
    const models::PredictionWithJacobians p = models::PredictWithJacobians(pose, m);
    const Mat2 cross = p.j.hm * map[i].pose_cross * p.j.hx.transpose();
    Mat2 s = p.j.hm * map[i].cov * p.j.hm.transpose() + p.j.hx * pose_cov * p.j.hx.transpose() +
             cross + cross.transpose() + r;
    Symmetrize(s);
    const double log_pd = log_intensity ? std::log(map[i].detection_probability) : 0.0;
    for (std::size_t j = 0; j < scan.size(); ++j) {
      const Vec2 nu(scan[j](0) - p.z_hat(0), WrapAngle(scan[j](1) - p.z_hat(1)));
      const Gaussian2Eval g = EvalGaussian2(nu, s);
      const double d2 = g.mahalanobis2;
      if (!(std::isfinite(d2) && d2 >= 0.0 && d2 < options.gate_chi2)) continue;
      if (log_intensity && !(log_pd + g.log_pdf >= *log_intensity)) continue;
      pairs.push_back({static_cast<int>(j), static_cast<int>(i), d2});
    }
  }
  return pairs;
}

}  // namespace

ScanAssociation AssociateScan(const Pose& pose, const Mat3& pose_cov,
                              const std::vector<MapLandmark>& map,
                              const std::vector<Measurement>& scan, const Mat2& measurement_cov,
                              const ScanAssociationOptions& options) {
  if (!(options.gate_chi2 > 0.0)) {
    throw std::invalid_argument("ScanAssociationOptions.gate_chi2: expected > 0");
  }
  if (!(options.new_landmark_intensity >= 0.0)) {
    throw std::invalid_argument("ScanAssociationOptions.new_landmark_intensity: expected >= 0");
  }
  if (options.jcbb_max_nodes < 1) {
    throw std::invalid_argument("ScanAssociationOptions.jcbb_max_nodes: expected >= 1");
  }
  std::vector<Pair> pairs = GatedPairs(pose, pose_cov, map, scan, measurement_cov, options);
  if (options.assignment == ScanAssignment::kJointCompatibility) {
    std::vector<GatedPair> gated;
    gated.reserve(pairs.size());
    for (const Pair& p : pairs) gated.push_back({p.measurement, p.landmark, p.d2});
    return JointCompatibleAssociation(
        pose, pose_cov, map, scan, measurement_cov, gated,
        {options.gate_chi2, options.jcbb_max_nodes, options.jcbb_null_intensity});
  }
  std::sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) {
    if (a.d2 != b.d2) return a.d2 < b.d2;
    if (a.measurement != b.measurement) return a.measurement < b.measurement;
    return a.landmark < b.landmark;
  });
  ScanAssociation out;
  out.landmark.assign(scan.size(), kUnassociated);
  out.mahalanobis2.assign(scan.size(), 0.0);
  out.gated.assign(scan.size(), 0);
  for (const Pair& p : pairs) ++out.gated[static_cast<std::size_t>(p.measurement)];
  std::vector<bool> used(map.size(), false);
  for (const Pair& p : pairs) {
    const auto j = static_cast<std::size_t>(p.measurement);
    const auto i = static_cast<std::size_t>(p.landmark);
    if (out.landmark[j] != kUnassociated || used[i]) continue;
    out.landmark[j] = p.landmark;
    out.mahalanobis2[j] = p.d2;
    used[i] = true;
  }
  return out;
}

LandmarkStatus ClassifyLandmark(const LandmarkSupport& support,
                                const ConfirmationOptions& options) {
  if (static_cast<double>(support.detections) < options.min_detection_ratio * support.expected) {
    return LandmarkStatus::kDeleted;
  }
  return support.detections >= options.min_observations ? LandmarkStatus::kConfirmed
                                                        : LandmarkStatus::kTentative;
}

std::vector<int> CollapsedLandmarks(const Association& association, const std::vector<Pose>& poses,
                                    const std::vector<Landmark>& landmarks, std::size_t first_step,
                                    double min_range) {
  std::vector<bool> collapsed(landmarks.size(), false);
  for (std::size_t k = first_step; k < association.size(); ++k) {
    for (int i : association[k]) {
      if (i == kUnassociated) continue;
      const auto li = static_cast<std::size_t>(i);
      if ((landmarks.at(li) - poses.at(k).head<2>()).norm() < min_range) collapsed[li] = true;
    }
  }
  std::vector<int> out;
  for (std::size_t i = 0; i < collapsed.size(); ++i) {
    if (collapsed[i]) out.push_back(static_cast<int>(i));
  }
  return out;
}

}  // namespace phdslam::reference
