#include "datasets/data_dir.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "datasets/test_temp_dir.h"

namespace phdslam::datasets {
namespace {

/// Sets PHDSLAM_DATA for the lifetime of the object and restores the previous value.
class ScopedDataEnv {
 public:
  explicit ScopedDataEnv(const std::optional<std::string>& value) {
    if (const char* old = std::getenv(kDataDirEnvVar)) old_ = old;
    if (value) {
      ::setenv(kDataDirEnvVar, value->c_str(), 1);
    } else {
      ::unsetenv(kDataDirEnvVar);
    }
  }
  ~ScopedDataEnv() {
    if (old_) {
      ::setenv(kDataDirEnvVar, old_->c_str(), 1);
    } else {
      ::unsetenv(kDataDirEnvVar);
    }
  }
  ScopedDataEnv(const ScopedDataEnv&) = delete;
  ScopedDataEnv& operator=(const ScopedDataEnv&) = delete;

 private:
  std::optional<std::string> old_;
};

std::string ErrorOf(const std::optional<std::string>& flag) {
  try {
    (void)ResolveDataDir(flag);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(ResolveDataDir, FlagWinsOverEnvironment) {
  const auto dir = testing::FreshTestDir();
  const auto other = dir / "other";
  std::filesystem::create_directories(other);
  const ScopedDataEnv env(other.string());
  EXPECT_EQ(ResolveDataDir(dir.string()), dir);
}

TEST(ResolveDataDir, EnvironmentWhenNoFlag) {
  const auto dir = testing::FreshTestDir();
  const ScopedDataEnv env(dir.string());
  EXPECT_EQ(ResolveDataDir(std::nullopt), dir);
}

TEST(ResolveDataDir, MissingFlagFolderNamesFolderAndOption) {
  const auto missing = testing::FreshTestDir() / "no-such-folder";
  const std::string message = ErrorOf(missing.string());
  EXPECT_NE(message.find(missing.string()), std::string::npos) << message;
  EXPECT_NE(message.find("--data-dir"), std::string::npos) << message;
  EXPECT_NE(message.find("does not exist"), std::string::npos) << message;
}

TEST(ResolveDataDir, MissingEnvironmentFolderNamesVariable) {
  const auto missing = testing::FreshTestDir() / "no-such-folder";
  const ScopedDataEnv env(missing.string());
  const std::string message = ErrorOf(std::nullopt);
  EXPECT_NE(message.find(missing.string()), std::string::npos) << message;
  EXPECT_NE(message.find("PHDSLAM_DATA"), std::string::npos) << message;
}

TEST(ResolveDataDir, FileIsNotAFolder) {
  const auto file = testing::FreshTestDir() / "plain-file";
  std::ofstream(file) << "x";
  const std::string message = ErrorOf(file.string());
  EXPECT_NE(message.find("is not a directory"), std::string::npos) << message;
}

TEST(ResolveDataDir, CompiledDefaultWhenNothingElse) {
  const ScopedDataEnv env(std::nullopt);
  // The compiled default is ../shared/datasets next to the repository: it either resolves to a
  // folder holding the data sets or the error names the compiled default.
  try {
    const auto dir = ResolveDataDir(std::nullopt);
    EXPECT_TRUE(std::filesystem::is_directory(dir / "phdslam3-synthetic")) << dir;
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("PHDSLAM_DEFAULT_DATA_DIR"), std::string::npos)
        << e.what();
  }
}

TEST(ResolveDataDir, EmptyEnvironmentValueCountsAsUnset) {
  const auto outcome = [] {
    try {
      return "ok: " + ResolveDataDir(std::nullopt).string();
    } catch (const std::runtime_error& e) {
      return std::string("error: ") + e.what();
    }
  };
  std::string unset;
  {
    const ScopedDataEnv env(std::nullopt);
    unset = outcome();
  }
  const ScopedDataEnv env{std::string()};
  EXPECT_EQ(outcome(), unset);
}

TEST(ResolveDataDir, MissingFolderSaysHowToGetTheDataSets) {
  const std::string message = ErrorOf((testing::FreshTestDir() / "absent").string());
  EXPECT_NE(message.find("phdslam data fetch"), std::string::npos) << message;
}

const std::vector<std::filesystem::path> kSyntheticFiles = {
    std::filesystem::path("phdslam3-synthetic") / "Environment_SLAM.mat"};

TEST(ResolveDataDirFor, TheRepositoryCarriesTheSyntheticScenario) {
  EXPECT_TRUE(std::filesystem::is_regular_file(BundledDataDir() / kSyntheticFiles[0]))
      << BundledDataDir();
}

TEST(ResolveDataDirFor, DataFolderWhenItHoldsTheFiles) {
  const auto dir = testing::FreshTestDir();
  std::filesystem::create_directories(dir / "phdslam3-synthetic");
  std::ofstream(dir / kSyntheticFiles[0]) << "x";
  EXPECT_EQ(ResolveDataDirFor(dir.string(), kSyntheticFiles), dir);
  const ScopedDataEnv env(dir.string());
  EXPECT_EQ(ResolveDataDirFor(std::nullopt, kSyntheticFiles), dir);
}

TEST(ResolveDataDirFor, RepositoryCopyWhenTheDataFolderLacksThemOrIsAbsent) {
  const auto dir = testing::FreshTestDir();
  EXPECT_EQ(ResolveDataDirFor(dir.string(), kSyntheticFiles), BundledDataDir());
  const ScopedDataEnv env((dir / "absent").string());
  EXPECT_EQ(ResolveDataDirFor(std::nullopt, kSyntheticFiles), BundledDataDir());
}

TEST(ResolveDataDirFor, NeitherFolderNamesTheFileAndBothFolders) {
  const auto dir = testing::FreshTestDir();
  try {
    (void)ResolveDataDirFor(dir.string(), {"victoria-park/measurements.dat"});
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("victoria-park/measurements.dat"), std::string::npos) << message;
    EXPECT_NE(message.find(dir.string()), std::string::npos) << message;
    EXPECT_NE(message.find(BundledDataDir().string()), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace phdslam::datasets
