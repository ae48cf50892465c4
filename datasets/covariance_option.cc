#include "datasets/covariance_option.h"

#include <Eigen/Cholesky>
#include <stdexcept>

namespace phdslam::datasets {

void RequireCovarianceOption(const Mat2& m, const std::string& field) {
  const bool symmetric =
      m.allFinite() && (m - m.transpose()).cwiseAbs().maxCoeff() <= 1e-12 * m.norm();
  if (!symmetric || m.llt().info() != Eigen::Success) {
    throw std::invalid_argument(field +
                                ": expected a finite symmetric positive-definite 2x2 matrix");
  }
}

}  // namespace phdslam::datasets
