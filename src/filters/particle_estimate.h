// What a particle filter reports of its weighted particles: the highest-weight particle (whose
// pose and map are the estimate) and the weighted spread of the pose samples about the estimate,
// sum_i w_i (x_i - c)(x_i - c)^T (the classical particle-spread covariance of the `nees` column).
// Shared by the skeleton (particle_filter.h), single-cluster PHD SLAM and the MRPT FastSLAM
// baselines. Headings are unwrapped numbers in this project, so differences are plain.
#pragma once

#include <cstddef>
#include <span>

#include "src/core/types.h"

namespace phdslam::filters {

/// The index of the item with the highest `weight_of(items[i])`, the first one on ties; 0 for an
/// empty range.
template <class Items, class WeightOf>
std::size_t HighestWeightIndex(const Items& items, WeightOf weight_of) {
  std::size_t best = 0;
  for (std::size_t i = 1; i < items.size(); ++i) {
    if (weight_of(items[i]) > weight_of(items[best])) best = i;
  }
  return best;
}

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
