#include "validation/runner/registry/scenario_shorthands.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "validation/runner/registry/scenario_registry.h"

namespace phdslam::validation {
namespace {

bool IsOptionOf(const ScenarioEntry& entry, const std::string& key) {
  return std::any_of(entry.option_keys.begin(), entry.option_keys.end(),
                     [&key](const ScenarioOptionHelp& o) { return o.key == key; });
}

TEST(ScenarioShorthands, EveryScenarioMapsEachShorthandOntoRowsOfItsOptionTable) {
  for (const ScenarioEntry& entry : ScenarioTable()) {
    for (const ScenarioShorthand& s : ScenarioShorthands()) {
      const std::vector<std::string> rows = ShorthandRows(entry, s.key);
      EXPECT_FALSE(rows.empty()) << entry.name << ": " << s.key;
      for (const std::string& row : rows) {
        EXPECT_TRUE(IsOptionOf(entry, row)) << entry.name << ": " << s.key << " -> " << row;
      }
    }
  }
}

TEST(ScenarioShorthands, VictoriaParksPdSetsBothOfItsDetectionProbabilities) {
  ScenarioOptions options;
  options.detection_probability = 0.8;
  options.clutter_rate = 2.0;
  const nlohmann::json settings =
      ShorthandSettings(FindScenario("victoria-park").shorthand_rows, options);
  EXPECT_EQ(settings, nlohmann::json::parse(R"({"detection_probability_max": 0.8,
      "detection_probability_nominal": 0.8, "clutter_rate": 2.0})"));
  EXPECT_EQ(ShorthandSettings(FindScenario("generated").shorthand_rows, ScenarioOptions{}),
            nlohmann::json::object());
}

TEST(ScenarioShorthands, OnlyPdAndClutterRateAreShorthands) {
  EXPECT_NE(FindScenarioShorthand("pd"), nullptr);
  EXPECT_NE(FindScenarioShorthand("clutter_rate"), nullptr);
  EXPECT_EQ(FindScenarioShorthand("detection_probability"), nullptr);
}

}  // namespace
}  // namespace phdslam::validation
