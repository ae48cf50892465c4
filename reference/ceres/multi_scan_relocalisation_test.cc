#include "reference/ceres/multi_scan_relocalisation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "reference/ceres/landmark_association.h"
#include "reference/ceres/scan_association.h"
#include "src/models/range_bearing_model.h"

namespace phdslam::reference {
namespace {

constexpr double kHalfPi = std::numbers::pi / 2.0;

Mat2 SensorNoise() { return Vec2(0.05 * 0.05, 0.01 * 0.01).asDiagonal(); }

/// Cluster A (indices 0-2, where dead reckoning puts the robot) and cluster B (3-6, where it
/// is): B's first two landmarks are laid out as A's first two, 1.5 m apart, 10 m further east.
std::vector<Landmark> TwoClusters() {
  return {{0.0, 0.0},  {1.5, 0.0},  {0.0, -2.0},                // A
          {10.0, 0.0}, {11.5, 0.0}, {10.0, 2.0}, {12.0, 2.5}};  // B
}

/// After a gap the robot is at (10.5, -4 + 0.5 k) heading north, dead reckoning says 10 m
/// west of that with the heading right; the pose's position std is 6 m.
Pose TruePose(int k) { return {10.5, -4.0 + 0.5 * k, kHalfPi}; }
Pose DeadReckoned(int k) { return TruePose(k) - Pose(10.0, 0.0, 0.0); }
Mat3 WidePoseCov() { return Vec3(36.0, 36.0, 0.09).asDiagonal(); }

/// Scan k: B's landmarks in view (the first scan only the pair that A repeats), with a small,
/// fixed range and bearing error.
std::vector<Measurement> Scan(int k, const std::vector<Landmark>& map) {
  std::vector<Measurement> out;
  const int last = k == 0 ? 4 : 6;
  for (int i = 3; i <= last; ++i) {
    Measurement z = models::PredictMeasurement(TruePose(k), map[static_cast<std::size_t>(i)]);
    z += Vec2(0.02 * ((i + k) % 3 - 1), 0.003 * ((i * k) % 3 - 1));
    out.push_back(z);
  }
  return out;
}

/// The detections of scans [0, scans) as points from the dead-reckoned poses.
std::vector<Landmark> Points(int scans, const std::vector<Landmark>& map) {
  std::vector<Landmark> out;
  for (int k = 0; k < scans; ++k) {
    for (const Measurement& z : Scan(k, map)) {
      out.push_back(models::InverseMeasurement(DeadReckoned(k), z));
    }
  }
  return out;
}

// The first scan after the gap sees two landmarks of B. Nearest neighbour on the wide pose gives
// them to A, the cluster dead reckoning points at; matched alone, the scan is refused (A and B
// explain it equally); with the next four scans, which also see B's other landmarks, the match
// is B with the 10 m correction.
TEST(MultiScanRelocalisation, PicksTheRightClusterWhereOneScanPicksTheWrongOne) {
  const std::vector<Landmark> map = TwoClusters();
  std::vector<MapLandmark> view;
  for (const Landmark& m : map) view.push_back({m, 0.01 * Mat2::Identity()});
  const ScanAssociation single =
      AssociateScan(DeadReckoned(0), WidePoseCov(), view, Scan(0, map), SensorNoise(), {});
  EXPECT_EQ(single.landmark, (std::vector<int>{0, 1}));  // the wrong cluster

  const RelocalisationMatch one =
      MatchPointsToMap(Points(1, map), map, DeadReckoned(0), WidePoseCov(), {});
  EXPECT_FALSE(one.found);
  EXPECT_EQ(one.best_inliers, 2);
  EXPECT_EQ(one.rival_inliers, 2);
  EXPECT_EQ(one.landmark, (std::vector<int>{kUnassociated, kUnassociated}));
  EXPECT_FALSE(one.ambiguous);  // two inliers are too few to call the map ambiguous

  const RelocalisationMatch five =
      MatchPointsToMap(Points(5, map), map, DeadReckoned(4), WidePoseCov(), {});
  ASSERT_TRUE(five.found);
  EXPECT_FALSE(five.ambiguous);
  EXPECT_EQ(five.best_inliers, 18);   // 2 + 4 x 4 detections
  EXPECT_EQ(five.rival_inliers, 10);  // A explains the repeated pair of every scan
  std::vector<int> expected{3, 4};
  for (int k = 1; k < 5; ++k) {
    for (int i = 3; i <= 6; ++i) expected.push_back(i);
  }
  EXPECT_EQ(five.landmark, expected);
  EXPECT_NEAR(five.correction.translation.x(), 10.0, 0.05);
  EXPECT_NEAR(five.correction.translation.y(), 0.0, 0.05);
  EXPECT_NEAR(five.correction.rotation, 0.0, 0.01);
  const Pose corrected = ApplyCorrection(five.correction, DeadReckoned(4));
  EXPECT_LT((corrected - TruePose(4)).head<2>().norm(), 0.05);
}

// Two identical clusters 10 m apart: however many scans, the match is refused.
TEST(MultiScanRelocalisation, RefusesBetweenIdenticalClusters) {
  // A is B shifted 10 m west, landmark for landmark (indices 3-6 are B, as Scan expects).
  const std::vector<Landmark> map{{0.0, 0.0},  {1.5, 0.0},  {0.0, 2.0},  {10.0, 0.0},
                                  {11.5, 0.0}, {10.0, 2.0}, {12.0, 2.5}, {2.0, 2.5}};
  const RelocalisationMatch m =
      MatchPointsToMap(Points(5, map), map, DeadReckoned(4), WidePoseCov(), {});
  EXPECT_FALSE(m.found);
  EXPECT_EQ(m.best_inliers, m.rival_inliers);
  EXPECT_GE(m.best_inliers, 3);
  EXPECT_TRUE(m.ambiguous);  // what incremental_relocalisation_leave_ambiguous acts on
}

TEST(MultiScanRelocalisation, RejectsNonsenseOptions) {
  const std::vector<Landmark> map = TwoClusters();
  RelocalisationOptions bad;
  bad.inlier_distance = 0.0;
  EXPECT_THROW(MatchPointsToMap({}, map, Pose::Zero(), Mat3::Identity(), bad),
               std::invalid_argument);
  bad = {};
  bad.margin = 0;
  EXPECT_THROW(MatchPointsToMap({}, map, Pose::Zero(), Mat3::Identity(), bad),
               std::invalid_argument);
}

}  // namespace
}  // namespace phdslam::reference
