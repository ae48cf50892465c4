// Contract tests run over every map model of the particle-filter skeleton (the MapModel concept
// of src/filters/particle_filter.h): the GM-PHD map of the PHD-SLAM family, the oracle's
// known-association landmark EKFs, the delta-GLMB map and the LMB map. They drive a model as the
// skeleton does (BeginStep, BeforePrediction, View, Update) from known poses, with no pose
// sampling, so what they check is the map model alone.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "oracle/oracle_rbpf.h"
#include "src/core/gaussian.h"
#include "src/filters/particle_filter.h"
#include "src/filters/rb_phd_slam.h"
#include "src/glmb/glmb_slam.h"
#include "src/models/range_bearing_model.h"

namespace phdslam::filters {
namespace {

/// Landmarks seen from two poses: the first steps see landmarks 0-2 from `first`, the later ones
/// landmarks 0-3 from `second` (landmark 3 is new there).
struct Scene {
  std::vector<Landmark> landmarks = {Landmark(20.0, 5.0), Landmark(30.0, -8.0),
                                     Landmark(15.0, -15.0), Landmark(35.0, 12.0)};
  Pose first = Pose(0.0, 0.0, 0.0);
  Pose second = Pose(2.0, 1.0, 0.05);
  EstimatorContext context;

  Scene() {
    context.sensor.noise_cov = Vec2(0.01, 1e-4).asDiagonal();
    context.sensor.clutter_rate = 1.0;
    context.sensor.pd_max = 0.95;
    context.sensor.pd_nominal = 0.95;
  }

