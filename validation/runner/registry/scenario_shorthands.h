// The scenario options with a key and a command-line option of their own: `pd` (--pd) and
// `clutter_rate` (--clutter-rate). This one table says where ScenarioOptions holds each, and
// every scenario names the rows of its option table each one sets (ScenarioEntry::shorthand_rows:
// Victoria Park's pd sets both of its pD rows), so that making, resolving and checking a scenario,
// and the experiment's checks, treat both alike.
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "validation/runner/registry/scenario_entry.h"

namespace phdslam::validation {

struct ScenarioShorthand {
  std::string key;   ///< the scenario option, sweep parameter and export.json `request` key
  std::string what;  ///< what it sets, for messages ("the detection probability")
  std::optional<double> ScenarioOptions::*value;  ///< where a scenario request holds it
};

/// `pd` and `clutter_rate`, in that order.
const std::vector<ScenarioShorthand>& ScenarioShorthands();

/// The row of `key`; nullptr when `key` is no shorthand.
const ScenarioShorthand* FindScenarioShorthand(const std::string& key);

/// The rows most scenarios' shorthands set: pd the row `detection_probability`, clutter_rate the
/// row `clutter_rate`.
std::map<std::string, std::vector<std::string>> DefaultShorthandRows();

/// The rows of `entry`'s option table that shorthand `key` sets (empty: none).
std::vector<std::string> ShorthandRows(const ScenarioEntry& entry, const std::string& key);

/// {row: value} for each row that a shorthand `options` sets writes to (ScenarioOptions::settings
/// are applied after these).
nlohmann::json ShorthandSettings(const std::map<std::string, std::vector<std::string>>& rows,
                                 const ScenarioOptions& options);

}  // namespace phdslam::validation
