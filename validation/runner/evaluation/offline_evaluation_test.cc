#include "validation/runner/evaluation/offline_evaluation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <stdexcept>
#include <string>

namespace phdslam::validation {
namespace {

std::vector<datasets::StampedPose> Track(const std::vector<double>& times, double dx) {
  std::vector<datasets::StampedPose> out;
  for (double t : times) out.push_back({t, Pose(t + dx, 0.0, 0.1 * t)});
  return out;
}

TEST(MatchByTime, ExactStampsByDefault) {
  const auto truth = Track({0.0, 1.0, 2.0, 3.0}, 0.0);
  const auto estimate = Track({3.0, 1.0, 2.5}, 0.5);  // unsorted on purpose
  const TimeMatchedPoses m = MatchByTime(truth, estimate, 0.0);
  EXPECT_EQ(m.times, (std::vector<double>{1.0, 3.0}));
  ASSERT_EQ(m.estimate.size(), 2u);
  EXPECT_DOUBLE_EQ(m.estimate[0](0), 1.5);
  EXPECT_DOUBLE_EQ(m.estimate[1](0), 3.5);
}

TEST(MatchByTime, NearestWithinToleranceEarlierOnTies) {
  const auto truth = Track({1.0, 2.0, 5.0}, 0.0);
  const auto estimate = Track({0.9, 1.1, 2.04, 6.0}, 0.0);
  const TimeMatchedPoses m = MatchByTime(truth, estimate, 0.1);
  ASSERT_EQ(m.times, (std::vector<double>{1.0, 2.0}));
  EXPECT_DOUBLE_EQ(m.estimate[0](0), 0.9);  // 0.9 and 1.1 are equally near: the earlier one
  EXPECT_DOUBLE_EQ(m.estimate[1](0), 2.04);
  EXPECT_TRUE(MatchByTime(truth, {}, 1.0).times.empty());
  EXPECT_THROW(MatchByTime(truth, estimate, -1.0), std::invalid_argument);
  EXPECT_THROW(MatchByTime(truth, estimate, std::nan("")), std::invalid_argument);
  EXPECT_THROW(MatchByTime({{std::nan(""), Pose::Zero()}}, estimate, 0.0), std::invalid_argument);
}

TEST(CompareTrajectories, RmseOverMatchedPoses) {
  auto truth = Track({0.0, 1.0, 2.0}, 0.0);
  auto estimate = truth;
  estimate[1].pose += Pose(3.0, 4.0, 0.1);
  estimate[2].t = 7.0;  // not matched
  const nlohmann::json j = CompareTrajectories(truth, estimate, 0.0);
  EXPECT_EQ(j.at("matched"), 2);
  EXPECT_EQ(j.at("truth_poses"), 3);
  EXPECT_DOUBLE_EQ(j.at("pos_rmse_m").get<double>(), std::sqrt(25.0 / 2.0));
  EXPECT_NEAR(j.at("heading_rmse_deg").get<double>(),
              std::sqrt(0.01 / 2.0) * 180.0 / std::numbers::pi, 1e-12);
}

std::string InvalidArgument(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(CompareTrajectories, EmptyOrDisjointTrajectoriesAreRefused) {
  const auto truth = Track({0.0, 1.0, 2.0}, 0.0);
  EXPECT_NE(InvalidArgument([&] {
              (void)CompareTrajectories(truth, {}, 0.0);
            }).find("estimated trajectory holds no poses"),
            std::string::npos);
  EXPECT_NE(InvalidArgument([&] {
              (void)CompareTrajectories({}, truth, 0.0);
            }).find("true trajectory holds no poses"),
            std::string::npos);
  const std::string disjoint = InvalidArgument([&] {
    (void)CompareTrajectories(truth, Track({10.0, 11.0}, 0.0), 0.5);
  });
  EXPECT_NE(disjoint.find("do not overlap in time"), std::string::npos) << disjoint;
  EXPECT_NE(disjoint.find("10.000000..11.000000"), std::string::npos) << disjoint;
}

TEST(CompareMaps, OverflowingCutOffOrOrderIsRefused) {
  const std::vector<datasets::MapPoint> truth = {{Landmark(0.0, 0.0), 1.0, std::nullopt}};
  const std::vector<datasets::MapPoint> estimate = {{Landmark(0.0, 3.0), 0.5, std::nullopt}};
  EXPECT_NE(InvalidArgument([&] { (void)CompareMaps(truth, {}, 1e308, 2.0); }).find("overflow"),
            std::string::npos);
  EXPECT_NE(
      InvalidArgument([&] { (void)CompareMaps(truth, estimate, 20.0, 1000.0); }).find("overflow"),
      std::string::npos);
  EXPECT_NO_THROW((void)CompareMaps(truth, estimate, 20.0, 2.0));
}

TEST(CompareMaps, GospaPartsAndOspa) {
  const std::vector<datasets::MapPoint> truth = {{Landmark(0.0, 0.0), 1.0, std::nullopt},
                                                 {Landmark(10.0, 0.0), 1.0, std::nullopt}};
  const std::vector<datasets::MapPoint> estimate = {{Landmark(0.0, 3.0), 0.5, std::nullopt}};
  const nlohmann::json j = CompareMaps(truth, estimate, 20.0, 2.0);
  EXPECT_DOUBLE_EQ(j.at("gospa").get<double>(), std::sqrt(9.0 + 200.0));
  EXPECT_DOUBLE_EQ(j.at("localisation").get<double>(), 9.0);
  EXPECT_DOUBLE_EQ(j.at("missed").get<double>(), 200.0);
  EXPECT_DOUBLE_EQ(j.at("false").get<double>(), 0.0);
  EXPECT_EQ(j.at("n_missed"), 1);
  EXPECT_EQ(j.at("n_false"), 0);
  // OSPA, n = 2: ((9 + 400) / 2)^(1/2).
  EXPECT_DOUBLE_EQ(j.at("ospa").get<double>(), std::sqrt(409.0 / 2.0));
  EXPECT_THROW(CompareMaps(truth, estimate, -1.0, 2.0), std::invalid_argument);
}

}  // namespace
}  // namespace phdslam::validation
