#include "reference/ceres/outlier_screening.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <utility>
#include <vector>

#include "reference/ceres/batch_smoother.h"
#include "reference/ceres/test_scenario.h"
#include "src/core/angles.h"

namespace phdslam::reference {
namespace {

using testing::CircleScenarioOptions;
using testing::MakeCircleScenario;
using testing::PositionRmse;

/// The known association of `s` as smoother labels (clutter = kUnassociated).
Association KnownLabels(const datasets::Scenario& s) {
  Association a;
  for (const auto& step : s.steps) {
    std::vector<int> labels;
    for (int o : step.origin) labels.push_back(o >= 0 ? o : kUnassociated);
    a.push_back(std::move(labels));
  }
  return a;
}

/// Turns the first measurement of each of `steps` into a misread one: the bearing of a detection
/// behind the sensor (off by pi), as a misread barcode on UTIAS MRCLAM gives.
void Misread(const std::vector<std::size_t>& steps, datasets::Scenario* s) {
  for (std::size_t k : steps) {
    ASSERT_FALSE(s->steps[k].data.measurements.empty()) << "step " << k;
    Measurement& z = s->steps[k].data.measurements[0];
    z(1) = WrapAngle(z(1) + std::numbers::pi);
  }
}

TEST(MeasurementChi2, IsTheWhitenedSquaredResidualWithTheBearingWrapped) {
  const Pose x(1.0, 2.0, 0.5);
  const Landmark m(4.0, 6.0);  // range 5, bearing atan2(4, 3) - 0.5
  const Mat2 r = Vec2(0.25, 0.01).asDiagonal();
  const double bearing = std::atan2(4.0, 3.0) - 0.5;
  EXPECT_NEAR(MeasurementChi2(x, m, Measurement(5.0, bearing), r), 0.0, 1e-20);
  EXPECT_NEAR(MeasurementChi2(x, m, Measurement(6.0, bearing + 0.2), r), 1.0 / 0.25 + 0.04 / 0.01,
              1e-12);
  // A bearing one turn away is the same bearing.
  EXPECT_NEAR(MeasurementChi2(x, m, Measurement(5.0, bearing + 2.0 * std::numbers::pi), r), 0.0,
              1e-18);
  EXPECT_TRUE(std::isinf(MeasurementChi2(x, x.head<2>(), Measurement(1.0, 0.0), r)));
}

TEST(DropOutlierMeasurements, DropsExactlyTheMisreadDetections) {
  datasets::Scenario s = MakeCircleScenario(CircleScenarioOptions{});
  Misread({10, 40, 70}, &s);
  Association a = KnownLabels(s);
  const Association before = a;
  EXPECT_EQ(DropOutlierMeasurements(s, s.truth.poses, s.truth.landmarks, 1000.0, &a), 3);
  for (std::size_t k = 0; k < a.size(); ++k) {
    for (std::size_t j = 0; j < a[k].size(); ++j) {
      const bool misread = j == 0 && (k == 10 || k == 40 || k == 70);
      EXPECT_EQ(a[k][j], misread ? kUnassociated : before[k][j]) << "step " << k << " z " << j;
    }
  }
}

TEST(DropOutlierMeasurements, KeepsALandmarksLastMeasurement) {
  datasets::Scenario s = MakeCircleScenario(CircleScenarioOptions{});
  Association a = KnownLabels(s);
  // Landmark 0 keeps a single, misread, measurement.
  std::size_t kept_step = 0;
  bool kept = false;
  for (std::size_t k = 0; k < a.size(); ++k) {
    for (int& l : a[k]) {
      if (l != 0) continue;
      if (kept) l = kUnassociated;
      kept_step = kept ? kept_step : k;
      kept = true;
    }
  }
  ASSERT_TRUE(kept);
  std::size_t j0 = 0;
  while (a[kept_step][j0] != 0) ++j0;
  Measurement& z = s.steps[kept_step].data.measurements[j0];
  z(1) = WrapAngle(z(1) + std::numbers::pi);
  EXPECT_EQ(DropOutlierMeasurements(s, s.truth.poses, s.truth.landmarks, 1000.0, &a), 0);
  EXPECT_EQ(a[kept_step][j0], 0);
}

TEST(DropOutlierMeasurements, RejectsBadInput) {
  const datasets::Scenario s = MakeCircleScenario(CircleScenarioOptions{});
  Association a = KnownLabels(s);
  EXPECT_THROW(DropOutlierMeasurements(s, s.truth.poses, s.truth.landmarks, 0.0, &a),
               std::invalid_argument);
  EXPECT_THROW(DropOutlierMeasurements(s, s.truth.poses, s.truth.landmarks, std::nan(""), &a),
               std::invalid_argument);
  a[5].push_back(0);  // one label more than measurements
  EXPECT_THROW(DropOutlierMeasurements(s, s.truth.poses, s.truth.landmarks, 1000.0, &a),
               std::invalid_argument);
}

// With misread detections in the known association, the screened smoother ends where the smoother
// on the association without them ends; the unscreened one (known_outlier_chi2 = 0, squared loss
// throughout) is pulled away.
class KnownAssociationWithMisreads : public ::testing::TestWithParam<SmootherInitialisation> {};

TEST_P(KnownAssociationWithMisreads, AreScreenedOut) {
  CircleScenarioOptions c;
  c.steps = 120;
  datasets::Scenario s = MakeCircleScenario(c);
  const std::vector<std::size_t> misread_steps = {30, 31, 32, 33};
  Misread(misread_steps, &s);
  datasets::Scenario clean = s;
  for (std::size_t k : misread_steps) clean.steps[k].origin[0] = datasets::kClutter;

  SmootherOptions o;
  o.compute_covariances = false;
  o.function_tolerance = 1e-14;
  o.initialisation = GetParam();
  BatchSmoother reference_smoother(o);
  const datasets::BatchResult expected = reference_smoother.Solve(clean);
  BatchSmoother screened(o);
  const datasets::BatchResult r = screened.Solve(s);
  EXPECT_EQ(screened.report().outliers_dropped, 4);
  for (std::size_t k : misread_steps) EXPECT_EQ(screened.association()[k][0], kUnassociated);
  ASSERT_EQ(r.poses.size(), expected.poses.size());
  for (std::size_t k = 0; k < r.poses.size(); ++k) {
    EXPECT_LT((r.poses[k] - expected.poses[k]).norm(), 1e-4) << "step " << k;
  }

  o.known_outlier_chi2 = 0.0;
  BatchSmoother unscreened(o);
  const datasets::BatchResult u = unscreened.Solve(s);
  EXPECT_EQ(unscreened.report().outliers_dropped, 0);
  const double rmse_screened = PositionRmse(s, r.poses);
  const double rmse_unscreened = PositionRmse(s, u.poses);
  EXPECT_GT(rmse_unscreened, 2.0 * rmse_screened)
      << "screened " << rmse_screened << " m, unscreened " << rmse_unscreened << " m";
}

INSTANTIATE_TEST_SUITE_P(BatchSmoother, KnownAssociationWithMisreads,
                         ::testing::Values(SmootherInitialisation::kIncremental,
                                           SmootherInitialisation::kBatch));

}  // namespace
}  // namespace phdslam::reference
