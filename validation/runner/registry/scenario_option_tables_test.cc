#include "validation/runner/registry/scenario_option_tables.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "validation/runner/registry/scenario_registry.h"

namespace phdslam::validation {
namespace {

std::string ErrorOf(const nlohmann::json& settings) {
  ScenarioOptions options;
  options.settings = settings;
  try {
    FindScenario("generated").resolved_options(options);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(ScenarioOptionTables, EveryKeyRoundTripsThroughTheTable) {
  datasets::GeneratorOptions o;
  const nlohmann::json written = GeneratedOptionsTable().ToJson(o);
  datasets::GeneratorOptions read;
  read.landmarks = 7;
  read.speed = 3.0;
  GeneratedOptionsTable().Apply(written, read);
  EXPECT_EQ(GeneratedOptionsTable().ToJson(read), written);
  EXPECT_EQ(
      written.at("measurement_noise_cov"),
      nlohmann::json({{o.measurement_noise_cov(0, 0), 0.0}, {0.0, o.measurement_noise_cov(1, 1)}}));
  EXPECT_EQ(written.at("initial_pose"), nlohmann::json({0.0, 0.0, 0.0}));
  for (const char* key : {"landmarks", "speed", "turn_amplitude", "dt", "fov_range"}) {
    EXPECT_NE(GeneratedOptionsTable().Find(key), nullptr) << key;
  }
  EXPECT_NE(VictoriaParkOptionsTable().Find("detection_probability_max"), nullptr);
  EXPECT_EQ(VictoriaParkOptionsTable().Find("landmarks"), nullptr);
  EXPECT_NE(PaperSyntheticOptionsTable().Find("measurement_noise_cov"), nullptr);
}

TEST(ScenarioOptionTables, ResolvedOptionsCarryTheSettings) {
  ScenarioOptions options;
  options.steps = 50;
  options.clutter_rate = 1.0;
  options.settings = {{"landmarks", 33},
                      {"measurement_noise_cov", {0.25, 0.01}},
                      {"initial_pose", {1.0, 2.0, 0.5}}};
  const nlohmann::json resolved = FindScenario("generated").resolved_options(options);
  EXPECT_EQ(resolved.at("landmarks"), 33);
  EXPECT_EQ(resolved.at("steps"), 50);
  EXPECT_EQ(resolved.at("clutter_rate"), 1.0);
  EXPECT_EQ(resolved.at("measurement_noise_cov"), nlohmann::json({{0.25, 0.0}, {0.0, 0.01}}));
  EXPECT_EQ(resolved.at("initial_pose"), nlohmann::json({1.0, 2.0, 0.5}));
  const datasets::Scenario s = MakeScenario("generated", 1, options);
  EXPECT_EQ(s.truth.landmarks.size(), 33u);
  EXPECT_DOUBLE_EQ(s.truth.poses.front()(0), 1.0);
}

TEST(ScenarioOptionTables, BadKeysAndValuesNameTheKey) {
  EXPECT_NE(ErrorOf({{"landmark", 3}}).find("unknown parameter 'landmark' (known: dt,"),
            std::string::npos);
  EXPECT_NE(ErrorOf({{"landmarks", 2.5}}).find("'landmarks': expected an integer, got 2.5"),
            std::string::npos);
  EXPECT_NE(ErrorOf({{"speed", "fast"}}).find("'speed': expected a number"), std::string::npos);
  EXPECT_NE(ErrorOf({{"fov_range", 0}}).find("'fov_range': must be > 0"), std::string::npos);
  EXPECT_NE(ErrorOf({{"measurement_noise_cov", {1, 2, 3}}}).find("'measurement_noise_cov'"),
            std::string::npos);
  EXPECT_NE(ErrorOf({{"initial_pose", {1, 2}}}).find("'initial_pose'"), std::string::npos);
  // Not symmetric: found by the options' own checks.
  EXPECT_FALSE(ErrorOf({{"control_noise_cov", {{1.0, 0.5}, {0.0, 1.0}}}}).empty());
  EXPECT_EQ(ErrorOf({{"landmarks", 0}, {"clutter_rate", 0}}), "");
}

TEST(ScenarioOptionTables, ValuesBeyondTheirPhysicalRangeAreRefusedCompactly) {
  EXPECT_NE(ErrorOf({{"speed", 1e20}}).find("'speed': must be >= 0 and <= 100, got 1e+20"),
            std::string::npos)
      << ErrorOf({{"speed", 1e20}});
  // The map metrics match every true landmark against the estimate: 10^4 at most.
  EXPECT_NE(ErrorOf({{"landmarks", 1e9}}).find("'landmarks': must be >= 0 and <= 10000"),
            std::string::npos);
  EXPECT_NE(ErrorOf({{"landmarks", 10001}}).find("'landmarks'"), std::string::npos);
  EXPECT_EQ(ErrorOf({{"landmarks", 10000}}), "");
  // A corridor far narrower than any vehicle overflowed the generator's raster (SIGSEGV).
  for (const double width : {5e-324, 1e-300, 0.0999}) {
    EXPECT_NE(ErrorOf({{"corridor_half_width", width}})
                  .find("'corridor_half_width': must be >= 0.1 and <= 100000"),
              std::string::npos)
        << width;
  }
  EXPECT_EQ(ErrorOf({{"corridor_half_width", 0.1}}), "");
  EXPECT_EQ(ErrorOf({{"corridor_half_width", 1e5}}), "");
  EXPECT_NE(ErrorOf({{"dt", 1e300}}).find("got 1e+300"), std::string::npos);
  EXPECT_NE(ErrorOf({{"initial_pose", {1e300, 0, 0}}}).find("'initial_pose'"), std::string::npos);
  EXPECT_NE(ErrorOf({{"measurement_noise_cov", {1e300, 1}}}).find("'measurement_noise_cov'"),
            std::string::npos);
  // The caps on what a scenario allocates, beyond the single options' ranges.
  ScenarioOptions options;
  options.steps = 1'000'000;
  options.settings = {{"clutter_rate", 1000}};
  try {
    FindScenario("generated").resolved_options(options);
    FAIL() << "10^9 expected clutter points were accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("steps x clutter_rate = 1000000000 expected clutter "
                                         "points exceeds the cap of 50000000"),
              std::string::npos)
        << e.what();
  }
  options.steps = 2'000'000;
  options.settings = nlohmann::json::object();
  EXPECT_THROW(FindScenario("generated").resolved_options(options), std::invalid_argument);
}

TEST(ScenarioOptionTables, OneOptionIsCheckedOnItsOwn) {
  EXPECT_NO_THROW(CheckScenarioOption("generated", "speed", 2.0));
  EXPECT_THROW(CheckScenarioOption("generated", "speed", 1e20), std::invalid_argument);
  EXPECT_THROW(CheckScenarioOption("generated", "warp", 1), std::invalid_argument);
  EXPECT_THROW(CheckScenarioOption("generated", "pd", 1.5), std::invalid_argument);
  EXPECT_THROW(CheckScenarioOption("victoria-park", "pd", 0.0), std::invalid_argument);
  EXPECT_THROW(CheckScenarioOption("mrclam", "dataset", 99), std::invalid_argument);
  EXPECT_NO_THROW(CheckScenarioOption("mrclam", "dataset", 6));
}

TEST(ScenarioOptionTables, GlmbSimTakesTheDataProtocolByName) {
  ScenarioOptions options;
  options.steps = 30;
  options.clutter_rate = 5.0;
  options.settings = {{"data_protocol", "single-realisation"}, {"data_seed", 4}};
  const nlohmann::json resolved = FindScenario("glmb-sim").resolved_options(options);
  EXPECT_EQ(resolved.at("data_protocol"), "single-realisation");
  EXPECT_EQ(resolved.at("data_seed"), 4);
  EXPECT_EQ(resolved.at("steps"), 30);
  EXPECT_EQ(FindScenario("glmb-sim").resolved_options(ScenarioOptions{}).at("data_protocol"),
            "per-seed");
  const datasets::Scenario a = MakeScenario("glmb-sim", 1, options);
  const datasets::Scenario b = MakeScenario("glmb-sim", 2, options);
  ASSERT_EQ(a.steps.size(), 30u);
  EXPECT_DOUBLE_EQ(a.sensor.clutter_rate, 5.0);
  for (std::size_t k = 0; k < a.steps.size(); ++k) {
    EXPECT_EQ(a.steps[k].data.measurements, b.steps[k].data.measurements) << "step " << k;
  }
  options.settings = {{"data_protocol", "per-run"}};
  try {
    FindScenario("glmb-sim").resolved_options(options);
    ADD_FAILURE() << "an unknown protocol was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("data_protocol"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace phdslam::validation
