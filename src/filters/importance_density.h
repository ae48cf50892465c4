// The importance density of the particle-filter skeleton (particle_filter.h): how the pose proposal
// is built from the predicted pose Gaussian, the particle's map and the scan. A density reads the
// map only through the landmark view the skeleton hands it, so densities serve any map kind.
#pragma once

#include <optional>
#include <span>
#include <vector>

#include "src/core/types.h"
#include "src/filters/gaussian_mixture_proposal.h"
#include "src/filters/phd_slam_params.h"
#include "src/models/sensor_model.h"
#include "src/phd/gaussian_component.h"

namespace phdslam::filters {

/// The landmarks of a particle's map that the scan may see, as Gaussians with log-weights (for a
/// GM-PHD map its active components; for a map of labelled tracks, the tracks in view).
using LandmarkView = std::span<const phd::GaussianComponent>;

struct ProposalInput {
  Pose predicted_mean;
  Mat3 predicted_cov;
  LandmarkView landmarks;
  std::span<const Measurement> measurements;
  const models::SensorModel* sensor = nullptr;
  /// When the association is known (the oracle): for each measurement the index into `landmarks`
  /// of its landmark, or -1 (clutter or a first sighting). Empty when it is unknown.
  std::span<const int> known_association;
};

struct ProposalOutput {
  GaussianMixtureProposal mixture;
  /// For each measurement, the index into ProposalInput::landmarks it is assigned to by the
  /// highest-weight data-association hypothesis, or -1 (clutter / not assigned). Empty when not
  /// applicable.
  std::vector<int> best_association;
  /// When set, the skeleton adds this to the particle's log-weight instead of
  /// log N(x; mu0, Sigma0) - log q(x) (a map model's own proposal with its own weight rule, e.g.
  /// delta-GLMB-SLAM 2.0's, glmb/glmb_slam.h). Unset for every importance density.
  std::optional<double> log_weight_increment;
};

class ImportanceDensity {
 public:
  virtual ~ImportanceDensity() = default;
  [[nodiscard]] virtual ProposalOutput Build(const ProposalInput& input) const = 0;
  /// log q(x) of a proposal this density built; by default the mixture density.
  [[nodiscard]] virtual double LogDensity(const PreparedProposal& proposal, const Pose& x) const {
    return LogMixtureDensity(proposal, x);
  }
};

/// The predicted Gaussian N(mu_0, Sigma_0) as the whole proposal, every measurement reported
/// unassigned (-1): what a density proposes when nothing can be associated.
ProposalOutput PriorProposal(const ProposalInput& input);

/// PHD-SLAM 1.0: the Gaussian-linearised transition density N(mu_0, Sigma_0). It associates
/// nothing, so it reports no association (best_association empty).
class TransitionDensity final : public ImportanceDensity {
 public:
  [[nodiscard]] ProposalOutput Build(const ProposalInput& input) const override;
};

}  // namespace phdslam::filters
