#include "datasets/mat_file.h"

#include <gtest/gtest.h>
#include <matio.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "datasets/data_dir.h"
#include "datasets/mat_v5_structure.h"
#include "datasets/test_data_sets.h"
#include "datasets/test_file_bytes.h"
#include "datasets/test_temp_dir.h"
#include "src/core/angles.h"

namespace phdslam::datasets {
namespace {

/// Writes variables into a fresh MAT-file (version 5 unless told) with libmatio.
class MatWriter {
 public:
  explicit MatWriter(const std::filesystem::path& path, mat_ft version = MAT_FT_MAT5)
      : mat_(Mat_CreateVer(path.c_str(), nullptr, version)) {
    if (mat_ == nullptr) throw std::runtime_error("cannot create " + path.string());
  }
  ~MatWriter() { Mat_Close(mat_); }
  MatWriter(const MatWriter&) = delete;
  MatWriter& operator=(const MatWriter&) = delete;

  void Write(const char* name, matio_classes cls, matio_types type, std::vector<size_t> dims,
             void* data, int flags = 0, matio_compression compression = MAT_COMPRESSION_NONE) {
    matvar_t* var =
        Mat_VarCreate(name, cls, type, static_cast<int>(dims.size()), dims.data(), data, flags);
    ASSERT_NE(var, nullptr);
    ASSERT_EQ(Mat_VarWrite(mat_, var, compression), 0);
    Mat_VarFree(var);
  }

