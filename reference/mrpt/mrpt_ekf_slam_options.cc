#include "reference/mrpt/mrpt_ekf_slam_options.h"

#include <stdexcept>
#include <string>

namespace phdslam::reference {

void MrptEkfSlamOptions::Validate() const {
  ValidateChi2Quantile(ic_chi2_quantile, "mrpt-ekf ic_chi2_quantile");
  if (prune_after_steps < 0) {
    throw std::invalid_argument("mrpt-ekf prune_after_steps: expected >= 0, got " +
                                std::to_string(prune_after_steps));
  }
  if (prune_min_associations < 1) {
    throw std::invalid_argument("mrpt-ekf prune_min_associations: expected >= 1, got " +
                                std::to_string(prune_min_associations));
  }
  if (min_associations < 0) {
    throw std::invalid_argument("mrpt-ekf min_associations: expected >= 0, got " +
                                std::to_string(min_associations));
  }
}

}  // namespace phdslam::reference
