// Entry-level quantities of the joint prediction/update (docs/algorithms/glmb-slam.md section 4.1),
// computed once per entry at one pose and shared by every hypothesis that holds the entry.
#pragma once

#include <optional>
#include <span>
#include <vector>

#include "src/core/types.h"
#include "src/glmb/track.h"
#include "src/models/sensor_model.h"

namespace phdslam::glmb {

/// One gated (entry, measurement) pair.
struct DetectionTerm {
  int measurement = 0;        ///< index j into the scan
  double log_q = 0.0;         ///< log g(z_j | entry): log sum_c alpha_c N(z_j; h(m_c), S_c)
  Vec2 nu = Vec2::Zero();     ///< innovation of the heaviest gated component (bearing wrapped)
  Mat2 s = Mat2::Identity();  ///< its innovation covariance
};

struct EntryTerms {
  double pd = 0.0;      ///< detection probability at the entry's point (0 outside the FOV)
  bool in_fov = false;  ///< the point test on the heaviest component's mean
  std::vector<DetectionTerm> detections;  ///< gated measurements, ascending index
};

/// What the entry terms depend on besides the entry.
struct MeasurementSetup {
  const models::SensorModel* sensor = nullptr;
  Mat2 noise_cov = Mat2::Identity();  ///< R
  /// Pose covariance entering the innovation covariance, H_x Sigma H_x' (zero for the map update
  /// at a sampled pose; the predicted Sigma_0 in the 2.0 proposal pass,
  /// docs/algorithms/glmb-slam.md section 6.3).
  Mat3 pose_cov = Mat3::Zero();
  double gate = 32.236;  ///< threshold on the squared Mahalanobis distance
};

/// The terms of `track` at pose x. A component gates z_j when nu' S^-1 nu <= gate; the pair gates
/// when some component does, and q sums the gated components.
EntryTerms ComputeEntryTerms(const Track& track, const Pose& x,
                             std::span<const Measurement> measurements,
                             const MeasurementSetup& setup);

/// The EKF child of `track` detected by z (pose covariance ignored: the update at a sampled
/// pose): every component updated in Joseph form and symmetrised, weights proportional to
/// alpha_c q_c over the components that gate. nullopt when no component gates.
std::optional<Track> DetectionChild(const Track& track, const Pose& x, const Measurement& z,
                                    const MeasurementSetup& setup);

}  // namespace phdslam::glmb
