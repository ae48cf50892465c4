#include "src/filters/importance_density.h"

namespace phdslam::filters {

ProposalOutput PriorProposal(const ProposalInput& input) {
  ProposalOutput out;
  out.mixture.Add(0.0, input.predicted_mean, input.predicted_cov);
  out.best_association.assign(input.measurements.size(), -1);
  return out;
}

ProposalOutput TransitionDensity::Build(const ProposalInput& input) const {
  ProposalOutput out;
  out.mixture.Add(0.0, input.predicted_mean, input.predicted_cov);
  return out;
}

}  // namespace phdslam::filters
