#include "validation/runner/registry/estimator_parameter_list.h"

#include <gtest/gtest.h>

#include <string>

namespace phdslam::validation {
namespace {

TEST(EstimatorParameterList, EveryRowOfEveryEstimatorHasAMeaningAndADefault) {
  for (const EstimatorEntry& e : EstimatorTable()) {
    for (const EstimatorParameter& p : EstimatorParameters(e)) {
      EXPECT_FALSE(p.meaning.empty()) << e.name << ": " << p.key;
      EXPECT_FALSE(p.accepted.empty()) << e.name << ": " << p.key;
      EXPECT_FALSE(p.default_value.is_null() && p.accepted.find("null") == std::string::npos)
          << e.name << ": " << p.key << " has no default";
    }
  }
}

// An entry whose parameters are not listed (EstimatorEntry::parameters unset) fails here too.
TEST(EstimatorParameterList, EveryResolvedParameterIsARowOfTheTable) {
  for (const EstimatorEntry& e : EstimatorTable()) {
    EstimatorRequest request;
    request.name = e.name;
    const nlohmann::json resolved = e.resolved_parameters(request);
    for (const auto& [key, value] : resolved.items()) {
      if (key == "particles") continue;  // --particles, a row of most tables
      bool found = false;
      for (const params::FieldDescription& row : e.parameters) found = found || row.key == key;
      EXPECT_TRUE(found) << e.name << ": resolved parameter " << key << " is not listed";
    }
  }
}

TEST(EstimatorParameterList, Phd3ShowsMaxHypothesesWithDefaultAndBounds) {
  const std::string text = FormatEstimatorParameters(FindEstimator("phd3"), "  ");
  EXPECT_NE(text.find("  max_hypotheses = 50 (an integer >= 0): most Murty"), std::string::npos)
      << text;
  EXPECT_NE(text.find("  ess_threshold_kind = \"relative\" (one of \"relative\", \"absolute\")"),
            std::string::npos)
      << text;
}

TEST(EstimatorParameterList, AnEstimatorWithoutParametersSaysSo) {
  EXPECT_EQ(FormatEstimatorParameters(FindEstimator("odometry"), "    "), "    (no parameters)\n");
}

TEST(EstimatorParameterList, AnUnknownNameListsTheKnownOnes) {
  try {
    (void)FindEstimator("phd4");
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("unknown estimator 'phd4' (known: odometry, "),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace phdslam::validation
