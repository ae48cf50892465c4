#include "validation/runner/evaluation/map_ospa_trace.h"

#include "validation/metrics/gospa.h"

namespace phdslam::validation {
namespace {

bool HasOriginLabels(const datasets::Scenario& scenario) {
  for (const datasets::ScenarioStep& s : scenario.steps) {
    if (s.origin.size() != s.data.measurements.size()) return false;
  }
  return true;
}

}  // namespace

std::vector<double> MapOspaTrace(const RunRecord& record, const datasets::Scenario& scenario,
                                 double cutoff) {
  std::vector<double> trace;
  if (record.step_maps.size() != scenario.steps.size() || scenario.truth.landmarks.empty() ||
      !HasOriginLabels(scenario)) {
    return trace;
  }
  std::vector<bool> seen(scenario.truth.landmarks.size(), false);
  std::vector<Vec2> detected;
  trace.reserve(scenario.steps.size());
  for (std::size_t k = 0; k < scenario.steps.size(); ++k) {
    for (int origin : scenario.steps[k].origin) {
      if (origin < 0 || static_cast<std::size_t>(origin) >= seen.size() || seen[origin]) continue;
      seen[origin] = true;
      detected.push_back(scenario.truth.landmarks[origin]);
    }
    trace.push_back(Ospa(detected, record.step_maps[k], cutoff, kMapOspaOrder).ospa);
  }
  return trace;
}

}  // namespace phdslam::validation
