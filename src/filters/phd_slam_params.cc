#include "src/filters/phd_slam_params.h"

namespace phdslam::filters {

PhdSlamParams PhdSlamParams::ForScenario(const std::string& scenario) {
  PhdSlamParams p;
  if (scenario == "victoria-park") {
    p.map.merge_threshold = 10.0;
    p.ess_threshold_kind = EssThresholdKind::kAbsolute;
    p.ess_threshold = 1.0;
  }
  return p;
}

}  // namespace phdslam::filters
