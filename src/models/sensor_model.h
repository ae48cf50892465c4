// Range-bearing sensor: field of view, detection probability, noise and clutter
// (reference notes sections 9 and 17).
#pragma once

#include <cmath>
#include <numbers>

#include "src/core/angles.h"
#include "src/core/types.h"

namespace phdslam::models {

enum class DetectionProfile {
  kConstant,     ///< pD = pd_max inside the FOV (synthetic scenario).
  kLinearRange,  ///< pD = pd_max (1 - r / fov_range) inside the FOV (Victoria Park).
};

struct SensorModel {
  double fov_range = 150.0;                  ///< m
  double fov_half_angle = DegToRad(90.0);    ///< rad
  double range_buffer = 10.0;                ///< m, enlarges the FOV for the active set only
  double angle_buffer = DegToRad(10.0);      ///< rad, likewise
  DetectionProfile profile = DetectionProfile::kConstant;
  double pd_max = 0.95;                      ///< constant pD, or the pD at zero range
  double pd_nominal = 0.95;                  ///< the nominal pD used by the estimate threshold
  Mat2 noise_cov = Mat2::Identity();         ///< R
  double clutter_rate = 5.0;                 ///< expected clutter points per scan (lambda)

  /// lambda_c = lambda / (Theta_fov R_fov^2): lambda over the Cartesian area of the FOV sector,
  /// used by the filters as a density in (r, phi) (reference notes 10.1, kept to reproduce the
  /// published numbers).
  [[nodiscard]] double ClutterIntensity() const {
    return clutter_rate / (fov_half_angle * fov_range * fov_range);
  }

  /// pD evaluated at the landmark point m from pose x (a point evaluation, notes section 9).
  [[nodiscard]] double DetectionProbability(const Pose& x, const Landmark& m) const {
    const double dx = m(0) - x(0);
    const double dy = m(1) - x(1);
    const double r2 = dx * dx + dy * dy;
    if (r2 > fov_range * fov_range) return 0.0;
    if (std::abs(WrapAngle(std::atan2(dy, dx) - x(2))) > fov_half_angle) return 0.0;
    if (profile == DetectionProfile::kConstant) return pd_max;
    return pd_max * (1.0 - std::sqrt(r2) / fov_range);
  }

  /// True when m lies inside the FOV enlarged by the buffers (the active-set test, notes 12.5).
  [[nodiscard]] bool InEnlargedFov(const Pose& x, const Landmark& m) const {
    const double dx = m(0) - x(0);
    const double dy = m(1) - x(1);
    const double rr = fov_range + range_buffer;
    if (dx * dx + dy * dy > rr * rr) return false;
    return std::abs(WrapAngle(std::atan2(dy, dx) - x(2))) <= fov_half_angle + angle_buffer;
  }
};

}  // namespace phdslam::models
