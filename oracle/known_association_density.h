// The oracle's importance density: the partitioned IPL (src/filters/ipl.h) from the predicted pose
// Gaussian over the measurements whose landmark is known and already in the map, taken in the
// order of the landmark view (ascending landmark index). With no such measurement, or when the
// IPL takes no step, the proposal is the prior itself. Its best association is the known one.
#pragma once

#include "src/filters/importance_density.h"
#include "src/filters/ipl.h"

namespace phdslam::oracle {

class KnownAssociationIplDensity final : public filters::ImportanceDensity {
 public:
  explicit KnownAssociationIplDensity(filters::IplOptions options) : options_(options) {}

  /// Requires ProposalInput::known_association (one entry per measurement).
  [[nodiscard]] filters::ProposalOutput Build(const filters::ProposalInput& input) const override;

  /// log N(x; mu, Sigma) of the single Gaussian, evaluated through its own Cholesky factor.
  [[nodiscard]] double LogDensity(const filters::PreparedProposal& proposal,
                                  const Pose& x) const override;

 private:
  filters::IplOptions options_;
};

}  // namespace phdslam::oracle
