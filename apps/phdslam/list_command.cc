#include "apps/phdslam/list_command.h"

#include <algorithm>
#include <iostream>

#include "validation/runner/registry/estimator_parameter_list.h"
#include "validation/runner/registry/estimator_registry.h"
#include "validation/runner/registry/scenario_registry.h"

namespace phdslam::apps {
namespace {

namespace v = phdslam::validation;

std::size_t NameWidth() {
  std::size_t width = 0;
  for (const auto& s : v::ScenarioTable()) width = std::max(width, s.name.size());
  for (const auto& e : v::EstimatorTable()) width = std::max(width, e.name.size());
  return width;
}

void PrintNamed(const std::string& name, const std::string& description, std::size_t width) {
  std::cout << "  " << name << std::string(width + 2 - name.size(), ' ') << description << "\n";
}

void PrintEstimator(const v::EstimatorEntry& e, std::size_t width) {
  PrintNamed(e.name, e.description + (e.batch ? " [batch]" : ""), width);
  std::cout << v::FormatEstimatorParameters(e, std::string(width + 6, ' '));
}

void PrintScenarios(std::size_t width) {
  std::cout << "scenarios:\n";
  for (const auto& s : v::ScenarioTable()) {
    PrintNamed(s.name, s.description, width);
    for (const v::ScenarioOptionHelp& o : s.option_keys) {
      std::cout << "  " << std::string(width + 2, ' ') << "  " << o.key << ": " << o.help << "\n";
    }
  }
}

}  // namespace

void AddListCommand(CLI::App& app, ListArguments& a) {
  CLI::App* list = app.add_subcommand(
      "list",
      "List the known scenarios (with their options) and estimators (with their parameters: "
      "key = default (accepted values): meaning; `--set key=value` changes one)");
  list->add_option("--estimator", a.estimator,
                   "Show only this estimator and its parameters (see `phdslam list`)");
}

int List(const ListArguments& a) {
  const std::size_t width = NameWidth();
  if (!a.estimator.empty()) {
    PrintEstimator(v::FindEstimator(a.estimator), width);
    return 0;
  }
  PrintScenarios(width);
  std::cout << "estimators:\n";
  for (const auto& e : v::EstimatorTable()) PrintEstimator(e, width);
  return 0;
}

}  // namespace phdslam::apps
