// The command-line options of an experiment's keys on a subcommand, one per row of the experiment
// key table (validation/runner/experiment/experiment_keys.h) with an option: `run` takes all of
// them, `export` and `ingest` those that select the scenario.
#pragma once

#include <CLI/CLI.hpp>
#include <deque>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "validation/runner/experiment/experiment_keys.h"

namespace phdslam::apps {

class ExperimentOptionSet {
 public:
  /// kAll: the options of `run`; kExport: those of `export` and `ingest` (the scenario).
  enum class Keys { kAll, kExport };

  /// Adds the options of `keys` to `command`, typed by their OptionKind, with their --help text
  /// (for kAll, the options of `run`, also the experiment-file key, when the key has one).
  void AddTo(CLI::App* command, Keys keys);

  /// The options given on the command line: option -> value (ExperimentOptions::given).
  [[nodiscard]] std::map<std::string, nlohmann::json> Given() const;

 private:
  struct Bound {
    const validation::ExperimentKey* key = nullptr;
    CLI::Option* option = nullptr;
    std::string text;
    int count = 0;
    double number = 0.0;
    bool flag = false;
    std::vector<std::string> texts;
  };
  static CLI::Option* Bind(CLI::App* command, Bound& b, Keys keys);
  static nlohmann::json ValueOf(const Bound& b);

  std::deque<Bound> bound_;  // a deque: CLI11 keeps the addresses of the values
};

}  // namespace phdslam::apps
