// One Gaussian component of a GM-PHD landmark map, with a natural-log weight.
#pragma once

#include "src/core/types.h"

namespace phdslam::phd {

struct GaussianComponent {
  Landmark mean = Landmark::Zero();
  Mat2 cov = Mat2::Identity();
  double log_weight = 0.0;  ///< eta: natural logarithm of the component weight
};

}  // namespace phdslam::phd
