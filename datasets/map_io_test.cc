#include "datasets/map_io.h"

#include <gtest/gtest.h>

#include <fstream>
#include <stdexcept>
#include <string>

#include "datasets/test_temp_dir.h"

namespace phdslam::datasets {
namespace {

std::string ReadError(const std::filesystem::path& path) {
  try {
    (void)ReadMapCsv(path);
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

TEST(MapCsv, RoundTripWithAndWithoutCovariances) {
  std::vector<MapPoint> points(3);
  points[0].position = Landmark(1.0 / 3.0, -250.125);
  points[0].weight = 1.0000000000000004e-06;
  Mat2 cov;
  cov << 0.64, 1e-4, 1e-4, 2.7416e-5;
  points[0].cov = cov;
  points[1].position = Landmark(1e-300, 7e12);
  points[2].position = Landmark(-0.0, 42.0);
  points[2].weight = 0.5;
  points[2].cov = Mat2::Identity();
  const auto path = testing::FreshTestDir() / "map.csv";
  WriteMapCsv(path, points);
  const auto read = ReadMapCsv(path);
  ASSERT_EQ(read.size(), points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    EXPECT_EQ(read[i].position, points[i].position) << i;
    EXPECT_EQ(read[i].weight, points[i].weight) << i;
    ASSERT_EQ(read[i].cov.has_value(), points[i].cov.has_value()) << i;
    if (read[i].cov) {
      EXPECT_EQ(*read[i].cov, *points[i].cov) << i;
    }
  }
  std::ifstream in(path);
  std::string header;
  std::string second_point;
  std::getline(in, header);
  std::getline(in, second_point);
  std::getline(in, second_point);
  EXPECT_EQ(header, "x,y,weight,pxx,pxy,pyy");
  EXPECT_EQ(second_point, "1e-300,7e+12,0,,,");
}

TEST(MapCsv, ColumnsInAnyOrderOptionalOnesAbsent) {
  auto path = WriteText("order.csv",
                        "# a comment\n"
                        "id, pyy ,y,pxy,x,pxx\n"
                        "7,4,2,0.5,1,9\n"
                        "\n"
                        "8,,3,,-1,\n");
  auto read = ReadMapCsv(path);
  ASSERT_EQ(read.size(), 2u);
  EXPECT_EQ(read[0].position, Landmark(1.0, 2.0));
  EXPECT_EQ(read[0].weight, 0.0);
  ASSERT_TRUE(read[0].cov.has_value());
  Mat2 expected;
  expected << 9.0, 0.5, 0.5, 4.0;
  EXPECT_EQ(*read[0].cov, expected);
  EXPECT_EQ(read[1].position, Landmark(-1.0, 3.0));
  EXPECT_FALSE(read[1].cov.has_value());

  path = WriteText("xy.csv", "y,x\r\n5,6\r\n");
  read = ReadMapCsv(path);
  ASSERT_EQ(read.size(), 1u);
  EXPECT_EQ(read[0].position, Landmark(6.0, 5.0));
  EXPECT_FALSE(read[0].cov.has_value());
}

TEST(MapCsv, MalformedInputNamesFileLineAndColumn) {
  auto path = WriteText("nox.csv", "\nweight,y\n1,2\n");
  auto message = ReadError(path);
  EXPECT_NE(message.find(path.string() + ":2:"), std::string::npos) << message;
  EXPECT_NE(message.find("required column 'x'"), std::string::npos) << message;

  path = WriteText("word.csv", "x,y,weight\n1,2,3\n4,five,6\n");
  message = ReadError(path);
  EXPECT_NE(message.find(path.string() + ":3:"), std::string::npos) << message;
  EXPECT_NE(message.find("column 'y' (field 2): 'five' is not a number"), std::string::npos)
      << message;

  path = WriteText("count.csv", "x,y\n1,2,3\n");
  message = ReadError(path);
  EXPECT_NE(message.find(path.string() + ":2:"), std::string::npos) << message;
  EXPECT_NE(message.find("expected 2 comma-separated fields"), std::string::npos) << message;

  path = WriteText("nan.csv", "x,y,weight\n1,2,nan\n");
  message = ReadError(path);
  EXPECT_NE(message.find(":2: column 'weight' (field 3) is not finite"), std::string::npos)
      << message;

  path = WriteText("emptyx.csv", "x,y\n,2\n");
  EXPECT_NE(ReadError(path).find(":2: column 'x' (field 1) is empty"), std::string::npos);

  path = WriteText("partial.csv", "x,y,pxx,pxy,pyy\n1,2,1,,1\n");
  EXPECT_NE(ReadError(path).find(":2: column 'pxy' is empty"), std::string::npos);

  path = WriteText("header.csv", "x,y,pxx\n1,2,3\n");
  EXPECT_NE(ReadError(path).find(":1: header: the covariance columns"), std::string::npos);

  path = WriteText("twice.csv", "x,y,x\n1,2,3\n");
  EXPECT_NE(ReadError(path).find(":1: header: column 'x' appears twice"), std::string::npos);

  path = WriteText("negative.csv", "x,y,pxx,pxy,pyy\n1,2,-1,0,1\n");
  EXPECT_NE(ReadError(path).find(":2: column 'pxx'"), std::string::npos);

  path = WriteText("indefinite.csv", "x,y,pxx,pxy,pyy\n1,2,1,2,1\n");
  EXPECT_NE(ReadError(path).find(":2: column 'pxy': covariance"), std::string::npos);

  path = WriteText("empty.csv", "# nothing\n");
  EXPECT_NE(ReadError(path).find("no header line"), std::string::npos);
}

TEST(MapCsv, LimitsNameTheLineAndColumn) {
  auto path = WriteText("negative.csv", "x,y,weight\n1,2,0.5\n1,2,-5\n");
  std::string message = ReadError(path);
  EXPECT_NE(message.find(":3: column 'weight' (field 3): -5 is outside [0, inf]"),
            std::string::npos)
      << message;

  MapValueLimits limits;
  limits.max_weight = 1.0;
  limits.max_abs_value = 1e9;
  limits.max_points = 2;
  path = WriteText("heavy.csv", "x,y,weight\n1,2,1.5\n");
  try {
    (void)ReadMapCsv(path, limits);
    FAIL() << "a weight of 1.5 was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(":2: column 'weight' (field 3): 1.5 is outside [0, 1]"),
              std::string::npos)
        << e.what();
  }
  path = WriteText("far.csv", "x,y\n1e300,2\n");
  try {
    (void)ReadMapCsv(path, limits);
    FAIL() << "x = 1e300 was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(":2: column 'x' (field 1): 1e+300 is beyond +-1e+09"),
              std::string::npos)
        << e.what();
  }
  path = WriteText("long.csv", "x,y\n1,1\n2,2\n3,3\n");
  try {
    (void)ReadMapCsv(path, limits);
    FAIL() << "a third landmark was accepted beyond the cap of 2";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(":4: more than 2 landmarks"), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(ReadMapCsv(WriteText("fine.csv", "x,y,weight\n1,2,1\n3,4,0\n"), limits).size(), 2U);
}

TEST(MapCsv, WriterRejectsNonFiniteValues) {
  std::vector<MapPoint> points(2);
  points[1].weight = std::numeric_limits<double>::infinity();
  try {
    WriteMapCsv(testing::FreshTestDir() / "bad.csv", points);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("point 1"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace phdslam::datasets
