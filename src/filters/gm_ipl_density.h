// PHD-SLAM 3.0 importance density (docs/algorithms/phd-slam.md section 4.3-4.6): a Gaussian mixture
// over the Murty-ranked data-association hypotheses, each conditioned by the partitioned IPL, plus
// an all-clutter component.
#pragma once

#include "src/filters/importance_density.h"
#include "src/models/range_bearing_model.h"

namespace phdslam::filters {

class GmIplDensity final : public ImportanceDensity {
 public:
  explicit GmIplDensity(const PhdSlamParams& params) : params_(params) {}
  [[nodiscard]] ProposalOutput Build(const ProposalInput& input) const override;

 private:
  PhdSlamParams params_;
};

/// The gated log-gain cost structure of docs/algorithms/phd-slam.md section 4.3, shared by the GM
/// density and PHD-SLAM 2.0b.
struct AssociationCosts {
  std::vector<double> pd;    ///< pD of every active component at the predicted mean
  std::vector<double> miss;  ///< log(1 - pD_i) + eta_i for every active component
  std::vector<int> rows;     ///< active components with at least one gated measurement
  /// h and its Jacobians at the predicted mean, one per row (what the IPL's first iteration uses)
  std::vector<models::PredictionWithJacobians> row_prediction;
  std::vector<int> cols;  ///< measurements gated by at least one component
  Eigen::MatrixXd cost;   ///< rows x (cols + rows): -log gains, +inf forbidden
};
AssociationCosts BuildAssociationCosts(const ProposalInput& input, const PhdSlamParams& params);

}  // namespace phdslam::filters
