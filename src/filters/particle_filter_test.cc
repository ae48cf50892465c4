// The particle-filter skeleton on a toy map model: its random-number layout, weights, estimate,
// ESS and resampling, independent of any map kind.
#include "src/filters/particle_filter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "src/core/gaussian.h"
#include "src/core/random.h"
#include "src/filters/gm_ipl_density.h"
#include "src/models/velocity_motion_model.h"

namespace phdslam::filters {
namespace {

/// A map that only counts its updates; the likelihood prefers poses near the origin.
struct CountingMap {
  int updates = 0;
};

class ToyModel {
 public:
  using Map = CountingMap;
  using Snapshot = int;

  [[nodiscard]] Map InitialMap() const { return {}; }
  void BeginStep(const StepData& /*step*/) { ++steps; }
  void BeforePrediction(Map& /*map*/, const Pose& /*pose*/) const {}
  [[nodiscard]] MapView View(const Map& /*map*/) const { return {}; }
  void Update(Map& map, const Pose& x, const StepData& /*step*/, double& log_weight) const {
    ++map.updates;
    log_weight += -0.5 * x.head<2>().squaredNorm() / likelihood_variance;
  }
  [[nodiscard]] Snapshot Estimate(const Map& map) const { return map.updates; }
  [[nodiscard]] MapEstimate ToMapEstimate(const Snapshot& updates) const {
    MapEstimate m;
    m.means.assign(static_cast<std::size_t>(updates), Landmark::Zero());
    return m;
  }
  [[nodiscard]] int ComponentCount(const Map& map) const { return map.updates; }

