#include "validation/runner/studies/parent_weights_output.h"

#include <algorithm>
#include <vector>

#include "src/core/random.h"
#include "validation/runner/io/results_io.h"

namespace phdslam::validation {

std::uint64_t ParentWeightsStreamSeed(std::uint64_t seed) {
  return DeriveSeed(HashName("parent-weights"), seed);
}

namespace {

// Steps every, 2 every, ... up to `until` (0 or past the end: the scenario's last step).
std::vector<std::size_t> EveryNthStep(std::size_t every, std::size_t until, std::size_t steps) {
  const std::size_t last = until == 0 ? steps - 1 : std::min(until, steps - 1);
  std::vector<std::size_t> compared;
  for (std::size_t k = every; k <= last; k += every) compared.push_back(k);
  return compared;
}

}  // namespace

ParentWeightsOutput WriteParentWeightsStudy(const datasets::Scenario& scenario,
                                            const ParentWeightsStudy& study,
                                            const std::filesystem::path& out) {
  ParentWeightsSettings settings = study.settings;
  settings.stream_seed = ParentWeightsStreamSeed(study.seed);
  const ParentWeights w = CompareParentWeightingAtStep(scenario, settings);
  std::filesystem::create_directories(out);
  ParentWeightsOutput output;
  output.at_step = ParentWeightsJson(w);
  output.at_step["scenario"] = study.scenario;
  output.at_step["seed"] = study.seed;
  output.parents = w.poses.size();
  WriteFileAtomically(out / kParentWeightsCsvFile, ParentWeightsCsv(w));
  WriteFileAtomically(out / kParentWeightsJsonFile, JsonFileText(output.at_step));
  if (study.every == 0) return output;

  const std::vector<StepEss> rows = CompareParentWeightingOverSteps(
      scenario, settings, EveryNthStep(study.every, study.until, scenario.steps.size()));
  nlohmann::json summary = StepEssJson(rows);
  summary["scenario"] = study.scenario;
  summary["seed"] = study.seed;
  summary["parents"] = settings.parents;
  summary["spread"] = settings.spread;
  summary["every"] = study.every;
  WriteFileAtomically(out / kParentWeightsStepsCsvFile, StepEssCsv(rows));
  WriteFileAtomically(out / kParentWeightsStepsJsonFile, JsonFileText(summary));
  output.over_steps = std::move(summary);
  output.steps_compared = rows.size();
  return output;
}

}  // namespace phdslam::validation
