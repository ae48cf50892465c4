#include "datasets/mat_v5_structure.h"

#include <gtest/gtest.h>
#include <matio.h>
#include <zlib.h>

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "datasets/data_dir.h"
#include "datasets/mat_file.h"
#include "datasets/paper_synthetic.h"
#include "datasets/test_data_sets.h"
#include "datasets/test_file_bytes.h"
#include "datasets/test_temp_dir.h"

namespace phdslam::datasets {
namespace {

using testing::ErrorOf;
using testing::ReadBytes;
using testing::WriteBytes;

std::filesystem::path SyntheticMat(const std::filesystem::path& data_dir) {
  return data_dir / "phdslam3-synthetic" / "Environment_SLAM.mat";
}

TEST(MatV5Structure, TheSyntheticFilePasses) {
  const std::filesystem::path path = SyntheticMat(testing::SyntheticDataDir());
  const std::string bytes = ReadBytes(path);
  ASSERT_TRUE(IsMatV5(bytes)) << path;
  EXPECT_NO_THROW(CheckMatV5Structure(bytes, path.string())) << path;
}

TEST(MatV5Structure, TheVictoriaParkFilesPass) {
  const testing::DataSetLookup found = testing::FindDataSetFiles("victoria-park");
  PHDSLAM_SKIP_WITHOUT_DATA_SET(found);
  const std::filesystem::path data = *found.dir;
  for (const auto& path :
       {data / "victoria-park" / "aa3_dr.mat", data / "victoria-park" / "aa3_gpsx.mat"}) {
    const std::string bytes = ReadBytes(path);
    ASSERT_TRUE(IsMatV5(bytes)) << path;
    EXPECT_NO_THROW(CheckMatV5Structure(bytes, path.string())) << path;
  }
}

TEST(MatV5Structure, FileCutInsideAVariableIsRefusedNamingTheFile) {
  const std::string good = ReadBytes(SyntheticMat(testing::SyntheticDataDir()));
  const auto dir = testing::FreshTestDir();
  const auto path = SyntheticMat(dir);
  WriteBytes(path, good.substr(0, good.size() * 6 / 10));
  const std::string error = ErrorOf([&] { (void)LoadPaperSyntheticEnvironment(dir); });
  EXPECT_NE(error.find(path.string()), std::string::npos) << error;
  EXPECT_NE(error.find("truncated"), std::string::npos) << error;
}

TEST(MatV5Structure, EveryTruncationOfTheSyntheticFileFailsToLoad) {
  const std::string good = ReadBytes(SyntheticMat(testing::SyntheticDataDir()));
  const auto dir = testing::FreshTestDir();
  for (std::size_t cut = 1; cut < good.size(); cut += 2749) {
    WriteBytes(SyntheticMat(dir), good.substr(0, cut));
    EXPECT_THROW((void)LoadPaperSyntheticEnvironment(dir), std::runtime_error) << "cut " << cut;
  }
}

TEST(MatV5Structure, ArrayDeclaringMoreElementsThanItStoresIsRefused) {
  const auto path = testing::FreshTestDir() / "short.mat";
  {
    mat_t* mat = Mat_CreateVer(path.c_str(), nullptr, MAT_FT_MAT5);
    ASSERT_NE(mat, nullptr);
    double values[3] = {1.0, 2.0, 3.0};
    size_t dims[2] = {3, 1};
    matvar_t* var = Mat_VarCreate("x", MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims, values, 0);
    ASSERT_NE(var, nullptr);
    ASSERT_EQ(Mat_VarWrite(mat, var, MAT_COMPRESSION_NONE), 0);
    Mat_VarFree(var);
    Mat_Close(mat);
  }
  std::string bytes = ReadBytes(path);
  // header (128) + matrix tag (8) + array flags (16) + dimensions tag (8): the row count.
  constexpr std::size_t kRowsOffset = 128 + 8 + 16 + 8;
  std::int32_t rows = 0;
  std::memcpy(&rows, bytes.data() + kRowsOffset, sizeof(rows));
  ASSERT_EQ(rows, 3);
  rows = 3000;
  std::memcpy(bytes.data() + kRowsOffset, &rows, sizeof(rows));
  WriteBytes(path, bytes);
  const std::string error = ErrorOf([&] { const MatFile file(path); });
  EXPECT_NE(error.find("declare 3000 elements but its real part stores 3"), std::string::npos)
      << error;
  EXPECT_NE(error.find("('x')"), std::string::npos) << error;
}

TEST(MatV5Structure, CorruptCompressedDataIsRefused) {
  std::string bytes = ReadBytes(SyntheticMat(testing::SyntheticDataDir()));
  for (std::size_t i = 400; i < 600; ++i) bytes[i] = static_cast<char>(bytes[i] ^ 0x5a);
  const std::string error = ErrorOf([&] { CheckMatV5Structure(bytes, "f.mat"); });
  EXPECT_NE(error.find("f.mat, variable #"), std::string::npos) << error;
}

TEST(MatV5Structure, CompressedSizeTheDataCannotInflateToIsRefusedUpFront) {
  // A compressed variable whose inner array tag declares 200 MB but whose deflated stream is a few
  // dozen bytes: deflate expands at most 1032:1, so the check refuses it without inflating (and
  // without allocating the declared size).
  const std::string header = ReadBytes(SyntheticMat(testing::SyntheticDataDir())).substr(0, 128);
  ASSERT_TRUE(IsMatV5(header));
  std::string inner(72, '\0');
  const std::uint32_t inner_tag[2] = {14, 200'000'000};  // miMATRIX, declared bytes
  std::memcpy(inner.data(), inner_tag, sizeof(inner_tag));
  std::string deflated(compressBound(inner.size()), '\0');
  uLongf deflated_size = deflated.size();
  ASSERT_EQ(compress(reinterpret_cast<Bytef*>(deflated.data()), &deflated_size,
                     reinterpret_cast<const Bytef*>(inner.data()), inner.size()),
            Z_OK);
  deflated.resize(deflated_size);
  const std::uint32_t outer_tag[2] = {15, static_cast<std::uint32_t>(deflated.size())};
  std::string bytes = header + std::string(sizeof(outer_tag), '\0') + deflated;
  std::memcpy(bytes.data() + 128, outer_tag, sizeof(outer_tag));
  const std::string error = ErrorOf([&] { CheckMatV5Structure(bytes, "f.mat"); });
  EXPECT_NE(error.find("f.mat, variable #1: declares 200000000 bytes, but its " +
                       std::to_string(deflated.size()) + " compressed bytes cannot inflate to"),
            std::string::npos)
      << error;
}

TEST(MatV5Structure, OtherFormatsAreNotVersion5) {
  EXPECT_FALSE(IsMatV5(""));
  EXPECT_FALSE(IsMatV5(std::string(200, 'x')));
  EXPECT_THROW(CheckMatV5Structure(std::string(64, '\0'), "f"), std::runtime_error);
}

}  // namespace
}  // namespace phdslam::datasets