  /// Step k (from 0): a single time stamp (no propagation) and the noise-free measurements of
  /// the landmarks seen at that step, in landmark order.
  [[nodiscard]] StepData Step(int k, int first_steps) const {
    StepData s;
    s.times = {static_cast<double>(k)};
    const bool later = k >= first_steps;
    const int seen = later ? 4 : 3;
    for (int i = 0; i < seen; ++i) {
      s.measurements.push_back(models::PredictMeasurement(later ? second : first, landmarks[i]));
    }
    return s;
  }
  [[nodiscard]] const Pose& PoseAt(int k, int first_steps) const {
    return k >= first_steps ? second : first;
  }
  /// The origin labels of `steps` steps (for the oracle).
  [[nodiscard]] std::vector<std::vector<int>> Origins(int steps, int first_steps) const {
    std::vector<std::vector<int>> origins;
    for (int k = 0; k < steps; ++k) {
      origins.push_back(k >= first_steps ? std::vector<int>{0, 1, 2, 3}
                                         : std::vector<int>{0, 1, 2});
    }
    return origins;
  }
};

constexpr int kFirstSteps = 4;  ///< steps from the first pose
constexpr int kAllSteps = 8;    ///< then from the second pose
constexpr std::uint64_t kSeed = 17;

/// How each map model is made for the scene.
struct GmPhd {
  static constexpr const char* kName = "GmPhd";
  static PhdMapModel Make(const Scene& s) { return {s.context, PhdSlamParams{}}; }
};
struct Oracle {
  static constexpr const char* kName = "Oracle";
  static oracle::OracleMapModel Make(const Scene& s) {
    return {s.Origins(kAllSteps, kFirstSteps), s.context.sensor.noise_cov};
  }
};
struct DeltaGlmb {
  static constexpr const char* kName = "DeltaGlmb";
  static glmb::GlmbMapModel Make(const Scene& s) {
    glmb::GlmbSlamParams params;
    params.gibbs_samples = 50;
    params.max_hypotheses = 50;
    return {s.context, params, true, kSeed};
  }
};
struct Lmb {
  static constexpr const char* kName = "Lmb";
  static glmb::LmbMapModel Make(const Scene& s) {
    glmb::GlmbSlamParams params;
    params.gibbs_samples = 50;
    return {s.context, params, kSeed};
  }
};

static_assert(MapModel<PhdMapModel>);
static_assert(MapModel<oracle::OracleMapModel>);
static_assert(MapModel<glmb::GlmbMapModel>);
static_assert(MapModel<glmb::LmbMapModel>);

/// One skeleton step of the map model at the known pose: returns the log-weight increment.
template <MapModel Model>
double Advance(Model& model, typename Model::Map& map, const Pose& pose, const StepData& step) {
  model.BeginStep(step);
  model.BeforePrediction(map, pose);
  (void)model.View(map);
  double log_weight = 0.0;
  if constexpr (ReportsInnovations<Model>) {
    InnovationStats nis;
    model.Update(map, pose, step, log_weight, nis);
  } else {
    model.Update(map, pose, step, log_weight);
  }
  return log_weight;
}

template <MapModel Model>
MapEstimate EstimateOf(const Model& model, const typename Model::Map& map) {
  return model.ToMapEstimate(model.Estimate(map));
}

void ExpectSameEstimate(const MapEstimate& a, const MapEstimate& b) {
  EXPECT_EQ(a.means, b.means);
  EXPECT_EQ(a.covs, b.covs);
  EXPECT_EQ(a.log_weights, b.log_weights);
}

/// The landmark views's content, copied (a view is valid only until the next View call).
std::vector<phd::GaussianComponent> ViewOf(auto& model, const auto& map) {
  const MapView view = model.View(map);
  return {view.landmarks.begin(), view.landmarks.end()};
}

template <class Case>
class MapModelContract : public ::testing::Test {
 protected:
  Scene scene;
};

/// Names the typed tests by map model (MapModelContract/GmPhd.*).
struct MapModelName {
  template <class Case>
  static std::string GetName(int /*index*/) {
    return Case::kName;
  }
};

using MapModels = ::testing::Types<GmPhd, Oracle, DeltaGlmb, Lmb>;
TYPED_TEST_SUITE(MapModelContract, MapModels, MapModelName);

TYPED_TEST(MapModelContract, TheInitialMapEstimatesNoLandmark) {
  auto model = TypeParam::Make(this->scene);
  EXPECT_EQ(EstimateOf(model, model.InitialMap()).size(), 0u);
}

// From known poses the map estimate finds every landmark seen: each within 0.1 m of an estimated
// landmark (noise-free measurements), no more estimates than landmarks, finite weights and
// positive-definite covariances; every update adds a finite log-likelihood.
TYPED_TEST(MapModelContract, MapsTheLandmarksSeenFromKnownPoses) {
  auto model = TypeParam::Make(this->scene);
  auto map = model.InitialMap();
  for (int k = 0; k < kAllSteps; ++k) {
    const double increment =
        Advance(model, map, this->scene.PoseAt(k, kFirstSteps), this->scene.Step(k, kFirstSteps));
    EXPECT_TRUE(std::isfinite(increment)) << "step " << k;
  }
  const MapEstimate estimate = EstimateOf(model, map);
  ASSERT_LE(estimate.size(), this->scene.landmarks.size());
  ASSERT_EQ(estimate.covs.size(), estimate.size());
  for (const Landmark& truth : this->scene.landmarks) {
    double nearest = std::numeric_limits<double>::infinity();
    for (const Landmark& m : estimate.means) nearest = std::min(nearest, (m - truth).norm());
    EXPECT_LT(nearest, 0.1) << "landmark at " << truth.transpose();
  }
  for (std::size_t i = 0; i < estimate.size(); ++i) {
    EXPECT_TRUE(CholeskyLower<2>(estimate.covs[i]).has_value()) << i;
    if (i < estimate.log_weights.size()) {
      EXPECT_TRUE(std::isfinite(estimate.log_weights[i])) << i;
    }
  }
  EXPECT_GE(model.ComponentCount(map), 1);
}

// Resampling copies maps, and copies may share storage (the GM-PHD map shares its passive chunks,
// the delta-GLMB map its hypotheses' track sets): a copy, and a snapshot taken by Estimate, must
// not change when the original is updated afterwards.
TYPED_TEST(MapModelContract, ACopiedMapIsUnaffectedByUpdatesToTheOriginal) {
  auto model = TypeParam::Make(this->scene);
  auto map = model.InitialMap();
  for (int k = 0; k < kFirstSteps; ++k) {
    Advance(model, map, this->scene.first, this->scene.Step(k, kFirstSteps));
  }
  const auto copy = map;
  const auto snapshot = model.Estimate(map);
  const MapEstimate copy_before = EstimateOf(model, copy);
  const MapEstimate snapshot_before = model.ToMapEstimate(snapshot);
  const int count_before = model.ComponentCount(copy);
  const std::vector<phd::GaussianComponent> view_before = ViewOf(model, copy);
  ASSERT_GT(copy_before.size(), 0u);

  for (int k = kFirstSteps; k < kAllSteps; ++k) {
    Advance(model, map, this->scene.second, this->scene.Step(k, kFirstSteps));
  }
  ASSERT_NE(EstimateOf(model, map).size(), copy_before.size())
      << "the original did not change, so the test shows nothing";

  ExpectSameEstimate(EstimateOf(model, copy), copy_before);
  ExpectSameEstimate(model.ToMapEstimate(snapshot), snapshot_before);
  EXPECT_EQ(model.ComponentCount(copy), count_before);
  const std::vector<phd::GaussianComponent> view_after = ViewOf(model, copy);
  ASSERT_EQ(view_after.size(), view_before.size());
  for (std::size_t i = 0; i < view_after.size(); ++i) {
    EXPECT_EQ(view_after[i].mean, view_before[i].mean) << i;
    EXPECT_EQ(view_after[i].cov, view_before[i].cov) << i;
    EXPECT_EQ(view_after[i].log_weight, view_before[i].log_weight) << i;
  }
}

// Two models made alike and fed alike give identical weights and maps (a map model's random
// numbers, if any, come from a stream seeded at construction).
TYPED_TEST(MapModelContract, SameInputsGiveIdenticalMaps) {
  auto a = TypeParam::Make(this->scene);
  auto b = TypeParam::Make(this->scene);
  auto map_a = a.InitialMap();
  auto map_b = b.InitialMap();
  for (int k = 0; k < kAllSteps; ++k) {
    const Pose& pose = this->scene.PoseAt(k, kFirstSteps);
    const StepData step = this->scene.Step(k, kFirstSteps);
    EXPECT_EQ(Advance(a, map_a, pose, step), Advance(b, map_b, pose, step)) << "step " << k;
  }
  ExpectSameEstimate(EstimateOf(a, map_a), EstimateOf(b, map_b));
  EXPECT_EQ(a.ComponentCount(map_a), b.ComponentCount(map_b));
}

}  // namespace
}  // namespace phdslam::filters
