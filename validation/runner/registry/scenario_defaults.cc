#include "validation/runner/registry/scenario_defaults.h"

#include <algorithm>

namespace phdslam::validation {

const std::vector<ScenarioDefaultsRow>& ScenarioDefaultsTable() {
  static const std::vector<ScenarioDefaultsRow> table = {
      {"victoria-park",
       {"phd1", "phd2a", "phd2b", "phd3", "rbphd", "scphd"},
       {{"merge_threshold", 10.0}},
       "docs/algorithms/models.md section 10.2: the merge threshold U is 10 on Victoria Park"},
      {"victoria-park",
       {"phd2b", "phd3"},
       {{"ess_threshold_kind", "absolute"}, {"ess_threshold", 1.0}},
       "docs/algorithms/models.md section 10.2: resample when ESS <= 1 on Victoria Park"},
      // The paper gives the absolute threshold 1 for 2.0b and 3.0 only. For 1.0 and 2.0a it is
      // not stated; 2.5 (half of N = 5, kept absolute) reproduces their published resampling
      // rates: over clutter seeds 1-4, 1.0 resamples at 40.4 % (N = 5) and 24.9 % (N = 10)
      // against the paper's 40.54 and 25.18 %, 2.0a at 38.1 and 23.8 % against 34.00 and
      // 20.84 %, whereas the threshold 1 gives 1.0 about 3 % at N = 5 and a diverged trajectory
      // (about 178 m).
      {"victoria-park",
       {"phd1", "phd2a", "rbphd"},
       {{"ess_threshold_kind", "absolute"}, {"ess_threshold", 2.5}},
       "reproduces the published resampling rates of PHD-SLAM 1.0 and 2.0a (not stated)"},
  };
  return table;
}

nlohmann::json ScenarioParameterDefaults(const std::string& scenario,
                                         const std::string& estimator) {
  nlohmann::json merged = nlohmann::json::object();
  for (const ScenarioDefaultsRow& row : ScenarioDefaultsTable()) {
    if (row.scenario != scenario) continue;
    if (std::find(row.estimators.begin(), row.estimators.end(), estimator) ==
        row.estimators.end()) {
      continue;
    }
    merged.update(row.parameters);
  }
  return merged;
}

}  // namespace phdslam::validation
