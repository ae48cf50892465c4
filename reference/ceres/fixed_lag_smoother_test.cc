#include "reference/ceres/fixed_lag_smoother.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
#include <memory>
#include <string>

#include "reference/ceres/filter_association.h"
#include "reference/ceres/test_scenario.h"
#include "reference/ceres/window_params_json.h"
#include "src/testing/jacobian_check.h"

namespace phdslam::reference {
namespace {

using testing::CircleScenarioOptions;
using testing::MakeCircleScenario;
using testing::PositionRmse;

std::vector<std::vector<int>> Origins(const datasets::Scenario& s) {
  std::vector<std::vector<int>> o;
  for (const datasets::ScenarioStep& step : s.steps) o.push_back(step.origin);
  return o;
}

struct WindowRun {
  std::vector<Pose> filtered;  ///< the newest pose after each step
  std::vector<Pose> window;    ///< the window after the last step
  filters::MapEstimate map;
  WindowReport report;
};

WindowRun RunWindow(const datasets::Scenario& s, const WindowParams& p) {
  FixedLagSmoother smoother(s.PublicContext(), p,
                            p.known_association ? Origins(s) : std::vector<std::vector<int>>{},
                            s.steps.size());
  WindowRun r;
  for (const datasets::ScenarioStep& step : s.steps)
    r.filtered.push_back(smoother.Step(step.data).pose);
  r.window = smoother.WindowPoses();
  r.map = smoother.Map();
  r.report = smoother.report();
  return r;
}

WindowParams Tight(int window_length) {
  WindowParams p;
  p.window_length = window_length;
  p.max_iterations = 100;
  p.function_tolerance = 1e-14;
  return p;
}

TEST(FixedLagSmoother, WindowAsLongAsTheRunIsTheBatchSmoother) {
  CircleScenarioOptions o;
  o.steps = 60;
  const datasets::Scenario s = MakeCircleScenario(o);
  const WindowRun w = RunWindow(s, Tight(60));
  SmootherOptions batch_options;
  batch_options.compute_covariances = false;
  batch_options.function_tolerance = 1e-14;
  BatchSmoother batch(batch_options);
  const datasets::BatchResult b = batch.Solve(s);
  ASSERT_EQ(w.window.size(), b.poses.size());
  EXPECT_EQ(w.report.marginalised_poses, 0);
  EXPECT_EQ(w.report.unconverged_solves, 0);
  for (std::size_t k = 0; k < b.poses.size(); ++k) {
    EXPECT_LT((w.window[k] - b.poses[k]).norm(), 1e-6) << "step " << k;
  }
  ASSERT_EQ(w.map.size(), b.map.size());
  for (std::size_t i = 0; i < b.map.size(); ++i) {
    EXPECT_LT((w.map.means[i] - b.map.means[i]).norm(), 1e-6) << "landmark " << i;
  }
  // The filtered answer of the last step is the smoothed last pose; earlier ones are not.
  EXPECT_LT((w.filtered.back() - b.poses.back()).norm(), 1e-6);
  EXPECT_GT((w.filtered[30] - b.poses[30]).norm(), 1e-4);
}

TEST(FixedLagSmoother, NoiseFreeDataAreRecoveredThroughMarginalisation) {
  for (const bool car : {false, true}) {
    CircleScenarioOptions o;
    o.noise = false;
    o.detection_probability = 1.0;
    if (car) {
      o.motion = datasets::MotionKind::kCar;
      o.sub_intervals = 4;
      o.first_step_propagates = true;
    }
    const datasets::Scenario s = MakeCircleScenario(o);
    const WindowRun w = RunWindow(s, Tight(5));
    EXPECT_EQ(w.report.marginalised_poses, 95) << "car " << car;
    for (std::size_t k = 0; k < w.filtered.size(); ++k) {
      EXPECT_LT((w.filtered[k] - s.truth.poses[k]).norm(), 1e-6) << "car " << car << " step " << k;
    }
    ASSERT_EQ(w.map.size(), 20u);
    for (std::size_t i = 0; i < 20; ++i) {
      EXPECT_LT((w.map.means[i] - s.truth.landmarks[i]).norm(), 1e-6);
      phdslam::testing::ExpectSymmetricPositiveDefinite(w.map.covs[i]);
    }
  }
}

TEST(FixedLagSmoother, MarginalisationKeepsTheNoisyEstimateCloseToTheBatchOne) {
  CircleScenarioOptions o;
  o.steps = 200;
  const datasets::Scenario s = MakeCircleScenario(o);
  BatchSmoother batch(SmootherOptions{});
  const double batch_rmse = PositionRmse(s, batch.Solve(s).poses);
  const WindowRun w = RunWindow(s, WindowParams{});
  const double window_rmse = PositionRmse(s, w.filtered);
  std::cout << "batch " << batch_rmse << " m, window (filtered) " << window_rmse << " m\n";
  // A filtered estimate is no better than the smoothed one, and marginalisation must not
  // break it: within a factor 3 of the batch smoother on this short loop.
  EXPECT_GE(window_rmse, 0.9 * batch_rmse);
  EXPECT_LT(window_rmse, 3.0 * batch_rmse);
  EXPECT_EQ(w.map.size(), 20u);
}

// Position RMSE of the window's map against the batch smoother's (the same labels, in order).
double MapDistance(const filters::MapEstimate& a, const filters::MapEstimate& b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) sum += (a.means[i] - b.means[i]).squaredNorm();
  return std::sqrt(sum / static_cast<double>(a.size()));
}

// On one turn of the circle every landmark leaves the field of view behind the robot and comes
// back at the loop's end. Kept in the window for the whole run (landmark_keep_steps), the
// landmarks are held by the prior with their correlations, and only poses are marginalised: the
// map and the last pose are then the batch smoother's up to the prior's fixed linearisation,
// closer than when a landmark leaves with its marginal Gaussian and re-enters with it.
TEST(FixedLagSmoother, LandmarksKeptInTheWindowGiveTheBatchSmoothersMap) {
  for (const std::uint64_t seed : {1, 2, 3}) {
    CircleScenarioOptions o;
    o.steps = 200;
    o.seed = seed;
    const datasets::Scenario s = MakeCircleScenario(o);
    SmootherOptions batch_options;
    batch_options.association = AssociationMode::kKnown;
    const datasets::BatchResult b = BatchSmoother(batch_options).Solve(s);
    WindowParams p = Tight(5);
    const WindowRun leaving = RunWindow(s, p);
    p.landmark_keep_steps = o.steps;
    const WindowRun kept = RunWindow(s, p);
    ASSERT_EQ(kept.map.size(), b.map.size());
    ASSERT_EQ(leaving.map.size(), b.map.size());
    const double kept_map = MapDistance(kept.map, b.map);
    const double leaving_map = MapDistance(leaving.map, b.map);
    EXPECT_LT(kept_map, 0.02) << "seed " << seed;
    EXPECT_LT(kept_map, leaving_map) << "seed " << seed;
    EXPECT_LT((kept.filtered.back() - b.poses.back()).head<2>().norm(), 0.02) << "seed " << seed;
    EXPECT_EQ(kept.report.marginalised_poses, leaving.report.marginalised_poses);
  }
}

TEST(FixedLagSmoother, OwnAssociationFindsTheLandmarksAmongClutter) {
  CircleScenarioOptions o;
  o.steps = 200;
  o.clutter_rate = 5.0;
  const datasets::Scenario s = MakeCircleScenario(o);
  WindowParams known;
  const double known_rmse = PositionRmse(s, RunWindow(s, known).filtered);
  WindowParams own;
  own.known_association = false;
  const WindowRun w = RunWindow(s, own);
  const double own_rmse = PositionRmse(s, w.filtered);
  std::cout << "known " << known_rmse << " m, own " << own_rmse << " m, map " << w.map.size()
            << ", deleted " << w.report.deleted_landmarks << "\n";
  EXPECT_LT(own_rmse, 1.5 * known_rmse + 0.1);
  EXPECT_GT(w.report.deleted_landmarks, 0);  // clutter started tentative landmarks
  // Every true landmark once, at most a few false ones.
  int matched = 0;
  for (const Landmark& t : s.truth.landmarks) {
    for (const Landmark& m : w.map.means) matched += (m - t).norm() < 3.0 ? 1 : 0;
  }
  EXPECT_EQ(matched, 20);
  EXPECT_LE(w.map.size(), 22u);
}

// The circle with 5 clutter detections per scan and the window's own association run over it.
struct OwnWindowRun {
  datasets::Scenario scenario;
  WindowParams params;
  std::unique_ptr<FixedLagSmoother> window;
  std::vector<Pose> filtered;  // the window's pose of every step
};

OwnWindowRun RunOwnWindowOnAClutteredCircle() {
  OwnWindowRun run;
  CircleScenarioOptions o;
  o.steps = 200;
  o.clutter_rate = 5.0;
  run.scenario = MakeCircleScenario(o);
  run.params.known_association = false;
  run.window = std::make_unique<FixedLagSmoother>(run.scenario.PublicContext(), run.params,
                                                  std::vector<std::vector<int>>{},
                                                  run.scenario.steps.size());
  for (const datasets::ScenarioStep& step : run.scenario.steps)
    run.filtered.push_back(run.window->Step(step.data).pose);
  return run;
}

// The window's final labels name one landmark per true landmark and leave clutter out; the
// batch smoother solving them (the graph-SLAM pipeline of smoother-filter with filter_front_end
// window) receives them as they are and is at least as accurate as the window's filtered poses.
TEST(FixedLagSmoother, FinalLabelsAreOneLandmarkPerTrueLandmarkAndFeedTheBatchSmoother) {
  const OwnWindowRun run = RunOwnWindowOnAClutteredCircle();
  const datasets::Scenario& s = run.scenario;
  const WindowParams& own = run.params;
  const FixedLagSmoother& window = *run.window;
  const std::vector<Pose>& filtered = run.filtered;
  const std::vector<std::vector<int>> labels = window.FinalLabels();
  ASSERT_EQ(labels.size(), s.steps.size());
  std::map<int, std::map<int, int>> labels_of_truth;  // true landmark -> label -> detections
  int clutter_kept = 0;
  int clutter = 0;
  for (std::size_t k = 0; k < s.steps.size(); ++k) {
    ASSERT_EQ(labels[k].size(), s.steps[k].origin.size());
    for (std::size_t j = 0; j < labels[k].size(); ++j) {
      const int truth = s.steps[k].origin[j];
      if (truth < 0) {
        ++clutter;
        clutter_kept += labels[k][j] >= 0 ? 1 : 0;
      } else if (labels[k][j] >= 0) {
        ++labels_of_truth[truth][labels[k][j]];
      }
    }
  }
  EXPECT_LT(clutter_kept, clutter / 50);  // under 2 % of the clutter kept on a landmark
  ASSERT_EQ(labels_of_truth.size(), 20u);
  for (const auto& [truth, counts] : labels_of_truth) {
    int most = 0;
    int all = 0;
    for (const auto& [label, n] : counts) {
      most = std::max(most, n);
      all += n;
    }
    EXPECT_GE(most, 0.9 * all) << "true landmark " << truth << " split over " << counts.size();
  }
  SmootherOptions smooth;
  smooth.compute_covariances = false;
  FilterThenSmooth pipeline(
      std::make_unique<FixedLagSmoother>(s.PublicContext(), own, std::vector<std::vector<int>>{},
                                         s.steps.size()),
      smooth);
  const datasets::BatchResult r = pipeline.Solve(s);
  EXPECT_EQ(pipeline.labels(), labels);
  EXPECT_LE(PositionRmse(s, r.poses), PositionRmse(s, filtered));
}

// smoother-unknown with front_end window: the window's labels are the own association's first
// association, which the re-association rounds then revise; the result keeps one landmark per
// true landmark and is at least as accurate as the window's filtered poses.
TEST(FixedLagSmoother, TheOwnAssociationStartsFromTheWindowsLabelsAndReassociatesThem) {
  const OwnWindowRun run = RunOwnWindowOnAClutteredCircle();
  const datasets::Scenario& s = run.scenario;
  const WindowParams& own = run.params;
  const FixedLagSmoother& window = *run.window;
  const std::vector<Pose>& filtered = run.filtered;
  SmootherOptions smooth;
  smooth.association = AssociationMode::kUnknown;
  smooth.front_end = OwnFrontEnd::kWindow;
  smooth.compute_covariances = false;
  FilterThenSmooth pipeline(
      std::make_unique<FixedLagSmoother>(s.PublicContext(), own, std::vector<std::vector<int>>{},
                                         s.steps.size()),
      smooth);
  const datasets::BatchResult r = pipeline.Solve(s);
  EXPECT_EQ(pipeline.labels(), window.FinalLabels());
  EXPECT_GE(pipeline.smoother().report().reassociation_rounds, 1);
  EXPECT_LE(PositionRmse(s, r.poses), PositionRmse(s, filtered));
  int matched = 0;
  for (const Landmark& t : s.truth.landmarks) {
    for (const Landmark& m : r.map.means) matched += (m - t).norm() < 1.0 ? 1 : 0;
  }
  EXPECT_EQ(matched, 20);
  EXPECT_LE(r.map.size(), 22u);
}

// The window front end needs the window's labels and its trajectory: without labels, or with
// another start, the error names the option.
TEST(FixedLagSmoother, TheWindowFrontEndRejectsAMissingLabellingOrAnotherStart) {
  const datasets::Scenario s = MakeCircleScenario(CircleScenarioOptions{});
  SmootherOptions o;
  o.association = AssociationMode::kUnknown;
  o.front_end = OwnFrontEnd::kWindow;
  BatchSmoother without_labels(o);
  try {
    (void)without_labels.Solve(s);
    ADD_FAILURE() << "front_end window solved without labels";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("front_end"), std::string::npos) << e.what();
  }
  o.start_from = StartTrajectory::kPhd3;
  try {
    o.Validate();
    ADD_FAILURE() << "front_end window accepted start_from phd3";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("start_from"), std::string::npos) << e.what();
  }
}

