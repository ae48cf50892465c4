#include "validation/metrics/gps_position_error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <vector>

#include "datasets/data_dir.h"
#include "datasets/test_data_sets.h"
#include "datasets/victoria_park.h"
#include "src/models/car_motion_model.h"

namespace phdslam::validation {
namespace {

using datasets::GpsFix;

GpsFix Fix(double t, double x, double y) {
  GpsFix f;
  f.t = t;
  f.position = Vec2(x, y);
  return f;
}

Pose At(double x, double y) { return Pose(x, y, 0.7); }  // the heading plays no part

TEST(GpsPositionErrorTest, NearestFixWithinTheWindow) {
  const std::vector<GpsFix> gps = {Fix(0.0, 0.0, 0.0), Fix(0.2, 10.0, 0.0), Fix(0.4, 20.0, 0.0),
                                   Fix(3.0, 50.0, 50.0)};
  const std::vector<double> times = {-1.0, 0.01, 0.1, 0.225, 0.226, 0.39, 2.99, 5.0};
  const std::vector<Pose> est = {At(0, 0),  At(3, 4),   At(5, 0),   At(10, -2),
                                 At(10, 0), At(14, -8), At(50, 49), At(50, 50)};
  const GpsErrors e = ComputeGpsErrors(times, est, gps);
  ASSERT_EQ(e.error_m.size(), times.size());
  EXPECT_TRUE(std::isnan(e.error_m[0]));  // 1 s before the first fix
  EXPECT_DOUBLE_EQ(e.error_m[1], 5.0);    // fix at 0.0 s, 10 ms away: ||(3, 4)||
  EXPECT_TRUE(std::isnan(e.error_m[2]));  // 100 ms from both neighbours
  EXPECT_DOUBLE_EQ(e.error_m[3], 2.0);    // fix at 0.2 s exactly 25 ms away: included
  EXPECT_TRUE(std::isnan(e.error_m[4]));  // 26 ms away
  EXPECT_DOUBLE_EQ(e.error_m[5], 10.0);   // fix at 0.4 s, 10 ms away: ||(6, 8)||
  EXPECT_DOUBLE_EQ(e.error_m[6], 1.0);    // fix at 3.0 s, after a 2.6 s gap
  EXPECT_TRUE(std::isnan(e.error_m[7]));  // 2 s after the last fix
  EXPECT_EQ(e.matched, 4u);

  // A wider window matches step 2 to the earlier of two equidistant fixes (0.0 s), and step 4.
  const GpsErrors wide = ComputeGpsErrors(times, est, gps, 0.15);
  EXPECT_DOUBLE_EQ(wide.error_m[2], 5.0);
  EXPECT_DOUBLE_EQ(wide.error_m[4], 0.0);
  EXPECT_EQ(wide.matched, 6u);
}

TEST(GpsPositionErrorTest, EmptyInputsAndBadArguments) {
  const GpsErrors none = ComputeGpsErrors({1.0, 2.0}, {At(0, 0), At(1, 1)}, {});
  EXPECT_EQ(none.matched, 0u);
  ASSERT_EQ(none.error_m.size(), 2u);
  EXPECT_TRUE(std::isnan(none.error_m[0]) && std::isnan(none.error_m[1]));
  EXPECT_EQ(ComputeGpsErrors({}, {}, {Fix(0, 0, 0)}).error_m.size(), 0u);

  EXPECT_THROW(ComputeGpsErrors({1.0}, {}, {Fix(0, 0, 0)}), std::invalid_argument);
  EXPECT_THROW(ComputeGpsErrors({1.0}, {At(0, 0)}, {Fix(1, 0, 0), Fix(0, 0, 0)}),
               std::invalid_argument);
  EXPECT_THROW(ComputeGpsErrors({1.0}, {At(0, 0)}, {Fix(0, 0, 0), Fix(0, 1, 1)}),
               std::invalid_argument);
  EXPECT_THROW(ComputeGpsErrors({1.0}, {At(0, 0)}, {Fix(0, 0, 0)}, -0.1), std::invalid_argument);
}

TEST(GpsOutlierTest, DropsIsolatedSpikesOnly) {
  const std::vector<GpsFix> gps = {
      Fix(0.0, 0.0, 0.0),  // end of the track: kept
      Fix(0.2, 0.5, 0.0),
      Fix(0.4, 9.0, 0.0),  // spike: 8.5 m and 8 m from its neighbours: dropped
      Fix(0.6, 1.0, 0.0),
      Fix(0.8, 1.2, 0.0),
      Fix(1.0, 8.0, 0.0),  // step change: 6.8 m from the previous fix but 0.3 m from the next
      Fix(1.2, 8.3, 0.0),
      Fix(4.0, 30.0, 0.0),  // after a 2.8 s gap: nothing to compare with on the left, kept
      Fix(4.2, 8.5, 0.0),
      Fix(4.4, 40.0, 0.0),  // last fix: kept
  };
  const std::vector<GpsFix> kept = RemoveGpsOutliers(gps, 5.0);
  std::vector<double> kept_times;
  for (const auto& f : kept) kept_times.push_back(f.t);
  // 4.2 s is 21.5 m and 31.5 m from its neighbours, both within 2 s: a spike as well.
  EXPECT_EQ(kept_times, (std::vector<double>{0.0, 0.2, 0.6, 0.8, 1.0, 1.2, 4.0, 4.4}));

  // With a 3 s neighbour window the fix at 1.2 s now has both neighbours, but it is 0.3 m from
  // the left one, so it stays; the fix at 4.0 s is 21.7 m and 21.5 m away: dropped.
  const std::vector<GpsFix> kept3 = RemoveGpsOutliers(gps, 5.0, 3.0);
  std::vector<double> kept3_times;
  for (const auto& f : kept3) kept3_times.push_back(f.t);
  EXPECT_EQ(kept3_times, (std::vector<double>{0.0, 0.2, 0.6, 0.8, 1.0, 1.2, 4.4}));

  EXPECT_THROW(RemoveGpsOutliers(gps, 0.0), std::invalid_argument);
  EXPECT_THROW(RemoveGpsOutliers(gps, 1.0, -1.0), std::invalid_argument);
}

// Dead reckoning over the Victoria Park steps, scored against GPS. The match count is fixed by the
// time stamps alone: 1,068 of the 7,230 scans have a GPS fix within 25 ms (counted independently
// on the integer millisecond clocks).
TEST(GpsPositionErrorRealDataTest, DeadReckoningOnVictoriaPark) {
  const datasets::testing::DataSetLookup found =
      datasets::testing::FindDataSetFiles("victoria-park");
  PHDSLAM_SKIP_WITHOUT_DATA_SET(found);
  const auto& root = found.dir;
  const datasets::VictoriaParkData data = datasets::LoadVictoriaParkData(*root);
  datasets::VictoriaParkOptions options;
  options.clutter_rate = 0.0;
  const datasets::Scenario s = datasets::MakeVictoriaParkScenario(data, 1, options);

  const models::CarMotionModel model(s.car);
  Pose x = s.initial_pose;
  std::vector<double> times;
  std::vector<Pose> poses;
  for (std::size_t k = 0; k < s.steps.size(); ++k) {
    const auto& step = s.steps[k].data;
    for (std::size_t i = 0; i + 1 < step.times.size(); ++i) {
      x = model.Predict(x, step.controls[i], step.times[i + 1] - step.times[i]);
    }
    times.push_back(s.StepTime(k));
    poses.push_back(x);
  }
  const GpsErrors e = ComputeGpsErrors(times, poses, s.truth.gps);
  EXPECT_EQ(e.matched, 1068u);

  double sum_sq = 0.0;
  double first_minute_max = 0.0;
  for (std::size_t k = 0; k < times.size(); ++k) {
    if (std::isnan(e.error_m[k])) continue;
    ASSERT_TRUE(std::isfinite(e.error_m[k]));
    sum_sq += e.error_m[k] * e.error_m[k];
    if (times[k] < 60.0) first_minute_max = std::max(first_minute_max, e.error_m[k]);
  }
  const double rmse = std::sqrt(sum_sq / static_cast<double>(e.matched));
  const std::size_t dropped = s.truth.gps.size() - RemoveGpsOutliers(s.truth.gps, 5.0).size();
  std::printf(
      "[ info ] dead reckoning vs GPS: %zu matched steps, RMSE %.2f m, max %.2f m in the "
      "first minute; %zu of %zu GPS fixes are isolated spikes > 5 m\n",
      e.matched, rmse, first_minute_max, dropped, s.truth.gps.size());
  EXPECT_TRUE(std::isfinite(rmse));
}

}  // namespace
}  // namespace phdslam::validation
