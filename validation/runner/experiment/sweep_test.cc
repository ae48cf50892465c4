#include "validation/runner/experiment/sweep.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <vector>

#include "datasets/test_temp_dir.h"
#include "validation/runner/io/results_io.h"
#include "validation/runner/io/results_layout.h"

namespace phdslam::validation {
namespace {

namespace fs = std::filesystem;

TEST(ResultsFolders, AResultsFolderIsItsOwn) {
  const fs::path root = datasets::testing::FreshTestDir();
  EXPECT_EQ(ResultsFolders(root), (std::vector<fs::path>{root}));
}

TEST(ResultsFolders, TheSweepPointsThatHoldRunsInPointOrder) {
  const fs::path root = datasets::testing::FreshTestDir();
  const std::vector<ExperimentSweep> sweep = {{"clutter_rate", {5, 10}}, {"pd", {0.3, 0.9}}};
  WriteSweepFiles(root, sweep);
  for (const char* folder : {"sweep-clutter_rate-10-pd-0.9", "sweep-clutter_rate-5-pd-0.3",
                             "sweep-clutter_rate-5-pd-0.9"}) {
    fs::create_directories(root / folder);
    WriteFileAtomically(root / folder / kRunsTableFile, "estimator\n");
  }
  fs::create_directories(root / "sweep-clutter_rate-10-pd-0.3");  // no runs.csv: left out
  EXPECT_EQ(ResultsFolders(root), (std::vector<fs::path>{root / "sweep-clutter_rate-5-pd-0.3",
                                                         root / "sweep-clutter_rate-5-pd-0.9",
                                                         root / "sweep-clutter_rate-10-pd-0.9"}));
}

TEST(ResultsFolders, AMalformedSweepFileIsAnErrorNamingIt) {
  const fs::path root = datasets::testing::FreshTestDir();
  WriteFileAtomically(root / kSweepFile, "{\"parameters\": 3}");
  try {
    ResultsFolders(root);
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find((root / kSweepFile).string()), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace phdslam::validation
