#include "src/filters/phd_slam_params.h"

namespace phdslam::filters {

PhdSlamParams PhdSlamParams::ForScenario(const std::string& scenario, const std::string& variant) {
  PhdSlamParams p;
  if (scenario == "victoria-park") {
    p.map.merge_threshold = 10.0;
    p.ess_threshold_kind = EssThresholdKind::kAbsolute;
    // The paper gives the absolute threshold 1 for 2.0b and 3.0 only. For 1.0 and 2.0a it is not
    // stated; 2.5 (half of N = 5, kept absolute) reproduces their published resampling rates:
    // over clutter seeds 1-4, 1.0 resamples at 40.4 % (N = 5) and 24.9 % (N = 10) against the
    // paper's 40.54 and 25.18 %, 2.0a at 38.1 and 23.8 % against 34.00 and 20.84 %, whereas the
    // threshold 1 gives 1.0 about 3 % at N = 5 and a diverged trajectory (about 178 m).
    p.ess_threshold = (variant == "phd1" || variant == "phd2a") ? 2.5 : 1.0;
  }
  return p;
}

}  // namespace phdslam::filters
