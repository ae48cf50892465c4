// libFuzzer target: the scenario-option path. The first byte picks a simulated scenario
// (generated, scphd-sim, glmb-sim); every further line `key=value` (the value JSON when it
// parses, else a string) goes through the scenario's option table as `--scenario-set` would,
// then the options' Validate(), then the scenario is built with a step cap. Every stage must
// accept its input or throw std::invalid_argument; nothing may crash, hang or run out of memory.
// As on the command line and in experiment files, text that is not UTF-8 is refused first
// (RequireUtf8): the tables' messages quote values as JSON, which holds UTF-8 only.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <string_view>

#include "datasets/glmb_simulation.h"
#include "datasets/scenario_generator.h"
#include "datasets/scphd_simulation.h"
#include "validation/runner/io/utf8_text.h"
#include "validation/runner/registry/scenario_option_tables.h"

namespace {

// Steps and landmarks of a fuzzed scenario are capped so that one input runs in milliseconds;
// the options' own caps (datasets/simulation_limits.h) are checked before the cap applies.
constexpr int kStepCap = 20;
constexpr int kLandmarkCap = 300;

template <class Options>
bool ApplyLines(const phdslam::params::ParameterTable<Options>& table, std::string_view text,
                Options& options) {
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view line = text.substr(start, end - start);
    start = end + 1;
    const std::size_t eq = line.find('=');
    if (eq == std::string_view::npos) continue;
    const std::string key(line.substr(0, eq));
    const std::string value_text(line.substr(eq + 1));
    nlohmann::json value = nlohmann::json::parse(value_text, nullptr, false);
    if (value.is_discarded()) value = value_text;
    try {
      table.Apply(nlohmann::json::object({{key, value}}), options);
    } catch (const std::invalid_argument&) {
      return false;
    }
  }
  return true;
}

template <class Options, class Make>
void Exercise(const phdslam::params::ParameterTable<Options>& table, std::string_view text,
              Make make) {
  Options options;
  if (!ApplyLines(table, text, options)) return;
  try {
    options.Validate();
    options.steps = std::min(options.steps, kStepCap);
    options.landmarks = std::min(options.landmarks, kLandmarkCap);
    (void)make(options);
  } catch (const std::invalid_argument&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  namespace d = phdslam::datasets;
  namespace v = phdslam::validation;
  const std::string_view text(reinterpret_cast<const char*>(data) + 1, size - 1);
  try {
    v::RequireUtf8(text, "--scenario-set");
  } catch (const std::invalid_argument&) {
    return 0;
  }
  switch (data[0] % 3) {
    case 0:
      Exercise(v::GeneratedOptionsTable(), text,
               [](const d::GeneratorOptions& o) { return d::GenerateScenario(o, 1); });
      break;
    case 1:
      Exercise(v::ScPhdSimOptionsTable(), text,
               [](const d::ScPhdSimOptions& o) { return d::MakeScPhdSimScenario(o, 1); });
      break;
    default:
      Exercise(v::GlmbSimOptionsTable(), text,
               [](const d::GlmbSimOptions& o) { return d::MakeGlmbSimScenario(o, 1); });
      break;
  }
  return 0;
}
