#include "oracle/known_association_density.h"

#include <limits>
#include <stdexcept>
#include <vector>

#include "src/core/gaussian.h"

namespace phdslam::oracle {

filters::ProposalOutput KnownAssociationIplDensity::Build(
    const filters::ProposalInput& input) const {
  if (input.known_association.size() != input.measurements.size()) {
    throw std::invalid_argument(
        "known-association density: the association must name every measurement");
  }
  filters::ProposalOutput out;
  out.best_association.assign(input.known_association.begin(), input.known_association.end());
  // The measurement of every landmark in the view, in view order.
  std::vector<int> measurement_of(input.landmarks.size(), -1);
  for (std::size_t j = 0; j < input.known_association.size(); ++j) {
    const int c = input.known_association[j];
    if (c >= 0) measurement_of[c] = static_cast<int>(j);
  }
  std::vector<filters::IplPair> pairs;
  for (std::size_t c = 0; c < input.landmarks.size(); ++c) {
    if (measurement_of[c] < 0) continue;
    pairs.push_back(
        {input.landmarks[c].mean, input.landmarks[c].cov, input.measurements[measurement_of[c]]});
  }
  if (!pairs.empty()) {
    const filters::IplResult ipl = filters::PartitionedIpl(
        input.predicted_mean, input.predicted_cov, pairs, input.sensor->noise_cov, options_);
    if (ipl.iterations > 0) {
      out.mixture.Add(0.0, ipl.mean, ipl.cov);
      return out;
    }
  }
  out.mixture.Add(0.0, input.predicted_mean, input.predicted_cov);
  return out;
}

double KnownAssociationIplDensity::LogDensity(const filters::PreparedProposal& proposal,
                                              const Pose& x) const {
  const auto log_q =
      LogNormalPdf<3>(x, proposal.mixture.means.front(), proposal.mixture.covs.front());
  // The skeleton calls this only after drawing x through the same covariance's Cholesky factor.
  return log_q ? *log_q : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace phdslam::oracle
