// Normalised innovation squared (NIS) of the measurements a filter associated at one step, from
// the innovation covariance the filter itself used: nu' S^-1 nu, chi-square with 2 degrees of
// freedom per range-bearing measurement when the filter is consistent.
#pragma once

#include <cmath>

#include "src/core/gaussian.h"
#include "src/core/types.h"

namespace phdslam::filters {

struct InnovationStats {
  double nis_sum = 0.0;  ///< sum over the step's associated measurements of nu' S^-1 nu
  int count = 0;         ///< measurements in the sum

  /// Adds one innovation (bearing residual already wrapped) with its covariance; an S that is not
  /// positive definite or a non-finite NIS is left out. For every finite S the NIS is Eigen's
  /// LLT<Mat2>::matrixL().solve(nu).squaredNorm() bit for bit (Cholesky2).
  void Add(const Vec2& nu, const Mat2& s) {
    const Cholesky2 factor(s);
    if (!factor.positive_definite()) return;
    const double nis = factor.SolveLower(nu).squaredNorm();
    if (!std::isfinite(nis)) return;
    nis_sum += nis;
    ++count;
  }
};

}  // namespace phdslam::filters
