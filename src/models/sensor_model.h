// Range-bearing sensor: field of view, detection probability, noise and clutter
// (docs/algorithms/models.md section 3.3-3.6 and section 10).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "src/core/angles.h"
#include "src/core/types.h"

namespace phdslam::models {

enum class DetectionProfile {
  kConstant,     ///< pD = pd_max inside the FOV (synthetic scenario).
  kLinearRange,  ///< pD = pd_max (1 - r / fov_range) inside the FOV (Victoria Park).
};

/// The space the clutter density 1 / V of ClutterIntensity() = lambda / V is defined over.
enum class ClutterSpace {
  /// V = Theta_fov R_fov^2, the Cartesian area of the FOV sector, used as a density in (r, phi)
  /// (the PHD-SLAM reference code's; docs/algorithms/models.md section 3.6). Every scenario but
  /// glmb-sim.
  kSectorArea,
  /// V = 2 Theta_fov R_fov, the (r, phi) box [0, R_fov] x [-Theta_fov, Theta_fov]: the exact
  /// intensity of clutter drawn uniform in range and bearing and not thinned (glmb-sim; the
  /// docs/algorithms/models.md section 3.6).
  kRangeBearingBox,
};

struct SensorModel {
  double fov_range = 150.0;                ///< m
  double fov_half_angle = DegToRad(90.0);  ///< rad
  double range_buffer = 10.0;              ///< m, enlarges the FOV for the active set only
  double angle_buffer = DegToRad(10.0);    ///< rad, likewise
  DetectionProfile profile = DetectionProfile::kConstant;
  double pd_max = 0.95;               ///< constant pD, or the pD at zero range
  double pd_nominal = 0.95;           ///< the nominal pD used by the estimate threshold
  Mat2 noise_cov = Mat2::Identity();  ///< R
  double clutter_rate = 5.0;          ///< expected clutter points per scan (lambda)
  ClutterSpace clutter_space = ClutterSpace::kSectorArea;  ///< what ClutterIntensity() divides by

  /// The smallest clutter rate the filters' likelihoods use (points per scan). The RB-PHD-SLAM
  /// family explains every measurement no component accounts for (clutter, but also a landmark's
  /// first detection) by the clutter intensity, so lambda_c = 0 would give those measurements zero
  /// likelihood and every particle the weight 0 (log -inf). A clutter-free scenario
  /// (clutter_rate = 0: the clutter sensitivity sweep) is filtered with this rate instead; it is
  /// far below every rate that occurs otherwise and changes nothing for them.
  static constexpr double kMinFilterClutterRate = 1e-3;

  /// lambda_c = lambda / V, lambda at least kMinFilterClutterRate, used by the filters as a
  /// density in (r, phi). V is the Cartesian area of the FOV sector Theta_fov R_fov^2 (reference
  /// docs/algorithms/models.md section 3.6, kept to reproduce the published numbers) or, for
  /// ClutterSpace::kRangeBearingBox, the (r, phi) box 2 Theta_fov R_fov.
  [[nodiscard]] double ClutterIntensity() const {
    const double rate = std::max(clutter_rate, kMinFilterClutterRate);
    if (clutter_space == ClutterSpace::kRangeBearingBox) {
      return rate / (2.0 * fov_half_angle * fov_range);
    }
    return rate / (fov_half_angle * fov_range * fov_range);
  }

  /// pD evaluated at the landmark point m from pose x (a point evaluation,
  /// docs/algorithms/models.md section 3.3).
  [[nodiscard]] double DetectionProbability(const Pose& x, const Landmark& m) const;
  /// True when m lies inside the FOV enlarged by the buffers (the active-set test,
  /// docs/algorithms/phd-slam.md section 3.4).
  [[nodiscard]] bool InEnlargedFov(const Pose& x, const Landmark& m) const;
};

/// The FOV tests of a SensorModel at one pose, with the pose's trigonometry precomputed. The
/// bearing test |wrap(atan2(dy, dx) - theta)| <= half-angle is evaluated as
/// d . heading >= |d| cos(half-angle), which is equivalent for half-angles in [0, pi] and needs
/// no atan2. Both tests are inclusive.
class FovView {
 public:
  FovView(const SensorModel& sensor, const Pose& x)
      : sensor_(&sensor),
        x_(x(0)),
        y_(x(1)),
        cos_(std::cos(x(2))),
        sin_(std::sin(x(2))),
        range2_(sensor.fov_range * sensor.fov_range),
        cos_half_(std::cos(sensor.fov_half_angle)),
        enlarged_range2_((sensor.fov_range + sensor.range_buffer) *
                         (sensor.fov_range + sensor.range_buffer)),
        cos_enlarged_half_(
            std::cos(std::min(sensor.fov_half_angle + sensor.angle_buffer, std::numbers::pi))) {}

  [[nodiscard]] double DetectionProbability(const Landmark& m) const {
    const double dx = m(0) - x_;
    const double dy = m(1) - y_;
    const double r2 = dx * dx + dy * dy;
    if (r2 > range2_) return 0.0;
    const double r = std::sqrt(r2);
    if (dx * cos_ + dy * sin_ < r * cos_half_) return 0.0;
    if (sensor_->profile == DetectionProfile::kConstant) return sensor_->pd_max;
    return sensor_->pd_max * (1.0 - r / sensor_->fov_range);
  }

  [[nodiscard]] bool InEnlargedFov(const Landmark& m) const {
    const double dx = m(0) - x_;
    const double dy = m(1) - y_;
    const double r2 = dx * dx + dy * dy;
    if (r2 > enlarged_range2_) return false;
    return dx * cos_ + dy * sin_ >= std::sqrt(r2) * cos_enlarged_half_;
  }

  /// True only when every point of the axis-aligned box [lo, hi] is surely outside the enlarged
  /// FOV (beyond its range, with a relative margin far above rounding), so InEnlargedFov is false
  /// for all of them; false when unsure.
  [[nodiscard]] bool BoxSurelyOutsideEnlargedFov(const Landmark& lo, const Landmark& hi) const {
    const double dx = std::max({lo(0) - x_, 0.0, x_ - hi(0)});
    const double dy = std::max({lo(1) - y_, 0.0, y_ - hi(1)});
    return dx * dx + dy * dy > enlarged_range2_ * (1.0 + 1e-6) + 1e-6;
  }

 private:
  const SensorModel* sensor_;
  double x_;
  double y_;
  double cos_;
  double sin_;
  double range2_;
  double cos_half_;
  double enlarged_range2_;
  double cos_enlarged_half_;
};

/// log pD and log(1 - pD) of the last pD given, recomputed only when pD changes: with a constant
/// detection profile the hot loops take the two logarithms once instead of once per component.
class LogDetectionTerms {
 public:
  void Set(double pd) {
    if (pd == pd_) return;
    pd_ = pd;
    log_pd_ = std::log(pd);
    log_miss_ = std::log1p(-pd);
  }
  [[nodiscard]] double log_pd() const { return log_pd_; }      ///< log pD
  [[nodiscard]] double log_miss() const { return log_miss_; }  ///< log(1 - pD)

 private:
  double pd_ = std::numeric_limits<double>::quiet_NaN();
  double log_pd_ = 0.0;
  double log_miss_ = 0.0;
};

inline double SensorModel::DetectionProbability(const Pose& x, const Landmark& m) const {
  return FovView(*this, x).DetectionProbability(m);
}
inline bool SensorModel::InEnlargedFov(const Pose& x, const Landmark& m) const {
  return FovView(*this, x).InEnlargedFov(m);
}

}  // namespace phdslam::models
