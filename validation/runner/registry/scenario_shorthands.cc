#include "validation/runner/registry/scenario_shorthands.h"

namespace phdslam::validation {

const std::vector<ScenarioShorthand>& ScenarioShorthands() {
  static const std::vector<ScenarioShorthand> table = {
      {"pd", "the detection probability", &ScenarioOptions::detection_probability},
      {"clutter_rate", "the clutter rate", &ScenarioOptions::clutter_rate},
  };
  return table;
}

const ScenarioShorthand* FindScenarioShorthand(const std::string& key) {
  for (const ScenarioShorthand& s : ScenarioShorthands()) {
    if (s.key == key) return &s;
  }
  return nullptr;
}

std::map<std::string, std::vector<std::string>> DefaultShorthandRows() {
  return {{"pd", {"detection_probability"}}, {"clutter_rate", {"clutter_rate"}}};
}

std::vector<std::string> ShorthandRows(const ScenarioEntry& entry, const std::string& key) {
  const auto it = entry.shorthand_rows.find(key);
  return it == entry.shorthand_rows.end() ? std::vector<std::string>{} : it->second;
}

nlohmann::json ShorthandSettings(const std::map<std::string, std::vector<std::string>>& rows,
                                 const ScenarioOptions& options) {
  nlohmann::json settings = nlohmann::json::object();
  for (const ScenarioShorthand& s : ScenarioShorthands()) {
    const std::optional<double>& value = options.*s.value;
    const auto it = rows.find(s.key);
    if (!value || it == rows.end()) continue;
    for (const std::string& row : it->second) settings[row] = *value;
  }
  return settings;
}

}  // namespace phdslam::validation
