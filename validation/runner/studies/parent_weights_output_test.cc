#include "validation/runner/studies/parent_weights_output.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "datasets/scenario_generator.h"
#include "datasets/test_temp_dir.h"
#include "validation/runner/io/results_io.h"

namespace phdslam::validation {
namespace {

namespace fs = std::filesystem;

datasets::Scenario SmallScenario() {
  datasets::GeneratorOptions o;
  o.steps = 40;
  o.landmarks = 40;
  o.corridor_half_width = 60.0;
  o.initial_pose = Pose(5.0, -3.0, 0.2);
  return datasets::GenerateScenario(o, 5);
}

ParentWeightsStudy SmallStudy(const datasets::Scenario& s) {
  ParentWeightsStudy study;
  study.scenario = "small";
  study.seed = 5;
  study.settings.parents = 6;
  study.settings.spread = 4.0;
  for (std::size_t k = 20; k < s.steps.size(); ++k) {
    if (!s.steps[k].data.measurements.empty()) {
      study.settings.step = k;
      return study;
    }
  }
  ADD_FAILURE() << "no scan with measurements";
  return study;
}

std::size_t Lines(const fs::path& path) {
  const std::string text = ReadTextFile(path);
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

TEST(ParentWeightsOutput, WritesTheComparisonAtOneStepWithItsScenarioAndSeed) {
  const datasets::Scenario s = SmallScenario();
  const fs::path out = datasets::testing::FreshTestDir() / "made-by-the-study";
  const ParentWeightsOutput o = WriteParentWeightsStudy(s, SmallStudy(s), out);
  EXPECT_EQ(o.parents, 6u);
  EXPECT_EQ(Lines(out / kParentWeightsCsvFile), 7u);  // header and one row per parent
  const nlohmann::json j = nlohmann::json::parse(ReadTextFile(out / kParentWeightsJsonFile));
  EXPECT_EQ(j, o.at_step);
  EXPECT_EQ(j.at("scenario"), "small");
  EXPECT_EQ(j.at("seed"), 5);
  EXPECT_EQ(j.at("step"), SmallStudy(s).settings.step);
  EXPECT_FALSE(o.over_steps.has_value());
  EXPECT_FALSE(fs::exists(out / kParentWeightsStepsCsvFile));
  EXPECT_FALSE(fs::exists(out / kParentWeightsStepsJsonFile));
}

TEST(ParentWeightsOutput, TheSameSeedGivesTheSameFilesAndAnotherSeedOthers) {
  const datasets::Scenario s = SmallScenario();
  const fs::path dir = datasets::testing::FreshTestDir();
  ParentWeightsStudy study = SmallStudy(s);
  WriteParentWeightsStudy(s, study, dir / "a");
  WriteParentWeightsStudy(s, study, dir / "b");
  study.seed = 6;
  WriteParentWeightsStudy(s, study, dir / "c");
  EXPECT_EQ(ReadTextFile(dir / "a" / kParentWeightsCsvFile),
            ReadTextFile(dir / "b" / kParentWeightsCsvFile));
  EXPECT_NE(ReadTextFile(dir / "a" / kParentWeightsCsvFile),
            ReadTextFile(dir / "c" / kParentWeightsCsvFile));
  EXPECT_NE(ParentWeightsStreamSeed(5), ParentWeightsStreamSeed(6));
}

TEST(ParentWeightsOutput, EveryNthStepUpToUntilOrTheLastStep) {
  const datasets::Scenario s = SmallScenario();
  const fs::path dir = datasets::testing::FreshTestDir();
  ParentWeightsStudy study = SmallStudy(s);
  study.every = 10;
  study.until = 25;
  const ParentWeightsOutput up_to_25 = WriteParentWeightsStudy(s, study, dir / "until");
  ASSERT_TRUE(up_to_25.over_steps.has_value());
  EXPECT_LE(up_to_25.steps_compared, 2u);  // steps 10 and 20, those with a scan
  EXPECT_GE(up_to_25.steps_compared, 1u);
  EXPECT_EQ(Lines(dir / "until" / kParentWeightsStepsCsvFile), up_to_25.steps_compared + 1);
  const nlohmann::json j =
      nlohmann::json::parse(ReadTextFile(dir / "until" / kParentWeightsStepsJsonFile));
  EXPECT_EQ(j, *up_to_25.over_steps);
  EXPECT_EQ(j.at("every"), 10);
  EXPECT_EQ(j.at("parents"), 6);
  EXPECT_EQ(j.at("spread"), 4.0);
  EXPECT_EQ(j.at("scenario"), "small");

  study.until = 0;  // the scenario's last step, 39: steps 10, 20 and 30
  const ParentWeightsOutput to_the_end = WriteParentWeightsStudy(s, study, dir / "end");
  EXPECT_GT(to_the_end.steps_compared, up_to_25.steps_compared);
  EXPECT_LE(to_the_end.steps_compared, 3u);
  study.until = 1000;  // past the end: the same
  EXPECT_EQ(WriteParentWeightsStudy(s, study, dir / "past").over_steps, to_the_end.over_steps);
}

}  // namespace
}  // namespace phdslam::validation
