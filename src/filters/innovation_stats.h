// Normalised innovation squared (NIS) of the measurements a filter associated at one step, from
// the innovation covariance the filter itself used: nu' S^-1 nu, chi-square with 2 degrees of
// freedom per range-bearing measurement when the filter is consistent.
#pragma once

#include <Eigen/Cholesky>

#include "src/core/types.h"

namespace phdslam::filters {

struct InnovationStats {
  double nis_sum = 0.0;  ///< sum over the step's associated measurements of nu' S^-1 nu
  int count = 0;         ///< measurements in the sum

  /// Adds one innovation (bearing residual already wrapped) with its covariance; an S that is not
  /// positive definite or a non-finite NIS is left out.
  void Add(const Vec2& nu, const Mat2& s) {
    const Eigen::LLT<Mat2> llt(s);
    if (llt.info() != Eigen::Success) return;
    const double nis = llt.matrixL().solve(nu).squaredNorm();
    if (!std::isfinite(nis)) return;
    nis_sum += nis;
    ++count;
  }
};

}  // namespace phdslam::filters
