#include "reference/ceres/scan_association.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "reference/ceres/batch_smoother.h"
#include "reference/ceres/factor_graph.h"
#include "reference/ceres/test_scenario.h"
#include "src/models/range_bearing_model.h"

namespace phdslam::reference {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

Mat2 SensorNoise() { return Vec2(0.1 * 0.1, (0.5 * kDeg) * (0.5 * kDeg)).asDiagonal(); }

/// A measurement of `m` from `x` shifted by (dr, dphi).
Measurement Observe(const Pose& x, const Landmark& m, double dr, double dphi) {
  const Measurement z = models::PredictMeasurement(x, m);
  return {z(0) + dr, z(1) + dphi};
}

/// Two landmarks 0.8 m apart at 10 m (about 4.6 bearing standard deviations), a third far away,
/// and clutter: each detection goes to its own landmark, the clutter to none.
TEST(ScanAssociationTest, TwoCloseLandmarksAndClutter) {
  const Pose x(0.0, 0.0, 0.3);
  const Mat3 px = Vec3(1e-4, 1e-4, 1e-6).asDiagonal();
  const Mat2 pm = 0.01 * 0.01 * Mat2::Identity();
  const std::vector<MapLandmark> map{{Landmark(8.0, 6.0), pm},
                                     {Landmark(7.52, 6.64), pm},  // 0.8 m from the first
                                     {Landmark(-20.0, 5.0), pm}};
  const std::vector<Measurement> scan{
      {12.0, 0.1},                                              // clutter between nothing
      Observe(x, map[1].mean, 0.05, -0.3 * kDeg),               // the second landmark
      Observe(x, map[0].mean, -0.08, 0.4 * kDeg),               // the first
      {5.0, -1.2},                                              // clutter
      Observe(x, map[0].mean + Landmark(0.35, 0.25), 0.0, 0.0)  // clutter near the first
  };
  const ScanAssociation a = AssociateScan(x, px, map, scan, SensorNoise(), {});
  ASSERT_EQ(a.landmark.size(), scan.size());
  EXPECT_EQ(a.landmark[0], kUnassociated);
  EXPECT_EQ(a.landmark[1], 1);
  EXPECT_EQ(a.landmark[2], 0);
  EXPECT_EQ(a.landmark[3], kUnassociated);
  EXPECT_EQ(a.landmark[4], kUnassociated);
  EXPECT_GT(a.mahalanobis2[1], 0.0);
  EXPECT_LT(a.mahalanobis2[1], 13.8);
  EXPECT_EQ(a.mahalanobis2[0], 0.0);
}

/// Two detections inside one landmark's gate: the nearer one gets it, the other none.
TEST(ScanAssociationTest, EachLandmarkAtMostOncePerScan) {
  const Pose x(1.0, 2.0, -0.4);
  const std::vector<MapLandmark> map{{Landmark(11.0, 2.0), 0.01 * Mat2::Identity()}};
  const std::vector<Measurement> scan{Observe(x, map[0].mean, 0.2, 0.0),
                                      Observe(x, map[0].mean, 0.05, 0.0)};
  const ScanAssociation a = AssociateScan(x, Mat3::Zero(), map, scan, SensorNoise(), {});
  EXPECT_EQ(a.landmark[0], kUnassociated);
  EXPECT_EQ(a.landmark[1], 0);
}

/// The gate widens with the marginal pose covariance: a detection 2 m off in range fails it for a
/// well-known pose and passes it for a pose known to +-2 m.
TEST(ScanAssociationTest, GateUsesThePoseCovariance) {
  const Pose x(0.0, 0.0, 0.0);
  const std::vector<MapLandmark> map{{Landmark(20.0, 0.0), 1e-4 * Mat2::Identity()}};
  const std::vector<Measurement> scan{Observe(x, map[0].mean, 2.0, 0.0)};
  const Mat3 tight = Vec3(1e-4, 1e-4, 1e-6).asDiagonal();
  const Mat3 loose = Vec3(4.0, 4.0, 1e-6).asDiagonal();
  EXPECT_EQ(AssociateScan(x, tight, map, scan, SensorNoise(), {}).landmark[0], kUnassociated);
  EXPECT_EQ(AssociateScan(x, loose, map, scan, SensorNoise(), {}).landmark[0], 0);
  // ... and with the landmark's: the same detection against a landmark known to +-2 m.
  const std::vector<MapLandmark> vague{{Landmark(20.0, 0.0), 4.0 * Mat2::Identity()}};
  EXPECT_EQ(AssociateScan(x, tight, vague, scan, SensorNoise(), {}).landmark[0], 0);
}

/// A landmark that shares the pose's drift (cross-covariance C = Cov(m, x) equal to the common
/// position covariance): the relative uncertainty is only the noise, and a detection 2 m off in
/// range, inside the gate without C, is outside it with C.
TEST(ScanAssociationTest, GateUsesThePoseLandmarkCrossCovariance) {
  const Pose x(0.0, 0.0, 0.0);
  const Mat3 px = Vec3(4.0, 4.0, 1e-6).asDiagonal();
  MapLandmark drifting{Landmark(20.0, 0.0), 4.0 * Mat2::Identity()};
  const std::vector<Measurement> scan{Observe(x, drifting.mean, 2.0, 0.0)};
  EXPECT_EQ(AssociateScan(x, px, {drifting}, scan, SensorNoise(), {}).landmark[0], 0);
  drifting.pose_cross.leftCols<2>() = 4.0 * Mat2::Identity();
  EXPECT_EQ(AssociateScan(x, px, {drifting}, scan, SensorNoise(), {}).landmark[0], kUnassociated);
  // The undisturbed detection still passes.
  const std::vector<Measurement> exact{Observe(x, drifting.mean, 0.0, 0.0)};
  EXPECT_EQ(AssociateScan(x, px, {drifting}, exact, SensorNoise(), {}).landmark[0], 0);
}

/// After a long stretch of dead reckoning (pose known to +-2 m, +-50 deg) a detection of a
/// landmark that is not mapped falls inside the gate of a mapped neighbour 1.5 m away, and the
/// nearest neighbour takes it. Against a new landmark of intensity 1 per m per rad the match is
/// too vague (pD N(nu; 0, S) ~ 0.02): the detection stays unassociated and starts a landmark. The
/// same detection from a well-known pose still matches the landmark it comes from.
TEST(ScanAssociationTest, NewLandmarkIntensityRejectsMatchesUnderAWidePose) {
  const Pose x(0.0, 0.0, 0.0);
  const Mat2 pm = 0.05 * 0.05 * Mat2::Identity();
  const std::vector<MapLandmark> map{
      {Landmark(2.0, 1.5), pm, Eigen::Matrix<double, 2, 3>::Zero(), 0.4}};  // mapped neighbour
  const Landmark unmapped(2.5, 0.0);
  const std::vector<Measurement> scan{Observe(x, unmapped, 0.0, 0.0)};
  const Mat3 wide = Vec3(2.0 * 2.0, 2.0 * 2.0, std::pow(50.0 * kDeg, 2)).asDiagonal();
  ScanAssociationOptions lr;
  lr.new_landmark_intensity = 1.0;
  const ScanAssociation nn = AssociateScan(x, wide, map, scan, SensorNoise(), {});
  EXPECT_EQ(nn.landmark[0], 0);
  EXPECT_EQ(nn.gated[0], 1);
  const ScanAssociation tested = AssociateScan(x, wide, map, scan, SensorNoise(), lr);
  EXPECT_EQ(tested.landmark[0], kUnassociated);
  EXPECT_EQ(tested.gated[0], 0);
  const Mat3 tight = Vec3(1e-3, 1e-3, 1e-5).asDiagonal();
  const std::vector<MapLandmark> mapped{{unmapped, pm, Eigen::Matrix<double, 2, 3>::Zero(), 0.4}};
  EXPECT_EQ(AssociateScan(x, tight, mapped, scan, SensorNoise(), lr).landmark[0], 0);
  lr.new_landmark_intensity = -1.0;
  EXPECT_THROW(AssociateScan(x, tight, mapped, scan, SensorNoise(), lr), std::invalid_argument);
}

/// A landmark started from the current (wide) pose carries that pose's uncertainty: without its
/// cross-covariance with the pose the innovation covariance counts it twice and the likelihood
/// test refuses the landmark's own second detection; with it (C = Jx Px) the pose's part cancels
/// and the detection is associated.
TEST(ScanAssociationTest, CrossCovarianceKeepsALandmarkStartedFromTheSamePose) {
  const Pose x(1.0, -1.0, 0.4);
  const Mat3 px = Vec3(2.0 * 2.0, 2.0 * 2.0, std::pow(50.0 * kDeg, 2)).asDiagonal();
  const Measurement first(3.0, 0.2);
  const Landmark m = models::InverseMeasurement(x, first);
  const double a = x(2) + first(1);
  Eigen::Matrix<double, 2, 3> jx;
  jx << 1.0, 0.0, -first(0) * std::sin(a), 0.0, 1.0, first(0) * std::cos(a);
  MapLandmark started{m,
                      models::BirthCovariance(x, first, SensorNoise()) + jx * px * jx.transpose(),
                      Eigen::Matrix<double, 2, 3>::Zero(), 0.4};
  const std::vector<Measurement> again{Measurement(3.05, 0.2 + 0.3 * kDeg)};
  ScanAssociationOptions lr;
  lr.new_landmark_intensity = 1.0;
  EXPECT_EQ(AssociateScan(x, px, {started}, again, SensorNoise(), lr).landmark[0], kUnassociated);
  started.pose_cross = jx * px;
  EXPECT_EQ(AssociateScan(x, px, {started}, again, SensorNoise(), lr).landmark[0], 0);
}

TEST(ScanAssociationTest, LandmarksBeyondTheDistanceLimitAreSkipped) {
  const Pose x(0.0, 0.0, 0.0);
  const std::vector<MapLandmark> map{{Landmark(30.0, 0.0), 1e-4 * Mat2::Identity()}};
  const std::vector<Measurement> scan{Observe(x, map[0].mean, 0.0, 0.0)};
  ScanAssociationOptions o;
  o.max_landmark_distance = 25.0;
  EXPECT_EQ(AssociateScan(x, Mat3::Zero(), map, scan, SensorNoise(), o).landmark[0], kUnassociated);
  o.max_landmark_distance = 35.0;
  EXPECT_EQ(AssociateScan(x, Mat3::Zero(), map, scan, SensorNoise(), o).landmark[0], 0);
  o.gate_chi2 = 0.0;
  EXPECT_THROW(AssociateScan(x, Mat3::Zero(), map, scan, SensorNoise(), o), std::invalid_argument);
}

TEST(ScanAssociationTest, ConfirmationByRepeatedAssociation) {
  const ConfirmationOptions o{3, 0.3};
  EXPECT_EQ(ClassifyLandmark({1, 0.9}, o), LandmarkStatus::kTentative);
  EXPECT_EQ(ClassifyLandmark({2, 2.7}, o), LandmarkStatus::kTentative);
  EXPECT_EQ(ClassifyLandmark({3, 3.0}, o), LandmarkStatus::kConfirmed);
  // Clutter that fell into a gate twice in the ten scans expected to see it.
  EXPECT_EQ(ClassifyLandmark({2, 9.0}, o), LandmarkStatus::kDeleted);
  EXPECT_EQ(ClassifyLandmark({3, 10.1}, o), LandmarkStatus::kDeleted);
}

// A landmark is collapsed when it lies closer than min_range to a pose it is associated from,
// at or after first_step; a pose that does not observe it does not count.
TEST(CollapsedLandmarks, OnlyNearAPoseThatObservesIt) {
  const std::vector<Pose> poses = {Pose(0.0, 0.0, 0.0), Pose(1.0, 0.0, 0.0), Pose(2.0, 0.0, 0.0)};
  const std::vector<Landmark> landmarks = {Landmark(1.5, 0.0), Landmark(2.2, 0.0),
                                           Landmark(0.1, 0.3), Landmark(20.0, 5.0)};
  // Step 0 sees landmark 2 (0.32 m away), step 1 sees 0 (0.5 m) and 3, step 2 sees 3 only
  // (landmark 1 is 0.2 m from pose 2 but never associated from it).
  const Association a = {{2}, {0, 3, kUnassociated}, {3}};
  EXPECT_EQ(CollapsedLandmarks(a, poses, landmarks, 0, 1.0), (std::vector<int>{0, 2}));
  EXPECT_EQ(CollapsedLandmarks(a, poses, landmarks, 1, 1.0), (std::vector<int>{0}));
  EXPECT_EQ(CollapsedLandmarks(a, poses, landmarks, 0, 0.4), (std::vector<int>{2}));
  EXPECT_TRUE(CollapsedLandmarks(a, poses, landmarks, 3, 1.0).empty());
}

/// The circle scenario without noise and with every landmark in view detected.
datasets::Scenario NoiseFreeCircle() {
  testing::CircleScenarioOptions o;
  o.noise = false;
  o.detection_probability = 1.0;
  return testing::MakeCircleScenario(o);
}

/// The generator's labels as an association, clutter unassociated.
Association TrueAssociation(const datasets::Scenario& s) {
  Association a;
  for (const auto& step : s.steps) {
    std::vector<int> labels;
    for (int l : step.origin) labels.push_back(l >= 0 ? l : kUnassociated);
    a.push_back(std::move(labels));
  }
  return a;
}

// One landmark collapsed onto a pose that observes it (0.1 nm away: a Jacobian of ~1e12 against
// ~1e4 for the rest) makes ceres::Covariance fail for the whole graph; with its measurements
// left out, as the incremental own association does when the covariance fails, the marginals
// are computed again.
TEST(CollapsedLandmarks, BreakTheGateMarginalsUntilTheirMeasurementsAreLeftOut) {
  const datasets::Scenario s = NoiseFreeCircle();
  const Association a = TrueAssociation(s);
  const std::vector<OdometryIncrement> inc = ScenarioOdometry(s, {});
  const OdometrySpec odometry{&inc, {}, true};
  std::vector<Pose> poses = s.truth.poses;
  std::vector<Landmark> landmarks = s.truth.landmarks;
  const std::size_t k = a.size() - 1;
  ASSERT_FALSE(a[k].empty());
  const int collapsed = a[k][0];
  ASSERT_NE(collapsed, kUnassociated);
  std::vector<int> in_view;
  for (int l : a[k]) {
    if (l != kUnassociated && l != collapsed) in_view.push_back(l);
  }
  Mat3 px;
  std::vector<Mat2> covs;
  {
    FactorGraph graph(s, odometry, a, nullptr, &poses, &landmarks);
    ASSERT_TRUE(graph.NewestCovariances(in_view, &px, &covs));
  }
  landmarks[static_cast<std::size_t>(collapsed)] = poses[k].head<2>() + Vec2(1e-10, 0.0);
  EXPECT_EQ(CollapsedLandmarks(a, poses, landmarks, 0, 0.8), (std::vector<int>{collapsed}));
  {
    FactorGraph graph(s, odometry, a, nullptr, &poses, &landmarks);
    EXPECT_FALSE(graph.NewestCovariances(in_view, &px, &covs));
  }
  Association pruned = a;
  for (auto& step : pruned) {
    for (int& l : step) {
      if (l == collapsed) l = kUnassociated;
    }
  }
  FactorGraph graph(s, odometry, pruned, nullptr, &poses, &landmarks);
  ASSERT_TRUE(graph.NewestCovariances(in_view, &px, &covs));
  EXPECT_GT(px.determinant(), 0.0);
  EXPECT_EQ(covs.size(), in_view.size());
}

/// The cross-covariances of the landmarks in view with the newest pose: requested alongside, the
/// marginals are unchanged, and each joint covariance [Px C^T; C Pm] is positive definite with a
/// non-zero C (the landmarks are seen from that pose).
TEST(NewestCovariances, PoseCrossCovariances) {
  const datasets::Scenario s = NoiseFreeCircle();
  const Association a = TrueAssociation(s);
  const std::vector<OdometryIncrement> inc = ScenarioOdometry(s, {});
  const OdometrySpec odometry{&inc, {}, true};
  std::vector<Pose> poses = s.truth.poses;
  std::vector<Landmark> landmarks = s.truth.landmarks;
  std::vector<int> in_view;
  for (int l : a.back()) {
    if (l != kUnassociated) in_view.push_back(l);
  }
  ASSERT_FALSE(in_view.empty());
  FactorGraph graph(s, odometry, a, nullptr, &poses, &landmarks);
  Mat3 px;
  std::vector<Mat2> covs;
  ASSERT_TRUE(graph.NewestCovariances(in_view, &px, &covs));
  Mat3 px2;
  std::vector<Mat2> covs2;
  std::vector<Eigen::Matrix<double, 2, 3>> cross;
  ASSERT_TRUE(graph.NewestCovariances(in_view, &px2, &covs2, &cross));
  ASSERT_EQ(cross.size(), in_view.size());
  EXPECT_LT((px2 - px).norm(), 1e-9 * px.norm());
  for (std::size_t n = 0; n < in_view.size(); ++n) {
    EXPECT_LT((covs2[n] - covs[n]).norm(), 1e-9 * covs[n].norm());
    EXPECT_GT(cross[n].norm(), 0.0);
    Eigen::Matrix<double, 5, 5> joint;
    joint << px, cross[n].transpose(), cross[n], covs[n];
    using Solver = Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 5, 5>>;
    EXPECT_GT(Solver(joint).eigenvalues().minCoeff(), 0.0);
  }
}

}  // namespace
}  // namespace phdslam::reference
