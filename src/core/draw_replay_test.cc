#include "src/core/draw_replay.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace phdslam {
namespace {

std::string WriteFile(const std::string& name, const std::string& text) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() / name;
  std::ofstream(path) << text;
  return path.string();
}

TEST(DrawReplay, ServesTheRecordedDrawsInOrderWhenTheTagsMatch) {
  const std::string path = WriteFile("draw_replay_ok.csv",
                                     "step,particle,purpose,index,value\n"
                                     "0,0,component,0,0.25\n"
                                     "0,0,pose,0,-1.5\n"
                                     "0,0,pose,1,0.125\n"
                                     "0,0,pose,2,2e-3\n"
                                     "1,1,resample,0,0.75\n");
  DrawReplay replay = DrawReplay::ReadCsv(path);
  EXPECT_EQ(replay.size(), 5u);
  EXPECT_EQ(replay.Next(0, 0, DrawPurpose::kComponent, 0), 0.25);
  EXPECT_EQ(replay.Next(0, 0, DrawPurpose::kPose, 0), -1.5);
  EXPECT_EQ(replay.Next(0, 0, DrawPurpose::kPose, 1), 0.125);
  EXPECT_EQ(replay.Next(0, 0, DrawPurpose::kPose, 2), 2e-3);
  EXPECT_EQ(replay.Next(1, 1, DrawPurpose::kResample, 0), 0.75);
  EXPECT_EQ(replay.consumed(), 5u);
  try {
    (void)replay.Next(2, 0, DrawPurpose::kComponent, 0);
    FAIL() << "a draw past the end must throw";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("end before (step 2, particle 0, component 0)"),
              std::string::npos)
        << e.what();
  }
}

TEST(DrawReplay, RefusesADrawWithAnotherTagNamingBoth) {
  DrawReplay replay({{3, 1, DrawPurpose::kPose, 0, 0.5}}, "recorded");
  try {
    (void)replay.Next(3, 1, DrawPurpose::kResample, 0);
    FAIL() << "a mismatched tag must throw";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("(step 3, particle 1, pose 0)"), std::string::npos) << what;
    EXPECT_NE(what.find("asks for (step 3, particle 1, resample 0)"), std::string::npos) << what;
  }
}

TEST(DrawReplay, NamesTheFileAndLineOfAMalformedRow) {
  const std::string bad_purpose = WriteFile("draw_replay_bad_purpose.csv",
                                            "step,particle,purpose,index,value\n"
                                            "0,0,component,0,0.5\n"
                                            "0,0,gibbs,0,0.5\n");
  EXPECT_THROW(
      {
        try {
          (void)DrawReplay::ReadCsv(bad_purpose);
        } catch (const std::runtime_error& e) {
          EXPECT_NE(std::string(e.what()).find(bad_purpose + ":3: unknown purpose 'gibbs'"),
                    std::string::npos)
              << e.what();
          throw;
        }
      },
      std::runtime_error);
  const std::string bad_number = WriteFile("draw_replay_bad_number.csv",
                                           "step,particle,purpose,index,value\n"
                                           "0,0,component,0,0.5x\n");
  EXPECT_THROW((void)DrawReplay::ReadCsv(bad_number), std::runtime_error);
  const std::string nan_value = WriteFile("draw_replay_nan.csv",
                                          "step,particle,purpose,index,value\n"
                                          "0,0,pose,0,nan\n");
  EXPECT_THROW((void)DrawReplay::ReadCsv(nan_value), std::runtime_error);
  EXPECT_THROW((void)DrawReplay::ReadCsv(WriteFile("draw_replay_no_header.csv", "0,0,pose,0,1\n")),
               std::runtime_error);
  EXPECT_THROW((void)DrawReplay::ReadCsv("/nonexistent/draws.csv"), std::runtime_error);
}

}  // namespace
}  // namespace phdslam
