// The list-valued keys of an experiment file (particles, seeds, estimators, scenario_options,
// sweep), each read from its YAML node with errors naming the file and line. The experiment key
// table (experiment_keys.cc) reads each key with one of these.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "validation/runner/experiment/experiment.h"
#include "validation/runner/experiment/yaml_file_values.h"

namespace phdslam::validation {

/// A particle count or a list of them, each in [1, kMaxParticles], none twice.
std::vector<int> ParticleList(const YamlKeyValue& value);

/// A range "1-100", a seed, or a list of seeds and ranges: the grammar of --seeds.
std::vector<std::uint64_t> SeedList(const YamlKeyValue& value);

/// Names or {name, set, particles} mappings, none twice.
std::vector<ExperimentEstimator> EstimatorList(const YamlKeyValue& value);

/// A mapping of scenario options, each set with SetScenarioOption.
void ReadScenarioOptions(const YamlKeyValue& value, Experiment& x);

/// `{parameter: ..., values: [...]}` or a grid `[{...}, {...}]`; refused when a swept parameter
/// is also among x's scenario options (read before).
std::vector<ExperimentSweep> ReadSweep(const YamlKeyValue& value, const Experiment& x);

}  // namespace phdslam::validation
