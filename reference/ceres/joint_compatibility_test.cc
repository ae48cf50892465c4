#include "reference/ceres/joint_compatibility.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "reference/ceres/scan_association.h"
#include "src/models/range_bearing_model.h"

namespace phdslam::reference {
namespace {

// Range 5 cm, bearing 0.01 rad.
Mat2 SensorNoise() { return Vec2(0.05 * 0.05, 0.01 * 0.01).asDiagonal(); }

// The pose estimate is 0.6 m off sideways (inside its 0.5 m standard deviation's gate): two
// landmarks 1 m apart ahead, both detected from the true pose, and a clutter point where the
// estimate predicts the first. Seen from the estimate, the first landmark's detection is nearer
// the second landmark's prediction and the clutter point sits on the first's.
struct CloseLandmarksInClutter {
  Pose estimate{0.0, 0.0, 0.0};
  Pose truth{0.0, 0.6, 0.0};
  Mat3 pose_cov = Vec3(0.01, 0.25, 1e-6).asDiagonal();
  std::vector<MapLandmark> map{{Landmark(5.0, 0.5), 1e-4 * Mat2::Identity()},
                               {Landmark(5.0, -0.5), 1e-4 * Mat2::Identity()}};
  std::vector<Measurement> scan{models::PredictMeasurement(truth, map[0].mean),
                                models::PredictMeasurement(truth, map[1].mean),
                                models::PredictMeasurement(estimate, map[0].mean)};
};

ScanAssociation Associate(const CloseLandmarksInClutter& s, ScanAssignment assignment) {
  ScanAssociationOptions o;
  o.assignment = assignment;
  return AssociateScan(s.estimate, s.pose_cov, s.map, s.scan, SensorNoise(), o);
}

TEST(JointCompatibility, TwoCloseLandmarksInClutterGetTheJointlyCompatiblePairs) {
  const CloseLandmarksInClutter s;
  const ScanAssociation nn = Associate(s, ScanAssignment::kNearestNeighbour);
  // The first landmark's detection and the clutter point are inside both gates, the second
  // landmark's only in its own; nearest neighbour takes the clutter point for the first landmark
  // and the first landmark's detection for the second, and leaves the second's unassociated.
  EXPECT_EQ(nn.gated, (std::vector<int>{2, 1, 2}));
  EXPECT_EQ(nn.landmark, (std::vector<int>{1, kUnassociated, 0}));

  const ScanAssociation jcbb = Associate(s, ScanAssignment::kJointCompatibility);
  EXPECT_EQ(jcbb.landmark, (std::vector<int>{0, 1, kUnassociated}));
  EXPECT_EQ(jcbb.gated, nn.gated);
  EXPECT_GT(jcbb.mahalanobis2[0], 0.0);
  EXPECT_LT(jcbb.mahalanobis2[0], 13.8);
  EXPECT_EQ(jcbb.mahalanobis2[2], 0.0);
}

TEST(JointCompatibility, PairsThatNeedDifferentPoseErrorsAreNotTakenTogether) {
  // The two detections were taken 0.6 m to one side and 0.9 m to the other: seen from the
  // estimate, the second is nearest the first landmark and the first nearest the second, each
  // inside its gate, but the two pairs need pose errors 0.5 m apart. Nearest neighbour takes both;
  // joint compatibility keeps the nearer pair only.
  CloseLandmarksInClutter s;
  s.scan = {models::PredictMeasurement(Pose(0.0, 0.6, 0.0), s.map[0].mean),
            models::PredictMeasurement(Pose(0.0, -0.9, 0.0), s.map[1].mean)};
  EXPECT_EQ(Associate(s, ScanAssignment::kNearestNeighbour).landmark, (std::vector<int>{1, 0}));
  EXPECT_EQ(Associate(s, ScanAssignment::kJointCompatibility).landmark,
            (std::vector<int>{kUnassociated, 0}));
}

TEST(JointCompatibility, AtTheNodeLimitTheBestCompleteAssignmentFoundIsReturned) {
  const CloseLandmarksInClutter s;
  ScanAssociationOptions o;
  o.assignment = ScanAssignment::kJointCompatibility;
  o.jcbb_max_nodes = 1;  // only the first pair of the first detection is tested
  const ScanAssociation a = AssociateScan(s.estimate, s.pose_cov, s.map, s.scan, SensorNoise(), o);
  EXPECT_EQ(a.landmark, (std::vector<int>{1, kUnassociated, kUnassociated}));
  o.jcbb_max_nodes = 0;
  EXPECT_THROW(AssociateScan(s.estimate, s.pose_cov, s.map, s.scan, SensorNoise(), o),
               std::invalid_argument);
}

TEST(JointCompatibility, TheLikelihoodObjectiveWeighsEachPairAgainstTheNullIntensity) {
  const CloseLandmarksInClutter s;
  ScanAssociationOptions o;
  o.assignment = ScanAssignment::kJointCompatibility;
  // A low null intensity: the two jointly compatible pairs are likelier than clutter.
  o.jcbb_null_intensity = 1e-3;
  EXPECT_EQ(AssociateScan(s.estimate, s.pose_cov, s.map, s.scan, SensorNoise(), o).landmark,
            (std::vector<int>{0, 1, kUnassociated}));
  // A null intensity above the pairs' likelihood (its density is at most 1 / (2 pi sqrt det S),
  // about 16 per m per rad under this pose covariance): every measurement is left out.
  o.jcbb_null_intensity = 1e3;
  EXPECT_EQ(AssociateScan(s.estimate, s.pose_cov, s.map, s.scan, SensorNoise(), o).landmark,
            (std::vector<int>{kUnassociated, kUnassociated, kUnassociated}));
  o.jcbb_null_intensity = -1.0;
  EXPECT_THROW(AssociateScan(s.estimate, s.pose_cov, s.map, s.scan, SensorNoise(), o),
               std::invalid_argument);
}

TEST(JointCompatibility, ChiSquareQuantilesOfEvenDegreesOfFreedom) {
  // 2 dof: exp(-x/2) = tail exactly; 4 and 10 dof at 0.999 against tables.
  EXPECT_NEAR(ChiSquareQuantileEvenDof(2, std::exp(-0.5 * 13.8)), 13.8, 1e-9);
  EXPECT_NEAR(ChiSquareQuantileEvenDof(4, 0.001), 18.4668, 1e-3);
  EXPECT_NEAR(ChiSquareQuantileEvenDof(10, 0.001), 29.5883, 1e-3);
  EXPECT_THROW(ChiSquareQuantileEvenDof(3, 0.001), std::invalid_argument);
  EXPECT_THROW(ChiSquareQuantileEvenDof(2, 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace phdslam::reference
