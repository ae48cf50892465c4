#include "datasets/trajectory_io.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>

#include "datasets/test_temp_dir.h"

namespace phdslam::datasets {
namespace {

std::string ReadError(const std::filesystem::path& path) {
  try {
    (void)ReadTumTrajectory(path);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

std::filesystem::path WriteText(const std::string& name, const std::string& content) {
  const auto path = testing::FreshTestDir() / name;
  std::ofstream(path) << content;
  return path;
}

TEST(TumTrajectory, RoundTripKeepsUnwrappedHeadings) {
  std::vector<StampedPose> poses;
  for (int k = 0; k < 50; ++k) {
    // The heading turns through more than two full turns, 0.3 rad per pose.
    poses.push_back({0.1 * k + 1e-7, Pose(300.0 + 1.0 / 3.0 * k, -400.25 * k, -0.0872 + 0.3 * k)});
  }
  const auto path = testing::FreshTestDir() / "traj.tum";
  WriteTumTrajectory(path, poses);
  const auto read = ReadTumTrajectory(path);
  ASSERT_EQ(read.size(), poses.size());
  for (std::size_t k = 0; k < poses.size(); ++k) {
    EXPECT_EQ(read[k].t, poses[k].t);
    EXPECT_EQ(read[k].pose(0), poses[k].pose(0));
    EXPECT_EQ(read[k].pose(1), poses[k].pose(1));
    EXPECT_NEAR(read[k].pose(2), poses[k].pose(2), 1e-12);
  }
  std::ifstream in(path);
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header, "# t x y z qx qy qz qw");
}

TEST(TumTrajectory, WritesZAndQuaternionAboutZ) {
  const auto path = testing::FreshTestDir() / "one.tum";
  WriteTumTrajectory(path, {{2.5, Pose(1.0, -2.0, std::numbers::pi / 2.0)}});
  std::ifstream in(path);
  std::string header;
  std::string line;
  std::getline(in, header);
  std::getline(in, line);
  std::istringstream fields(line);
  double v[8];
  for (double& x : v) fields >> x;
  EXPECT_EQ(v[0], 2.5);
  EXPECT_EQ(v[1], 1.0);
  EXPECT_EQ(v[2], -2.0);
  EXPECT_EQ(v[3], 0.0);
  EXPECT_EQ(v[4], 0.0);
  EXPECT_EQ(v[5], 0.0);
  EXPECT_NEAR(v[6], std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(v[7], std::sqrt(0.5), 1e-15);
}

TEST(TumTrajectory, ReadsCommentsBlankLinesAndUnnormalisedQuaternions) {
  const auto path = WriteText("in.tum",
                              "# t x y z qx qy qz qw\n"
                              "\n"
                              "0 1 2 0.5 0 0 0 2\n"  // identity, scaled
                              "  # indented comment\n"
                              "1.5 3 4 0 0 0 0.9489846193555862 0.3153223623952687\n"    // 2.5
                              "2 5 6 0 0 0 -0.7071067811865476 -0.7071067811865476\n");  // -q
  const auto poses = ReadTumTrajectory(path);
  ASSERT_EQ(poses.size(), 3u);
  EXPECT_EQ(poses[0].t, 0.0);
  EXPECT_EQ(poses[0].pose, Pose(1.0, 2.0, 0.0));
  EXPECT_EQ(poses[1].t, 1.5);
  EXPECT_NEAR(poses[1].pose(2), 2.5, 1e-12);
  // -q is the same rotation, yaw pi/2 (wrapped to within pi of the previous heading).
  EXPECT_NEAR(poses[2].pose(2), std::numbers::pi / 2.0, 1e-12);
}

TEST(TumTrajectory, MalformedLinesNameFileAndLine) {
  auto path = WriteText("cols.tum", "# header\n0 1 2 0 0 0 0 1\n1 2 3 0 0 0 1\n");
  std::string message = ReadError(path);
  EXPECT_NE(message.find(path.string() + ":3:"), std::string::npos) << message;
  EXPECT_NE(message.find("expected 8 values"), std::string::npos) << message;
  EXPECT_NE(message.find("found 7"), std::string::npos) << message;

  path = WriteText("word.tum", "0 1 2 0 0 0 0 1\n1 2 abc 0 0 0 0 1\n");
  message = ReadError(path);
  EXPECT_NE(message.find(path.string() + ":2:"), std::string::npos) << message;
  EXPECT_NE(message.find("column 3 (y): 'abc' is not a number"), std::string::npos) << message;

  path = WriteText("nan.tum", "0 nan 2 0 0 0 0 1\n");
  message = ReadError(path);
  EXPECT_NE(message.find(path.string() + ":1:"), std::string::npos) << message;
  EXPECT_NE(message.find("column 2 (x) is not finite"), std::string::npos) << message;

  path = WriteText("zero.tum", "0 1 2 0 0 0 0 0\n");
  message = ReadError(path);
  EXPECT_NE(message.find(":1: the quaternion"), std::string::npos) << message;

  path = WriteText("trailing.tum", "0 1 2 0 0 0 0 1x\n");
  message = ReadError(path);
  EXPECT_NE(message.find("column 8 (qw): '1x' is not a number"), std::string::npos) << message;

  path = WriteText("duplicate.tum", "0 1 2 0 0 0 0 1\n1 2 2 0 0 0 0 1\n0 5 2 0 0 0 0 1\n");
  message = ReadError(path);
  EXPECT_NE(message.find(path.string() + ":3: time stamp 0 repeats that of line 1"),
            std::string::npos)
      << message;

  path = WriteText("escape.tum", "0 1 \x1b[2J 0 0 0 0 1\n");
  message = ReadError(path);
  EXPECT_EQ(message.find('\x1b'), std::string::npos) << message;
  EXPECT_NE(message.find("'\\x1b[2J' is not a number"), std::string::npos) << message;

  path = WriteText("tilted.tum", "0 1 2 0 0.3826834323650898 0 0 0.9238795325112867\n");
  message = ReadError(path);
  EXPECT_NE(message.find(":1: the quaternion is not a rotation about z"), std::string::npos)
      << message;

  path = WriteText("empty.tum", "# t x y z qx qy qz qw\n\n");
  message = ReadError(path);
  EXPECT_NE(message.find("holds no poses"), std::string::npos) << message;

  message = ReadError(testing::FreshTestDir() / "missing.tum");
  EXPECT_NE(message.find("missing.tum"), std::string::npos) << message;
}

TEST(TumTrajectory, WriterRejectsNonFiniteValues) {
  const auto path = testing::FreshTestDir() / "bad.tum";
  try {
    WriteTumTrajectory(path, {{0.0, Pose::Zero()}, {1.0, Pose(0.0, std::nan(""), 0.0)}});
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("pose 1"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace phdslam::datasets
