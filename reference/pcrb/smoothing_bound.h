// The smoothing bound (docs/algorithms/pcrb.md section 3): the marginals of the inverse Fisher
// information of the whole graph (every pose, the map) at the truth. Computed exactly, without
// forming the graph's dense inverse, by the law of total covariance over the map:
//
//   Cov(x_k | Z) = C_k + B_k Cov(m | Z) B_k^T,
//
// where C_k is the covariance of x_k given the map and all the data (a pose-only two-filter
// smoother: a forward covariance filter and a backward information filter whose prediction is the
// Schur complement over the control noise, so only Q_u^-1 is inverted, never a rank-2 pose-space
// matrix), B_k = d E[x_k | m, Z] / dm, and Cov(m | Z) the map's bound after the last step
// (filtering_bound.h).
#pragma once

#include <vector>

#include "reference/pcrb/filtering_bound.h"
#include "reference/pcrb/linearised_slam.h"
#include "src/core/types.h"

namespace phdslam::reference::pcrb {

/// Per step, the smoothing bound on the pose covariance. `filtering` is
/// ComputeFilteringBound(model) (its final map covariance is the map's smoothing bound).
/// Throws std::invalid_argument when Q_u is not positive definite.
std::vector<Mat3> ComputeSmoothingBound(const LinearisedSlam& model,
                                        const FilteringBound& filtering);

}  // namespace phdslam::reference::pcrb
