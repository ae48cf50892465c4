// The weighted spread of pose samples about an estimate, sum_i w_i (x_i - c)(x_i - c)^T: the
// pose covariance the particle filters report beside their estimate (the classical
// particle-spread covariance of the `nees` column), shared by the skeleton and single-cluster
// PHD SLAM. Headings are unwrapped numbers in this project, so differences are plain.
#pragma once

#include <cstddef>
#include <span>

#include "src/core/types.h"

namespace phdslam::filters {

/// `pose_of(items[i])` is the i-th sample, `weights` its normalised weight.
template <class Items, class PoseOf>
Mat3 WeightedSpread(const Items& items, std::span<const double> weights, const Pose& centre,
                    PoseOf pose_of) {
  Mat3 spread = Mat3::Zero();
  for (std::size_t i = 0; i < weights.size(); ++i) {
    const Vec3 d = pose_of(items[i]) - centre;
    spread += weights[i] * d * d.transpose();
  }
  return spread;
}

}  // namespace phdslam::filters