 private:
  mat_t* mat_;
};

std::string ReadError(const MatFile& file, const std::string& variable) {
  try {
    (void)file.ReadMatrix(variable);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(MatFile, ReadsTheRealSyntheticEnvironment) {
  const auto path = testing::SyntheticDataDir() / "phdslam3-synthetic" / "Environment_SLAM.mat";
  const MatFile file(path);
  EXPECT_TRUE(file.Has("Landmark_Groundtruth"));
  EXPECT_TRUE(file.Has("Robot_Control"));
  EXPECT_FALSE(file.Has("No_Such_Variable"));

  const Eigen::MatrixXd landmarks = file.ReadMatrix("Landmark_Groundtruth");
  EXPECT_EQ(landmarks.rows(), 160);
  EXPECT_EQ(landmarks.cols(), 5);
  const Eigen::MatrixXd controls = file.ReadMatrix("Robot_Control");
  EXPECT_EQ(controls.rows(), 2);
  EXPECT_EQ(controls.cols(), 4000);
  // Ranges stated in docs/algorithms/models.md section 5.1.
  EXPECT_GE(controls.row(0).minCoeff(), 0.83);
  EXPECT_LE(controls.row(0).maxCoeff(), 1.18);
  EXPECT_LE(controls.row(1).cwiseAbs().maxCoeff(), 0.0173);
  const Eigen::MatrixXd truth = file.ReadMatrix("Robot_Groundtruth");
  ASSERT_EQ(truth.rows(), 3);
  EXPECT_DOUBLE_EQ(truth(0, 0), 300.0);
  EXPECT_DOUBLE_EQ(truth(1, 0), 400.0);
  EXPECT_NEAR(truth(2, 0), DegToRad(-5.0), 1e-12);
}

TEST(MatFile, MissingFileErrorNamesTheFile) {
  const auto path = testing::FreshTestDir() / "missing.mat";
  try {
    const MatFile file(path);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  }
}

TEST(MatFile, NonMatFileErrorNamesTheFile) {
  const auto path = testing::FreshTestDir() / "text.mat";
  std::ofstream(path) << "this is not a MAT-file\n";
  try {
    const MatFile file(path);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  }
}

TEST(MatFile, Version73FileIsRefusedWithHowToResaveIt) {
  const auto path = testing::FreshTestDir() / "v73.mat";
  {
    MatWriter w(path, MAT_FT_MAT73);
    double d[2] = {1.0, 2.0};
    w.Write("d", MAT_C_DOUBLE, MAT_T_DOUBLE, {1, 2}, d);
  }
  const std::string what = testing::ErrorOf([&] { const MatFile file(path); });
  EXPECT_NE(what.find(path.string()), std::string::npos) << what;
  EXPECT_NE(what.find("version 7.3"), std::string::npos) << what;
  EXPECT_NE(what.find("-v7"), std::string::npos) << what;
}

TEST(MatFile, ConvertsEveryNumericClassColumnMajor) {
  const auto path = testing::FreshTestDir() / "classes.mat";
  {
    MatWriter w(path);
    double d[6] = {1.5, -2.0, 3.0, 4.0, 5.0, 6.25};  // 2 x 3, column-major
    w.Write("d", MAT_C_DOUBLE, MAT_T_DOUBLE, {2, 3}, d);
    float f[2] = {0.5f, -1.25f};
    w.Write("f", MAT_C_SINGLE, MAT_T_SINGLE, {1, 2}, f);
    std::int16_t i16[3] = {-7, 0, 32767};
    w.Write("i16", MAT_C_INT16, MAT_T_INT16, {3, 1}, i16);
    std::uint8_t u8[2] = {0, 255};
    w.Write("u8", MAT_C_UINT8, MAT_T_UINT8, {2, 1}, u8);
    std::uint16_t u16[1] = {60000};
    w.Write("u16", MAT_C_UINT16, MAT_T_UINT16, {1, 1}, u16);
    std::int64_t i64[1] = {-123456789012LL};
    w.Write("i64", MAT_C_INT64, MAT_T_INT64, {1, 1}, i64);
  }
  const MatFile file(path);
  Eigen::MatrixXd expected_d(2, 3);
  expected_d << 1.5, 3.0, 5.0, -2.0, 4.0, 6.25;
  EXPECT_EQ(file.ReadMatrix("d"), expected_d);
  EXPECT_EQ(file.ReadMatrix("f"), Eigen::RowVector2d(0.5, -1.25));
  EXPECT_EQ(file.ReadMatrix("i16"), Eigen::Vector3d(-7.0, 0.0, 32767.0));
  EXPECT_EQ(file.ReadMatrix("u8"), Eigen::Vector2d(0.0, 255.0));
  EXPECT_EQ(file.ReadMatrix("u16")(0, 0), 60000.0);
  EXPECT_EQ(file.ReadMatrix("i64")(0, 0), -123456789012.0);
}

TEST(MatFile, ClearErrorsForBadVariables) {
  const auto path = testing::FreshTestDir() / "bad.mat";
  {
    MatWriter w(path);
    char text[3] = {'a', 'b', 'c'};
    w.Write("text", MAT_C_CHAR, MAT_T_UINT8, {1, 3}, text);
    double re[2] = {1.0, 2.0};
    double im[2] = {0.5, 0.0};
    mat_complex_split_t z = {re, im};
    w.Write("z", MAT_C_DOUBLE, MAT_T_DOUBLE, {1, 2}, &z, MAT_F_COMPLEX);
    double cube[8] = {};
    w.Write("cube", MAT_C_DOUBLE, MAT_T_DOUBLE, {2, 2, 2}, cube);
  }
  const MatFile file(path);
  const auto expect_error = [&](const std::string& var, const std::string& what) {
    const std::string message = ReadError(file, var);
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
    EXPECT_NE(message.find("'" + var + "'"), std::string::npos) << message;
    EXPECT_NE(message.find(what), std::string::npos) << message;
  };
  expect_error("missing", "no such variable");
  expect_error("text", "class char");
  expect_error("z", "complex");
  expect_error("cube", "3 dimensions");
}

TEST(MatFile, VariableLargerThanTheSizeCapIsRefusedBeforeItIsRead) {
  // A double-class variable stored as deflated uint8 zeros: 33.6 MB inflated (under the cap, so the
  // structure check passes) but 269 MB as doubles, more than kMaxMatVariableBytes; read, it would
  // take that twice (libmatio's copy and the matrix).
  const auto path = testing::FreshTestDir() / "bomb.mat";
  const std::vector<size_t> dims = {size_t{1} << 15, (size_t{1} << 10) + 1};
  ASSERT_GT(dims[0] * dims[1] * sizeof(double), kMaxMatVariableBytes);
  {
    std::vector<std::uint8_t> zeros(dims[0] * dims[1], 0);
    MatWriter w(path);
    w.Write("bomb", MAT_C_DOUBLE, MAT_T_UINT8, dims, zeros.data(), 0, MAT_COMPRESSION_ZLIB);
  }
  ASSERT_LT(std::filesystem::file_size(path), 1U << 20);
  const MatFile file(path);
  const std::string message = ReadError(file, "bomb");
  EXPECT_NE(message.find("'bomb': its 32768 x 1025 elements would take more than the 268435456 "
                         "bytes accepted for one variable"),
            std::string::npos)
      << message;
}

TEST(MatFile, IsMovable) {
  const auto path = testing::SyntheticDataDir() / "phdslam3-synthetic" / "Environment_SLAM.mat";
  MatFile first(path);
  MatFile second(std::move(first));
  EXPECT_EQ(second.ReadMatrix("Robot_Control").cols(), 4000);
}

}  // namespace
}  // namespace phdslam::datasets
