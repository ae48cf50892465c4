#include "reference/mrpt/fastslam_options.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace phdslam::reference {

std::string ToString(ResamplingScheme s) {
  switch (s) {
    case ResamplingScheme::kMultinomial:
      return "multinomial";
    case ResamplingScheme::kResidual:
      return "residual";
    case ResamplingScheme::kStratified:
      return "stratified";
    case ResamplingScheme::kSystematic:
      break;
  }
  return "systematic";
}

ResamplingScheme ParseResamplingScheme(const std::string& s, const std::string& field) {
  if (s == "multinomial") return ResamplingScheme::kMultinomial;
  if (s == "residual") return ResamplingScheme::kResidual;
  if (s == "stratified") return ResamplingScheme::kStratified;
  if (s == "systematic") return ResamplingScheme::kSystematic;
  throw std::invalid_argument(field +
                              ": expected \"multinomial\", \"residual\", \"stratified\" or "
                              "\"systematic\", got \"" +
                              s + "\"");
}

void FastSlamOptions::Validate() const {
  ValidateChi2Quantile(ic_chi2_quantile, "fastslam ic_chi2_quantile");
  if (new_landmark_log_likelihood && !std::isfinite(*new_landmark_log_likelihood)) {
    throw std::invalid_argument("fastslam new_landmark_log_likelihood: expected a finite number");
  }
  if (confirm_associations < 0) {
    throw std::invalid_argument("fastslam confirm_associations: expected >= 0, got " +
                                std::to_string(confirm_associations));
  }
  if (tentative_steps < 1) {
    throw std::invalid_argument("fastslam tentative_steps: expected >= 1, got " +
                                std::to_string(tentative_steps));
  }
  if (!(ess_threshold_fraction >= 0.0 && ess_threshold_fraction <= 1.0)) {
    throw std::invalid_argument(
        "fastslam ess_threshold_fraction: expected a value in [0, 1], got " +
        std::to_string(ess_threshold_fraction));
  }
  if (!(pose_regulariser_diag.array() >= 0.0).all() || !pose_regulariser_diag.allFinite()) {
    throw std::invalid_argument(
        "fastslam pose_regulariser_diag: expected three finite, non-negative variances");
  }
}

}  // namespace phdslam::reference
