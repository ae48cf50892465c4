// The files of `phdslam parent-weights`: the parent weightings compared at one step and,
// optionally, their effective sample sizes over every N-th step, written into a folder (the
// report draws them when the folder is a results folder).
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "datasets/scenario.h"
#include "validation/runner/studies/parent_weights.h"

namespace phdslam::validation {

inline constexpr const char* kParentWeightsCsvFile = "parent_weights.csv";
inline constexpr const char* kParentWeightsJsonFile = "parent_weights.json";
inline constexpr const char* kParentWeightsStepsCsvFile = "parent_weights_steps.csv";
inline constexpr const char* kParentWeightsStepsJsonFile = "parent_weights_steps.json";

struct ParentWeightsStudy {
  std::string scenario;  ///< the scenario's name, recorded in the JSON files
  std::uint64_t seed = 1;
  /// step, parents and spread; the stream seed is derived from `seed` (ParentWeightsStreamSeed).
  ParentWeightsSettings settings;
  std::size_t every = 0;  ///< also compare at steps every, 2 every, ... (0: only settings.step)
  std::size_t until = 0;  ///< the last of those steps (0 or past the end: the scenario's last)
};

/// What WriteParentWeightsStudy wrote, for the command line's message.
struct ParentWeightsOutput {
  nlohmann::json at_step;  ///< the content of parent_weights.json
  std::size_t parents = 0;
  std::optional<nlohmann::json> over_steps;  ///< parent_weights_steps.json, with every > 0
  std::size_t steps_compared = 0;            ///< its rows
};

/// The random stream of the filter run and the parent draws of Monte Carlo seed `seed`.
std::uint64_t ParentWeightsStreamSeed(std::uint64_t seed);

/// Compares the parent weightings of `scenario` (Monte Carlo seed study.seed) at
/// study.settings.step and writes parent_weights.csv (ParentWeightsCsv) and parent_weights.json
/// (ParentWeightsJson with "scenario" and "seed") into `out` (created if needed); with
/// study.every > 0 also parent_weights_steps.csv (StepEssCsv) and parent_weights_steps.json
/// (StepEssJson with "scenario", "seed", "parents", "spread" and "every") over steps every,
/// 2 every, ... up to `until`. Files are written atomically. Throws what
/// CompareParentWeightingAtStep throws for settings it refuses.
ParentWeightsOutput WriteParentWeightsStudy(const datasets::Scenario& scenario,
                                            const ParentWeightsStudy& study,
                                            const std::filesystem::path& out);

}  // namespace phdslam::validation
