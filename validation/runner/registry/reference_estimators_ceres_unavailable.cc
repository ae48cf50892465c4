// Built instead of reference_estimators_ceres.cc when Ceres is not available.
#include "validation/runner/registry/estimator_registry.h"

namespace phdslam::validation {

std::vector<EstimatorEntry> CeresEstimators() { return {}; }

}  // namespace phdslam::validation
