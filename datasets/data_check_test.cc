#include "datasets/data_check.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "datasets/data_catalog.h"
#include "datasets/data_dir.h"
#include "datasets/test_data_sets.h"
#include "datasets/test_temp_dir.h"

namespace phdslam::datasets {
namespace {

namespace fs = std::filesystem;

// Copies the files of data set `name` from `from` to `to`.
void CopyDataSet(const std::string& name, const fs::path& from, const fs::path& to) {
  for (const DataFile& file : FindDataSet(name).files) {
    fs::create_directories((to / file.path).parent_path());
    fs::copy_file(from / file.path, to / file.path);
  }
}

void FlipOneByte(const fs::path& path, std::streamoff at) {
  std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
  f.seekg(at);
  const char c = static_cast<char>(f.get());
  f.seekp(at);
  f.put(static_cast<char>(c ^ 0x01));
}

TEST(DataCatalog, NamesTheThreeDataSetsAndRefusesOthers) {
  ASSERT_EQ(DataSetCatalog().size(), 3u);
  EXPECT_EQ(DataSetCatalog()[0].name, "synthetic");
  EXPECT_EQ(DataSetCatalog()[1].name, "victoria-park");
  EXPECT_EQ(DataSetCatalog()[2].name, "mrclam");
  EXPECT_EQ(FindDataSet("mrclam").files.size(), 17u);
  EXPECT_EQ(FindDataSet("victoria-park").files.size(), 6u);
  try {
    (void)FindDataSet("kitti");
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("victoria-park"), std::string::npos) << e.what();
  }
}

TEST(DataCheck, TheRepositoryCopyOfTheSyntheticScenarioIsVerified) {
  const DataSetCheck check = CheckDataSet(testing::FreshTestDir(), FindDataSet("synthetic"));
  EXPECT_TRUE(check.from_repository);
  EXPECT_EQ(check.dir, BundledDataDir());
  EXPECT_EQ(check.State(), "present");
  ASSERT_EQ(check.files.size(), 1u);
  EXPECT_EQ(check.files[0].state, FileState::kVerified);
}

TEST(DataCheck, AnEmptyFolderMissesTheRealDataSets) {
  const fs::path dir = testing::FreshTestDir();
  for (const std::string name : {"victoria-park", "mrclam"}) {
    const DataSetCheck check = CheckDataSet(dir, FindDataSet(name));
    EXPECT_EQ(check.State(), "missing") << name;
    EXPECT_FALSE(check.from_repository);
    for (const FileCheck& f : check.files) EXPECT_EQ(f.state, FileState::kMissing) << f.path;
  }
}

// The checksums kept in the repository against the real files of the data folder.
TEST(DataCheck, EveryRealFileIsVerified) {
  for (const std::string name : {"victoria-park", "mrclam"}) {
    const testing::DataSetLookup found = testing::FindDataSetFiles(name);
    PHDSLAM_SKIP_WITHOUT_DATA_SET(found);
    const DataSetCheck check = CheckDataSet(*found.dir, FindDataSet(name));
    EXPECT_EQ(check.State(), "present") << name;
    for (const FileCheck& f : check.files) {
      EXPECT_EQ(f.state, FileState::kVerified) << f.path << ": " << f.detail;
    }
  }
}

TEST(DataCheck, OneChangedByteMakesThatFileCorruptAndNoOther) {
  const testing::DataSetLookup found = testing::FindDataSetFiles("victoria-park");
  PHDSLAM_SKIP_WITHOUT_DATA_SET(found);
  const fs::path dir = testing::FreshTestDir();
  CopyDataSet("victoria-park", *found.dir, dir);
  FlipOneByte(dir / "victoria-park" / "inputs.dat", 1000);
  const DataSetCheck check = CheckDataSet(dir, FindDataSet("victoria-park"));
  EXPECT_EQ(check.State(), "corrupt");
  for (const FileCheck& f : check.files) {
    const bool changed = f.path.filename() == "inputs.dat";
    EXPECT_EQ(f.state, changed ? FileState::kCorrupt : FileState::kVerified) << f.path;
    if (changed) {
      EXPECT_NE(f.detail.find("SHA-256"), std::string::npos) << f.detail;
    }
  }
}

TEST(DataCheck, ACutFileIsCorruptBySize) {
  const fs::path dir = testing::FreshTestDir();
  const DataFile& expected = FindDataSet("synthetic").files[0];
  fs::create_directories((dir / expected.path).parent_path());
  std::ofstream(dir / expected.path) << "MATLAB";
  const DataSetCheck check = CheckDataSet(dir, FindDataSet("synthetic"));
  EXPECT_FALSE(check.from_repository);  // the data folder's copy is the one read, and checked
  EXPECT_EQ(check.State(), "corrupt");
  EXPECT_NE(check.files[0].detail.find("size 6 bytes, expected 214403"), std::string::npos)
      << check.files[0].detail;
}

}  // namespace
}  // namespace phdslam::datasets
