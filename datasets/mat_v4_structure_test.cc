#include "datasets/mat_v4_structure.h"

#include <gtest/gtest.h>
#include <matio.h>

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>

#include "datasets/mat_file.h"
#include "datasets/test_file_bytes.h"
#include "datasets/test_temp_dir.h"

namespace phdslam::datasets {
namespace {

using testing::ErrorOf;
using testing::ReadBytes;
using testing::WriteBytes;

/// A version 4 file written by libmatio: "a" (2 x 3 doubles) then "b" (1 x 2 uint8 as double).
std::filesystem::path WriteV4File() {
  const auto path = testing::FreshTestDir() / "v4.mat";
  mat_t* mat = Mat_CreateVer(path.c_str(), nullptr, MAT_FT_MAT4);
  if (mat == nullptr) throw std::runtime_error("cannot create " + path.string());
  double a[6] = {1, 2, 3, 4, 5, 6};
  std::uint8_t b[2] = {7, 250};
  size_t dims_a[2] = {2, 3};
  size_t dims_b[2] = {1, 2};
  matvar_t* va = Mat_VarCreate("a", MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims_a, a, 0);
  matvar_t* vb = Mat_VarCreate("b", MAT_C_DOUBLE, MAT_T_UINT8, 2, dims_b, b, 0);
  const bool written = va != nullptr && vb != nullptr &&
                       Mat_VarWrite(mat, va, MAT_COMPRESSION_NONE) == 0 &&
                       Mat_VarWrite(mat, vb, MAT_COMPRESSION_NONE) == 0;
  Mat_VarFree(va);
  Mat_VarFree(vb);
  Mat_Close(mat);
  if (!written) throw std::runtime_error("cannot write " + path.string());
  return path;
}

/// Overwrites the int32 at `offset` (this machine's byte order, as libmatio writes).
void Poke(std::string& bytes, std::size_t offset, std::int32_t value) {
  std::memcpy(bytes.data() + offset, &value, sizeof(value));
}

// First variable: header at 0 (type, rows, cols, imagf, name length), name "a\0" at 20, data at 22.
constexpr std::size_t kRows = 4;
constexpr std::size_t kNameLength = 16;

TEST(MatV4Structure, AVersion4FileWrittenByLibmatioPassesAndReads) {
  const auto path = WriteV4File();
  const std::string bytes = ReadBytes(path);
  ASSERT_EQ(bytes.size(), 20 + 2 + 6 * 8 + 20 + 2 + 2 * 1);
  EXPECT_NO_THROW(CheckMatV4Structure(bytes, "v4.mat"));
  const MatFile file(path);
  Eigen::MatrixXd a(2, 3);
  a << 1, 3, 5, 2, 4, 6;
  EXPECT_EQ(file.ReadMatrix("a"), a);
  EXPECT_EQ(file.ReadMatrix("b"), Eigen::RowVector2d(7.0, 250.0));
}

TEST(MatV4Structure, NameLongerThanTheFileIsRefusedBeforeLibmatioAllocatesIt) {
  const auto path = WriteV4File();
  std::string bytes = ReadBytes(path);
  Poke(bytes, kNameLength, 2'000'000'000);
  WriteBytes(path, bytes);
  const std::string error = ErrorOf([&] { const MatFile file(path); });
  EXPECT_NE(error.find(path.string()), std::string::npos) << error;
  EXPECT_NE(error.find("read as version 4), variable #1: name length 2000000000 is not between 1 "
                       "and the 74 bytes left"),
            std::string::npos)
      << error;
}

TEST(MatV4Structure, DimensionsDeclaringMoreDataThanTheFileHoldsAreRefused) {
  std::string bytes = ReadBytes(WriteV4File());
  Poke(bytes, kRows, 1 << 30);
  const std::string error = ErrorOf([&] { CheckMatV4Structure(bytes, "v4.mat"); });
  EXPECT_NE(error.find("v4.mat, variable #1: its 1073741824 x 3 elements of 8 bytes need more than "
                       "the 72 bytes left"),
            std::string::npos)
      << error;
  Poke(bytes, kRows, -2);
  EXPECT_NE(ErrorOf([&] { CheckMatV4Structure(bytes, "v4.mat"); }).find("negative dimensions"),
            std::string::npos);
}

TEST(MatV4Structure, EveryTruncationFailsToLoad) {
  const auto path = WriteV4File();
  const std::string good = ReadBytes(path);
  constexpr std::size_t kFirstVariableEnd = 20 + 2 + 6 * 8;  // a file holding only "a"
  for (std::size_t cut = 0; cut < good.size(); ++cut) {
    WriteBytes(path, good.substr(0, cut));
    if (cut == kFirstVariableEnd) {
      const MatFile file(path);
      EXPECT_EQ(file.ReadMatrix("a").size(), 6);
      EXPECT_FALSE(file.Has("b"));
    } else {
      EXPECT_THROW((void)MatFile(path), std::runtime_error) << "cut " << cut;
    }
  }
}

TEST(MatV4Structure, UnknownTypeWordIsRefusedNamingIt) {
  std::string bytes = ReadBytes(WriteV4File());
  Poke(bytes, 0, 60);  // P = 6 does not exist
  EXPECT_NE(ErrorOf([&] {
              CheckMatV4Structure(bytes, "v4.mat");
            }).find("type word 60 is not one libmatio reads"),
            std::string::npos);
  const std::string text = "this is not a MAT-file\n";
  EXPECT_NE(ErrorOf([&] { CheckMatV4Structure(text, "t.mat"); }).find("is not a version 4 type"),
            std::string::npos);
}

}  // namespace
}  // namespace phdslam::datasets
