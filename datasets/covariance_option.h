// The check every data-set options struct makes of its 2x2 noise covariances.
#pragma once

#include <string>

#include "src/core/types.h"

namespace phdslam::datasets {

/// Throws std::invalid_argument "<field>: expected a finite symmetric positive-definite 2x2
/// matrix" unless `m` is finite, symmetric to 1e-12 relative and has a Cholesky factor.
void RequireCovarianceOption(const Mat2& m, const std::string& field);

}  // namespace phdslam::datasets
