// Experiment files: one YAML file per Monte Carlo experiment (validation/experiments/*.yaml),
// read into an Experiment. The keys are documented in validation/README.md; every setting not in
// the file keeps the paper's default (the estimator table and the scenario supply them).
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "validation/runner/experiment/experiment.h"

namespace phdslam::validation {

/// Parses an experiment file's text. `source` names the file in error messages and in
/// Experiment::source; `default_name` is the experiment name when the file has no `name`.
/// Throws std::invalid_argument "<source>:<line>: ..." for YAML syntax errors, unknown keys,
/// missing required keys (scenario, estimators, seeds) and values of the wrong kind, and
/// "<source>: line L, column C: not valid UTF-8" for text that is not UTF-8.
Experiment ParseExperimentYaml(std::string_view text, const std::string& source,
                               const std::string& default_name);

/// Reads and parses an experiment file; the default name is the file's stem. Throws
/// std::runtime_error when the file cannot be read.
Experiment ReadExperimentFile(const std::filesystem::path& path);

}  // namespace phdslam::validation
