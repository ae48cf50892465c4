// Particle-weight strategies of RB-PHD-SLAM (Mullane, Vo, Adams & Vo, IEEE T-RO 2011, section
// IV-B), selected by PhdSlamParams::weighting.
//
// The RFS measurement likelihood of a particle is g(Z | M, X) p(M | Z_{k-1}) / p(M | Z_k) for any
// map M; with Poisson map densities it is evaluated at a chosen M:
//  - empty map (M = {}):
//      ln g = sum_z ln kappa(z) + m_k - m_{k|k-1} - lambda;
//  - single feature (M = {m*}, m* the mean of the highest-weight component of the updated
//    intensity with pD(m*) > 0 at the sampled pose):
//      ln g = sum_z ln kappa(z) + ln[(1 - pD(m*)) + pD(m*) sum_z g(z | m*, X) / kappa(z)]
//             + ln v_{k|k-1}(m*) - ln v_k(m*) + m_k - m_{k|k-1} - lambda,
// where m = integral of v (the sum of the component weights), kappa the clutter intensity,
// lambda = max(clutter_rate, kMinFilterClutterRate) its integral and g(z | m*, X) = N(z; h(X, m*),
// R) with the bearing residual wrapped. Without a detectable component the single-feature strategy
// falls back to the empty map. The intensities include the passive components (unchanged by the
// update) and the births of the step.
#pragma once

#include <span>

#include "src/core/types.h"
#include "src/models/sensor_model.h"
#include "src/phd/gaussian_component.h"

namespace phdslam::filters {

enum class RbPhdWeighting {
  /// PHD-SLAM 3.0 eq. 46 as the reference code evaluates it (the map update's log-likelihood).
  kPaper46,
  /// Mullane et al.'s empty-map strategy.
  kEmptyMap,
  /// Mullane et al.'s single-feature map strategy.
  kSingleFeature,
};

/// The intensities a strategy compares: before and after the measurement update of one particle.
struct PhdIntensityPair {
  std::span<const phd::GaussianComponent> predicted;  ///< active components before the update
  std::span<const phd::GaussianComponent> updated;    ///< active components after the update
  std::span<const phd::GaussianComponent> passive;    ///< components outside the enlarged FOV
};

/// ln of the sum of the component weights.
double LogMass(std::span<const phd::GaussianComponent> components);

/// ln v(m) of a Gaussian-mixture intensity at the point m (-inf for an empty mixture).
double LogIntensityAt(std::span<const phd::GaussianComponent> components, const Landmark& m);

/// The empty-map strategy's log-likelihood.
double EmptyMapLogWeight(const PhdIntensityPair& v, std::span<const Measurement> measurements,
                         const models::SensorModel& sensor);

/// The single-feature strategy's log-likelihood at the sampled pose.
double SingleFeatureLogWeight(const PhdIntensityPair& v, const Pose& pose,
                              std::span<const Measurement> measurements,
                              const models::SensorModel& sensor);

/// The strategy's log-likelihood; kPaper46 returns `paper46_log_likelihood` unchanged.
double RbPhdLogWeight(RbPhdWeighting weighting, double paper46_log_likelihood,
                      const PhdIntensityPair& v, const Pose& pose,
                      std::span<const Measurement> measurements, const models::SensorModel& sensor);

}  // namespace phdslam::filters