  double likelihood_variance = 1.0;
  int steps = 0;
};

EstimatorContext Context() {
  EstimatorContext c;
  c.initial_pose = Pose(0.5, -0.25, 0.1);
  c.motion = std::make_shared<models::VelocityMotionModel>();
  c.control_noise_cov = Vec2(0.04, 0.01).asDiagonal();
  return c;
}

StepData MoveStep() {
  StepData s;
  s.times = {0.0, 1.0};
  s.controls = {Control(1.0, 0.05)};
  return s;
}

std::unique_ptr<ParticleFilter<ToyModel>> Filter(ParticleFilterParams params, std::uint64_t seed,
                                                 double variance = 1.0) {
  ToyModel model;
  model.likelihood_variance = variance;
  return std::make_unique<ParticleFilter<ToyModel>>(Context(), params, model,
                                                    std::make_unique<TransitionDensity>(), seed);
}

TEST(ParticleFilter, DrawsTheUniformsThenTheNormalsOfEveryParticle) {
  ParticleFilterParams params;
  params.particles = 3;
  params.resampling = false;
  auto filter = Filter(params, 42);
  const StepData step = MoveStep();
  filter->Step(step);
  // The predicted Gaussian every particle starts from (all are copies of the initial pose).
  Pose mu0 = Context().initial_pose;
  Mat3 sigma0 = Mat3::Zero();
  PredictPoseGaussian(Context(), step, params.pose_regularisation, mu0, sigma0);
  const Mat3 chol = *CholeskyLower<3>(sigma0);
  RandomStream rng(42);
  for (int i = 0; i < 3; ++i) rng.Uniform();
  for (int i = 0; i < 3; ++i) {
    Vec3 xi;
    xi << rng.Normal(), rng.Normal(), rng.Normal();
    const Pose expected = mu0 + chol * xi;
    EXPECT_LT((filter->particles()[i].pose - expected).norm(), 1e-12) << "particle " << i;
    // The prior is the proposal: the weight changes by the likelihood alone.
    const double expected_log_w = -std::log(3.0) - 0.5 * expected.head<2>().squaredNorm();
    EXPECT_NEAR(filter->particles()[i].log_weight, expected_log_w, 1e-12) << "particle " << i;
  }
  EXPECT_EQ(filter->model().steps, 1);
}

TEST(ParticleFilter, EstimateIsTheHeaviestParticleAndEssMatchesTheWeights) {
  ParticleFilterParams params;
  params.particles = 20;
  params.resampling = false;
  auto filter = Filter(params, 7);
  const StepOutput out = filter->Step(MoveStep());
  std::vector<double> log_w;
  int best = 0;
  for (int i = 0; i < 20; ++i) {
    log_w.push_back(filter->particles()[i].log_weight);
    if (log_w[i] > log_w[best]) best = i;
  }
  EXPECT_EQ(filter->best_particle(), best);
  EXPECT_EQ(out.pose, filter->particles()[best].pose);
  const std::vector<double> w = NormalisedWeights(log_w);
  EXPECT_NEAR(out.diag.ess, EffectiveSampleSize(w), 1e-12);
  EXPECT_FALSE(out.diag.resampled);
  ASSERT_TRUE(out.pose_cov.has_value());
  Mat3 spread = Mat3::Zero();
  for (int i = 0; i < 20; ++i) {
    const Vec3 d = filter->particles()[i].pose - out.pose;
    spread += w[i] * d * d.transpose();
  }
  EXPECT_LT((*out.pose_cov - spread).norm(), 1e-12);
  EXPECT_EQ(out.diag.map_components, 1);
  EXPECT_EQ(out.diag.hypotheses, 1);
  EXPECT_EQ(filter->Map().size(), 1u);
}

TEST(ParticleFilter, ResamplesBelowTheThresholdToEqualWeights) {
  ParticleFilterParams params;
  params.particles = 10;
  params.ess_threshold = 1.0;  // relative: always resample
  auto filter = Filter(params, 9, 0.01);
  const StepOutput out = filter->Step(MoveStep());
  EXPECT_TRUE(out.diag.resampled);
  EXPECT_LT(out.diag.ess, 10.0);
  for (const auto& p : filter->particles()) {
    EXPECT_DOUBLE_EQ(p.log_weight, -std::log(10.0));
    EXPECT_GE(p.parent, 0);
    EXPECT_LT(p.parent, 10);
  }
  // An absolute threshold below any ESS never resamples.
  params.ess_threshold_kind = EssThresholdKind::kAbsolute;
  params.ess_threshold = 0.5;
  auto never = Filter(params, 9, 0.01);
  EXPECT_FALSE(never->Step(MoveStep()).diag.resampled);
}

TEST(ParticleFilter, SharingTheProposalBetweenCopiesChangesNothing) {
  ParticleFilterParams shared;
  shared.particles = 8;
  shared.ess_threshold = 1.0;
  ParticleFilterParams own = shared;
  own.reuse_parent_proposal = false;
  auto a = Filter(shared, 3, 0.05);
  auto b = Filter(own, 3, 0.05);
  for (int k = 0; k < 5; ++k) {
    const StepOutput oa = a->Step(MoveStep());
    const StepOutput ob = b->Step(MoveStep());
    EXPECT_EQ(oa.pose, ob.pose) << "step " << k;
    EXPECT_EQ(oa.diag.ess, ob.diag.ess) << "step " << k;
  }
  for (int i = 0; i < 8; ++i) {
    EXPECT_EQ(a->particles()[i].pose, b->particles()[i].pose);
    EXPECT_EQ(a->particles()[i].log_weight, b->particles()[i].log_weight);
  }
}

TEST(ParticleFilter, ASingleTimeStampStepKeepsThePose) {
  ParticleFilterParams params;
  auto filter = Filter(params, 1);
  StepData still;
  still.times = {0.0};
  const StepOutput out = filter->Step(still);
  // No propagation: the predicted covariance is zero, has no Cholesky factor, and the pose stays.
  EXPECT_EQ(out.pose, Context().initial_pose);
  EXPECT_EQ(filter->particles()[0].map.updates, 1);
}

/// A density with one fixed component offset from the prediction (a stand-in for a conditional).
class ShiftedDensity final : public ImportanceDensity {
 public:
  [[nodiscard]] ProposalOutput Build(const ProposalInput& input) const override {
    ProposalOutput out;
    out.mixture.Add(0.0, input.predicted_mean + Vec3(0.1, -0.2, 0.01),
                    Vec3(0.02, 0.03, 0.001).asDiagonal());
    return out;
  }
};

TEST(ParticleFilter, WithOneParticleTheRbCovarianceIsThatParticlesProposal) {
  ParticleFilterParams params;
  params.particles = 1;
  // The transition density: the predicted Gaussian.
  auto prior = Filter(params, 5);
  Pose mu0 = Context().initial_pose;
  Mat3 sigma0 = Mat3::Zero();
  PredictPoseGaussian(Context(), MoveStep(), params.pose_regularisation, mu0, sigma0);
  const StepOutput a = prior->Step(MoveStep());
  ASSERT_TRUE(a.pose_cov_rb.has_value());
  EXPECT_EQ(*a.pose_mean_rb, mu0);
  EXPECT_TRUE(a.pose_cov_rb->isApprox(sigma0, 1e-14)) << *a.pose_cov_rb;
  EXPECT_FALSE(a.pose_cov.has_value());  // no particle spread with one particle
  // Another density: its component.
  ParticleFilter<ToyModel> shifted(Context(), params, ToyModel{},
                                   std::make_unique<ShiftedDensity>(), 5);
  const StepOutput b = shifted.Step(MoveStep());
  EXPECT_TRUE(b.pose_mean_rb->isApprox(mu0 + Vec3(0.1, -0.2, 0.01), 1e-14));
  EXPECT_EQ(*b.pose_cov_rb, Mat3(Vec3(0.02, 0.03, 0.001).asDiagonal()));
}

TEST(ParticleFilter, RbMomentsMixTheParticlesWithTheCarriedInWeights) {
  ParticleFilterParams params;
  params.particles = 4;
  params.resampling = false;
  auto filter = Filter(params, 11, 0.05);
  filter->Step(MoveStep());
  // The weights and poses carried into the second step, and each particle's predicted Gaussian.
  std::vector<PoseMoments> expected;
  for (const auto& p : filter->particles()) {
    Pose mu = p.pose;
    Mat3 sigma = Mat3::Zero();
    PredictPoseGaussian(Context(), MoveStep(), params.pose_regularisation, mu, sigma);
    expected.push_back({p.log_weight, mu, sigma});
  }
  const auto m = MatchMoments(expected);
  ASSERT_TRUE(m.has_value());
  const StepOutput out = filter->Step(MoveStep());
  ASSERT_TRUE(out.pose_cov_rb.has_value());
  EXPECT_TRUE(out.pose_mean_rb->isApprox(m->mean, 1e-12));
  EXPECT_TRUE(out.pose_cov_rb->isApprox(m->cov, 1e-12));
  // The mixture is wider than any one predicted Gaussian (the particles are spread).
  EXPECT_GT(out.pose_cov_rb->trace(), expected[0].cov.trace());
}

}  // namespace
}  // namespace phdslam::filters
