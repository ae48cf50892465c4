// The keys of an Experiment, one row each: its name in experiment files, its command-line
// option with the --help text, its key in export.json's `request`, and how each of them is read
// (and the manifest's written). The experiment-file reader (experiment_file.cc), the option
// precedence of `phdslam run` (option_precedence.cc), the options of `run`, `export` and
// `ingest` (apps/phdslam/experiment_options.cc) and the export manifest (scenario_export.cc) all
// follow this one table, so a new key of Experiment is one row in experiment_keys.cc.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "validation/runner/experiment/experiment.h"

namespace phdslam::validation {

struct YamlKeyValue;

/// How a key's option takes its value on the command line; the value reaches
/// ExperimentKey::apply_option as JSON of the kind's type.
enum class OptionKind {
  kText,            ///< a string
  kCount,           ///< an integer >= 0
  kNumber,          ///< a number
  kPositiveNumber,  ///< a number > 0
  kFlag,            ///< no value: true when given
  kRepeated,        ///< a string, repeatable: an array of strings
};

/// One key of Experiment.
struct ExperimentKey {
  std::string file_key{};      ///< key in experiment files; empty: not read from files
  std::string option{};        ///< command-line option ("--steps"); empty: none
  std::string manifest_key{};  ///< key in export.json's `request`; empty: not recorded there
  OptionKind kind = OptionKind::kText;
  std::string help{};          ///< the option's --help text
  std::string default_text{};  ///< the default --help shows; empty: none shown
  bool required = false;       ///< required in a file, and on the command line without a file
  /// The scenario, its options and seeds: also an option of `export` and `ingest`.
  bool export_option = false;
  /// A setting of the machine (a folder): never read from files, nor recorded in config.json as
  /// overriding a file.
  bool machine_setting = false;
  std::function<void(const YamlKeyValue&, Experiment&)> read_file{};  ///< throws naming file:line
  std::function<void(const nlohmann::json&, Experiment&)> apply_option{};  ///< invalid_argument
  std::function<nlohmann::json(const Experiment&)> write_manifest{};
  std::function<void(const nlohmann::json&, Experiment&)> read_manifest{};  ///< json exceptions
};

/// Every key, in the order options are applied (and files read): a key whose check depends on
/// another (--pd on --scenario, --set on --estimator) comes after it.
const std::vector<ExperimentKey>& ExperimentKeys();

/// The row of command-line option `option`; nullptr when no key has it.
const ExperimentKey* FindExperimentOption(const std::string& option);

}  // namespace phdslam::validation
