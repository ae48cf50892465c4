#include "validation/runner/evaluation/map_ospa_trace.h"

#include <gtest/gtest.h>

#include <cmath>

namespace phdslam::validation {
namespace {

// Two landmarks; landmark 0 detected at step 0, landmark 1 first at step 2.
datasets::Scenario TwoLandmarks() {
  datasets::Scenario s;
  s.truth.landmarks = {Landmark(0.0, 0.0), Landmark(10.0, 0.0)};
  s.steps.resize(3);
  s.steps[0].data.measurements = {Measurement(1.0, 0.0), Measurement(2.0, 0.1)};
  s.steps[0].origin = {0, datasets::kClutter};
  s.steps[1].data.measurements = {};
  s.steps[2].data.measurements = {Measurement(1.0, 0.0), Measurement(3.0, 0.0)};
  s.steps[2].origin = {1, 0};
  return s;
}

TEST(MapOspaTrace, ComparesWithTheLandmarksDetectedSoFar) {
  const datasets::Scenario s = TwoLandmarks();
  RunRecord r;
  r.step_maps = {{Landmark(1.0, 0.0)},                        // d = 1 to landmark 0
                 {Landmark(1.0, 0.0), Landmark(50.0, 0.0)},   // one false: (1 + 5) / 2
                 {Landmark(0.0, 2.0), Landmark(10.0, 8.0)}};  // 2, then cut at 5: (2 + 5) / 2
  const std::vector<double> trace = MapOspaTrace(r, s);
  ASSERT_EQ(trace.size(), 3u);
  EXPECT_NEAR(trace[0], 1.0, 1e-12);
  EXPECT_NEAR(trace[1], 3.0, 1e-12);
  EXPECT_NEAR(trace[2], 3.5, 1e-12);
}

TEST(MapOspaTrace, TakesTheCutoff) {
  const datasets::Scenario s = TwoLandmarks();
  RunRecord r;
  r.step_maps = {{Landmark(0.3, 0.0)},                        // d = 0.3 < c
                 {Landmark(1.0, 0.0), Landmark(50.0, 0.0)},   // cut at 0.5, one false: 0.5
                 {Landmark(0.0, 0.2), Landmark(10.0, 8.0)}};  // 0.2, then cut: (0.2 + 0.5) / 2
  const std::vector<double> trace = MapOspaTrace(r, s, 0.5);
  ASSERT_EQ(trace.size(), 3u);
  EXPECT_NEAR(trace[0], 0.3, 1e-12);
  EXPECT_NEAR(trace[1], 0.5, 1e-12);
  EXPECT_NEAR(trace[2], 0.35, 1e-12);
  EXPECT_NEAR(MapOspaTrace(r, s)[2], (0.2 + 5.0) / 2.0, 1e-12);  // the default c = 5 m
}

TEST(MapOspaTrace, EmptyWithoutRecordedMapsOrTrueMap) {
  datasets::Scenario s = TwoLandmarks();
  RunRecord r;
  EXPECT_TRUE(MapOspaTrace(r, s).empty());
  r.step_maps.resize(3);
  s.truth.landmarks.clear();
  EXPECT_TRUE(MapOspaTrace(r, s).empty());
}

}  // namespace
}  // namespace phdslam::validation
