#include "validation/runner/registry/parameter_overrides.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace phdslam::validation {
namespace {

using nlohmann::json;

const json kDefaults = {{"hypotheses", 50},
                        {"ess_threshold", 0.2},
                        {"resample", true},
                        {"variant", "3.0"},
                        {"ipl", {{"iterations", 5}, {"tolerance", 1e-3}}}};

TEST(ApplyOverrides, ReplacesKnownKeysAndKeepsTheRest) {
  const json r = ApplyOverrides(
      kDefaults, {{"hypotheses", 10}, {"ipl", {{"tolerance", 1e-4}}}, {"resample", false}}, "t");
  EXPECT_EQ(r["hypotheses"], 10);
  EXPECT_EQ(r["ess_threshold"], 0.2);
  EXPECT_EQ(r["resample"], false);
  EXPECT_EQ(r["variant"], "3.0");
  EXPECT_EQ(r["ipl"]["iterations"], 5);
  EXPECT_EQ(r["ipl"]["tolerance"], 1e-4);
}

TEST(ApplyOverrides, NumbersConvertToTheDefaultsKind) {
  const json r = ApplyOverrides(kDefaults, {{"hypotheses", 7.0}, {"ess_threshold", 1}}, "t");
  EXPECT_TRUE(r["hypotheses"].is_number_integer());
  EXPECT_EQ(r["hypotheses"], 7);
  EXPECT_TRUE(r["ess_threshold"].is_number_float());
  EXPECT_EQ(r["ess_threshold"].get<double>(), 1.0);
}

TEST(ApplyOverrides, RejectsUnknownKeysAndWrongTypes) {
  EXPECT_THROW(ApplyOverrides(kDefaults, {{"hypothesis", 3}}, "t"), std::invalid_argument);
  EXPECT_THROW(ApplyOverrides(kDefaults, {{"ipl", {{"iters", 3}}}}, "t"), std::invalid_argument);
  EXPECT_THROW(ApplyOverrides(kDefaults, {{"hypotheses", 2.5}}, "t"), std::invalid_argument);
  EXPECT_THROW(ApplyOverrides(kDefaults, {{"resample", 1}}, "t"), std::invalid_argument);
  EXPECT_THROW(ApplyOverrides(kDefaults, {{"variant", 3}}, "t"), std::invalid_argument);
  EXPECT_THROW(ApplyOverrides(kDefaults, {{"ipl", 3}}, "t"), std::invalid_argument);
  EXPECT_THROW(ApplyOverrides(kDefaults, json::array(), "t"), std::invalid_argument);
  EXPECT_THROW(ApplyOverrides(json::object(), {{"x", 1}}, "t"), std::invalid_argument);
  try {
    ApplyOverrides(kDefaults, {{"hypothesis", 3}}, "estimator 'phd3'");
    FAIL();
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("estimator 'phd3'"), std::string::npos) << what;
    EXPECT_NE(what.find("'hypothesis'"), std::string::npos) << what;
    EXPECT_NE(what.find("hypotheses"), std::string::npos) << what;  // lists the known keys
  }
}

TEST(ParseParameterAssignment, ValuesAreJsonWhenTheyParse) {
  EXPECT_EQ(ParseParameterAssignment("hypotheses=10").overrides, json({{"hypotheses", 10}}));
  EXPECT_EQ(ParseParameterAssignment("resample=false").overrides, json({{"resample", false}}));
  EXPECT_EQ(ParseParameterAssignment("variant=2.0b").overrides, json({{"variant", "2.0b"}}));
  EXPECT_EQ(ParseParameterAssignment("variant=\"7\"").overrides, json({{"variant", "7"}}));
  EXPECT_EQ(ParseParameterAssignment("name=").overrides, json({{"name", ""}}));
  EXPECT_EQ(ParseParameterAssignment("ipl.tolerance=1e-4").overrides,
            json({{"ipl", {{"tolerance", 1e-4}}}}));
  const ParameterAssignment scoped = ParseParameterAssignment("phd3:hypotheses=5");
  EXPECT_EQ(scoped.estimator, "phd3");
  EXPECT_EQ(scoped.overrides, json({{"hypotheses", 5}}));
  EXPECT_TRUE(ParseParameterAssignment("a=b=c").overrides == json({{"a", "b=c"}}));
}

TEST(ParseParameterAssignment, RejectsMalformedText) {
  for (const char* bad : {"hypotheses", "=3", ".a=1", "a.=1", "a..b=1", ":a=1", "phd3:=1",
                          "variant=\xff", "a\xc0\xaf=1"}) {
    EXPECT_THROW(ParseParameterAssignment(bad), std::invalid_argument) << bad;
  }
}

TEST(MergeJsonObjects, MergesNestedObjects) {
  json a = {{"x", 1}, {"ipl", {{"iterations", 5}}}};
  MergeJsonObjects(a, {{"ipl", {{"tolerance", 1e-3}}}, {"y", 2}});
  EXPECT_EQ(a, json({{"x", 1}, {"y", 2}, {"ipl", {{"iterations", 5}, {"tolerance", 1e-3}}}}));
}

}  // namespace
}  // namespace phdslam::validation
