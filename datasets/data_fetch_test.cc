#include "datasets/data_fetch.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "datasets/data_catalog.h"
#include "datasets/data_check.h"
#include "datasets/external_program.h"
#include "datasets/test_data_sets.h"
#include "datasets/test_temp_dir.h"

namespace phdslam::datasets {
namespace {

namespace fs = std::filesystem;

// Every file under `dir`, relative, sorted.
std::vector<std::string> FilesUnder(const fs::path& dir) {
  std::vector<std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (e.is_regular_file()) files.push_back(fs::relative(e.path(), dir).generic_string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::vector<std::string> CataloguePaths(const std::string& name) {
  std::vector<std::string> paths;
  for (const DataFile& f : FindDataSet(name).files) paths.push_back(f.path);
  std::sort(paths.begin(), paths.end());
  return paths;
}

// A mirror of data set `name` (a data folder's layout) with one byte of `changed` flipped.
fs::path MirrorWithOneChangedByte(const fs::path& from, const std::string& name,
                                  const std::string& changed, const fs::path& mirror) {
  for (const DataFile& file : FindDataSet(name).files) {
    fs::create_directories((mirror / file.path).parent_path());
    fs::copy_file(from / file.path, mirror / file.path);
  }
  std::fstream f(mirror / changed, std::ios::in | std::ios::out | std::ios::binary);
  f.seekp(10);
  f.put('#');
  return mirror;
}

TEST(DataFetch, FromALocalFolderInstallsEveryFileVerifiedThenLeavesThem) {
  const testing::DataSetLookup found = testing::FindDataSetFiles("victoria-park");
  PHDSLAM_SKIP_WITHOUT_DATA_SET(found);
  const fs::path data = testing::FreshTestDir() / "data";  // created by the fetch
  std::ostringstream log;
  FetchReport r = FetchDataSet(FindDataSet("victoria-park"), data, found.dir->string(), log);
  EXPECT_EQ(r.installed, 6u);
  EXPECT_EQ(r.already_verified, 0u);
  EXPECT_EQ(FilesUnder(data), CataloguePaths("victoria-park"));  // no temporary file left
  EXPECT_EQ(CheckDataSet(data, FindDataSet("victoria-park")).State(), "present");
  r = FetchDataSet(FindDataSet("victoria-park"), data, "file://" + found.dir->string(), log);
  EXPECT_EQ(r.installed, 0u);
  EXPECT_EQ(r.already_verified, 6u);
}

TEST(DataFetch, FromAFileAddressAndAMismatchIsRefusedNamingTheFile) {
  const testing::DataSetLookup found = testing::FindDataSetFiles("victoria-park");
  PHDSLAM_SKIP_WITHOUT_DATA_SET(found);
  const fs::path root = testing::FreshTestDir();
  const fs::path mirror = MirrorWithOneChangedByte(
      *found.dir, "victoria-park", "victoria-park/measurements.dat", root / "mirror");
  const fs::path data = root / "data";
  std::ostringstream log;
  try {
    (void)FetchDataSet(FindDataSet("victoria-park"), data, "file://" + mirror.string(), log);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("victoria-park/measurements.dat"), std::string::npos) << message;
    EXPECT_NE(message.find("does not match"), std::string::npos) << message;
    EXPECT_EQ(message.find("inputs.dat"), std::string::npos) << message;
  }
  // The other five are in place and verified; the changed one is nowhere, not even half-written.
  std::vector<std::string> expected = CataloguePaths("victoria-park");
  std::erase(expected, "victoria-park/measurements.dat");
  EXPECT_EQ(FilesUnder(data), expected);
}

TEST(DataFetch, ACorruptFileInPlaceIsReplacedOnlyByAVerifiedOne) {
  const testing::DataSetLookup found = testing::FindDataSetFiles("victoria-park");
  PHDSLAM_SKIP_WITHOUT_DATA_SET(found);
  const fs::path root = testing::FreshTestDir();
  const fs::path data = root / "data";
  fs::create_directories(data / "victoria-park");
  std::ofstream(data / "victoria-park" / "gps.dat") << "damaged";
  const fs::path bad = MirrorWithOneChangedByte(*found.dir, "victoria-park",
                                                "victoria-park/gps.dat", root / "mirror");
  std::ostringstream log;
  EXPECT_THROW((void)FetchDataSet(FindDataSet("victoria-park"), data, bad.string(), log),
               std::runtime_error);
  EXPECT_EQ(
      VerifyDataFile(data / "victoria-park" / "gps.dat", FindDataSet("victoria-park").files[3])
          .detail.find("size 7 bytes"),
      0u);
  const FetchReport r = FetchDataSet(FindDataSet("victoria-park"), data, found.dir->string(), log);
  EXPECT_EQ(r.installed, 1u);
  EXPECT_EQ(CheckDataSet(data, FindDataSet("victoria-park")).State(), "present");
}

TEST(DataFetch, TheArchiveRouteExtractsAndVerifiesEachFile) {
  const testing::DataSetLookup found = testing::FindDataSetFiles("mrclam");
  PHDSLAM_SKIP_WITHOUT_DATA_SET(found);
  const auto python = FindProgram("python3");
  ASSERT_TRUE(python.has_value()) << "python3 makes the test's archive";
  const fs::path root = testing::FreshTestDir();
  const fs::path archive = root / "MRCLAM_Dataset6.zip";
  ASSERT_EQ(RunProgram(*python, {"-m", "zipfile", "-c", archive.string(),
                                 (*found.dir / "utias-mrclam" / "MRCLAM_Dataset6").string()}),
            0);
  DataSetEntry entry = FindDataSet("mrclam");
  entry.archive_url = "file://" + archive.string();
  std::ostringstream log;
  const FetchReport r = FetchDataSet(entry, root / "data", "", log);
  EXPECT_EQ(r.installed, 17u) << log.str();
  EXPECT_EQ(FilesUnder(root / "data"), CataloguePaths("mrclam"));  // the archive is gone too
}

TEST(DataFetch, AnAddressWithoutCurlOrWgetSaysSo) {
  const fs::path empty = testing::FreshTestDir();
  const std::string old_path = std::getenv("PATH") != nullptr ? std::getenv("PATH") : "";
  ::setenv("PATH", empty.c_str(), 1);
  std::ostringstream log;
  std::string message;
  try {
    (void)FetchDataSet(FindDataSet("synthetic"), empty / "data", "https://example.invalid/d", log);
  } catch (const std::runtime_error& e) {
    message = e.what();
  }
  ::setenv("PATH", old_path.c_str(), 1);
  EXPECT_NE(message.find("neither curl nor wget"), std::string::npos) << message;
  EXPECT_NE(message.find("phdslam3-synthetic/Environment_SLAM.mat"), std::string::npos) << message;
  EXPECT_NE(message.find("by hand"), std::string::npos) << message;
  EXPECT_FALSE(fs::exists(empty / "data" / "phdslam3-synthetic" / "Environment_SLAM.mat"));
}

}  // namespace
}  // namespace phdslam::datasets
