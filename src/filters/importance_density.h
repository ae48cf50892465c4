// The one part that varies across the RB-PHD-SLAM family: how the pose proposal is built from the
// predicted pose Gaussian, the particle's map and the scan.
#pragma once

#include <span>
#include <vector>

#include "src/core/types.h"
#include "src/filters/gaussian_mixture_proposal.h"
#include "src/filters/phd_slam_params.h"
#include "src/models/sensor_model.h"
#include "src/phd/gm_phd_map.h"

namespace phdslam::filters {

struct ProposalInput {
  Pose predicted_mean;
  Mat3 predicted_cov;
  const phd::GmPhdMap* map = nullptr;
  std::span<const Measurement> measurements;
  const models::SensorModel* sensor = nullptr;
};

struct ProposalOutput {
  GaussianMixtureProposal mixture;
  /// For each measurement, the active-component index it is assigned to by the highest-weight
  /// data-association hypothesis, or -1 (clutter / not assigned). Empty when not applicable.
  std::vector<int> best_association;
};

class ImportanceDensity {
 public:
  virtual ~ImportanceDensity() = default;
  [[nodiscard]] virtual ProposalOutput Build(const ProposalInput& input) const = 0;
};

/// PHD-SLAM 1.0: the Gaussian-linearised transition density N(mu_0, Sigma_0).
class TransitionDensity final : public ImportanceDensity {
 public:
  [[nodiscard]] ProposalOutput Build(const ProposalInput& input) const override;
};

}  // namespace phdslam::filters
