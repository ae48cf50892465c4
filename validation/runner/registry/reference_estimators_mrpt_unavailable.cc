// Built instead of reference_estimators_mrpt.cc when MRPT is not available.
#include "validation/runner/registry/estimator_registry.h"

namespace phdslam::validation {

std::vector<EstimatorEntry> MrptEstimators() { return {}; }

}  // namespace phdslam::validation