TEST(FixedLagSmoother, BadWindowLengthsAreRejectedNamingTheParameter) {
  const datasets::Scenario s = MakeCircleScenario(CircleScenarioOptions{});
  for (const int length : {0, -3, 101}) {
    WindowParams p;
    p.window_length = length;
    try {
      FixedLagSmoother smoother(s.PublicContext(), p, Origins(s), s.steps.size());
      ADD_FAILURE() << "window_length " << length << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("window_length"), std::string::npos) << e.what();
    }
  }
  WindowParams p;
  p.window_length = 100;  // exactly the run: accepted
  EXPECT_NO_THROW(FixedLagSmoother(s.PublicContext(), p, Origins(s), s.steps.size()));
  p.solve_every = 0;
  EXPECT_THROW(FixedLagSmoother(s.PublicContext(), p, Origins(s), s.steps.size()),
               std::invalid_argument);
  // Through the parameter table: the key is named, the parameters unchanged.
  WindowParams q;
  try {
    ApplyJson(nlohmann::json{{"window_length", 0}}, q);
    ADD_FAILURE() << "window_length 0 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("window_length"), std::string::npos) << e.what();
  }
  EXPECT_EQ(q.window_length, 20);
  EXPECT_THROW(ApplyJson(nlohmann::json{{"association", "unknown"}}, q), std::invalid_argument);
  EXPECT_THROW(ApplyJson(nlohmann::json{{"robust_loss", "tukey"}}, q), std::invalid_argument);
}

TEST(FixedLagSmoother, UnconvergedSolvesAreCounted) {
  const datasets::Scenario s = MakeCircleScenario(CircleScenarioOptions{});
  WindowParams p;
  p.max_iterations = 1;
  p.function_tolerance = 1e-300;
  FixedLagSmoother smoother(s.PublicContext(), p, Origins(s), s.steps.size());
  for (const datasets::ScenarioStep& step : s.steps) smoother.Step(step.data);
  const filters::SolveCounts counts = smoother.Solves();
  EXPECT_EQ(counts.solves, 100);  // one per step
  EXPECT_GT(counts.unconverged, 0);
  EXPECT_EQ(counts.unconverged, smoother.report().unconverged_solves);
}

TEST(WindowParamsJson, RoundTrips) {
  WindowParams p;
  p.window_length = 7;
  p.solve_every = 3;
  p.robust_loss = "huber";
  WindowParams q;
  ApplyJson(ToJson(p), q);
  EXPECT_EQ(ToJson(q), ToJson(p));
}

}  // namespace
}  // namespace phdslam::reference
