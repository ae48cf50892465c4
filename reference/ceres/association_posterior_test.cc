#include "reference/ceres/association_posterior.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "reference/ceres/batch_smoother.h"
#include "reference/ceres/test_scenario.h"
#include "src/models/sensor_model.h"

namespace phdslam::reference {
namespace {

using testing::CircleScenarioOptions;
using testing::MakeCircleScenario;

// The hidden origin labels as an association (clutter: kUnassociated).
Association TrueAssociation(const datasets::Scenario& s) {
  Association a(s.steps.size());
  for (std::size_t k = 0; k < s.steps.size(); ++k) {
    for (int origin : s.steps[k].origin) a[k].push_back(origin >= 0 ? origin : kUnassociated);
  }
  return a;
}

// The odometry factors the final solve of a smoother with `options` holds.
struct Odometry {
  explicit Odometry(const datasets::Scenario& s, const SmootherOptions& options = {})
      : increments(ScenarioOdometry(s, options.odometry_floor)),
        spec{&increments, options.odometry_floor,
             options.odometry_residual == OdometryResidual::kControlSpace} {}
  Odometry(const Odometry&) = delete;  // spec points into this object's increments
  Odometry& operator=(const Odometry&) = delete;
  std::vector<OdometryIncrement> increments;
  OdometrySpec spec;
};

TEST(AssociationPosterior, TermsAtTheNoiseFreeTruthMatchACountOfItsEvents) {
  CircleScenarioOptions o;
  o.noise = false;
  o.detection_probability = 0.8;
  const datasets::Scenario s = MakeCircleScenario(o);
  const Odometry odometry(s);
  const Association truth = TrueAssociation(s);
  const PosteriorTerms t =
      NegativeLogPosterior(s, odometry.spec, s.truth.poses, s.truth.landmarks, truth);

  // Every detection is of a landmark in the FOV (constant pD 0.8), every landmark in the FOV
  // not detected is a miss, and nothing is clutter.
  std::size_t detections = 0;
  std::size_t misses = 0;
  for (std::size_t k = 0; k < s.steps.size(); ++k) {
    detections += truth[k].size();
    for (const Landmark& m : s.truth.landmarks) {
      if (s.sensor.DetectionProbability(s.truth.poses[k], m) > 0.0) ++misses;
    }
  }
  misses -= detections;
  ASSERT_GT(detections, 100u);
  ASSERT_GT(misses, 100u);
  const double n = static_cast<double>(detections);
  const double half_log_det =
      0.5 * std::log((2.0 * std::numbers::pi * s.sensor.noise_cov).determinant());
  EXPECT_NEAR(t.odometry, 0.0, 1e-9);
  EXPECT_NEAR(t.measurements, n * half_log_det, 1e-9 * n);
  EXPECT_NEAR(t.detections, -n * std::log(0.8), 1e-9 * n);
  EXPECT_NEAR(t.missed, -static_cast<double>(misses) * std::log(0.2), 1e-9 * n);
  EXPECT_EQ(t.clutter, 0.0);
  EXPECT_NEAR(t.births, static_cast<double>(s.truth.landmarks.size()) * std::log(1e6), 1e-9);
  EXPECT_DOUBLE_EQ(t.Total(),
                   t.odometry + t.measurements + t.detections + t.missed + t.clutter + t.births);
}

TEST(AssociationPosterior, EachLandmarkPaysTheBirthIntensityUnlessTheMapPriorIsFlat) {
  CircleScenarioOptions o;
  o.clutter_rate = 1.0;
  const datasets::Scenario s = MakeCircleScenario(o);
  const Odometry odometry(s);
  const Association truth = TrueAssociation(s);
  PosteriorOptions birth;
  birth.birth_log_weight = std::log(0.01);
  PosteriorOptions flat;
  flat.map_prior = PosteriorMapPrior::kFlat;
  const PosteriorTerms with_birth =
      NegativeLogPosterior(s, odometry.spec, s.truth.poses, s.truth.landmarks, truth, birth);
  const PosteriorTerms without =
      NegativeLogPosterior(s, odometry.spec, s.truth.poses, s.truth.landmarks, truth, flat);
  const double n = static_cast<double>(s.truth.landmarks.size());
  ASSERT_GT(n, 2.0);
  EXPECT_NEAR(with_birth.births, -n * std::log(0.01), 1e-12);
  EXPECT_EQ(without.births, 0.0);
  EXPECT_NEAR(with_birth.Total() - without.Total(), with_birth.births, 1e-9);
  // The default is the Poisson birth term with the RFS filters' birth weight.
  const PosteriorTerms by_default =
      NegativeLogPosterior(s, odometry.spec, s.truth.poses, s.truth.landmarks, truth);
  EXPECT_NEAR(by_default.births, n * std::log(1e6), 1e-9);
}

// Landmark 0's second half of detections as a landmark of its own at the same true position.
struct SplitSolution {
  std::vector<Landmark> landmarks;
  Association association;
};
SplitSolution SplitLandmarkZero(const datasets::Scenario& s, const Association& truth) {
  SplitSolution split{s.truth.landmarks, truth};
  split.landmarks.push_back(s.truth.landmarks[0]);
  const int copy = static_cast<int>(s.truth.landmarks.size());
  std::size_t seen = 0;
  std::size_t total = 0;
  for (const auto& step : truth)
    total += static_cast<std::size_t>(std::count(step.begin(), step.end(), 0));
  for (auto& step : split.association) {
    for (int& a : step) {
      if (a == 0 && ++seen > total / 2) a = copy;
    }
  }
  return split;
}

TEST(AssociationPosterior, SplittingALandmarkCostsOneBirthMoreThanUnderTheFlatPrior) {
  CircleScenarioOptions o;
  o.clutter_rate = 1.0;
  const datasets::Scenario s = MakeCircleScenario(o);
  const Odometry odometry(s);
  const Association truth = TrueAssociation(s);
  const SplitSolution split = SplitLandmarkZero(s, truth);
  PosteriorOptions flat;
  flat.map_prior = PosteriorMapPrior::kFlat;
  const auto margin = [&](const PosteriorOptions& options) {
    return NegativeLogPosterior(s, odometry.spec, s.truth.poses, split.landmarks, split.association,
                                options)
               .Total() -
           NegativeLogPosterior(s, odometry.spec, s.truth.poses, s.truth.landmarks, truth, options)
               .Total();
  };
  const double with_birth = margin(PosteriorOptions{});
  EXPECT_GT(with_birth, 0.0);
  EXPECT_NEAR(with_birth - margin(flat), std::log(1e6), 1e-6);
}

TEST(AssociationPosterior, RejectsABirthWeightThatIsNotFinite) {
  CircleScenarioOptions o;
  o.steps = 10;
  const datasets::Scenario s = MakeCircleScenario(o);
  const Odometry odometry(s);
  PosteriorOptions bad;
  bad.birth_log_weight = std::numeric_limits<double>::quiet_NaN();
  try {
    NegativeLogPosterior(s, odometry.spec, s.truth.poses, s.truth.landmarks, TrueAssociation(s),
                         bad);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("posterior_birth_log_weight"), std::string::npos);
  }
}

TEST(AssociationPosterior, TheTrueAssociationScoresBelowCorruptedOnes) {
  CircleScenarioOptions o;
  o.clutter_rate = 2.0;
  const datasets::Scenario s = MakeCircleScenario(o);
  const Odometry odometry(s);
  const Association truth = TrueAssociation(s);
  const double at_truth =
      NegativeLogPosterior(s, odometry.spec, s.truth.poses, s.truth.landmarks, truth).Total();

  // Landmarks 0 and 1 exchange their measurements.
  Association swapped = truth;
  for (auto& step : swapped) {
    for (int& a : step) a = a == 0 ? 1 : (a == 1 ? 0 : a);
  }
  // Landmark 2's measurements are called clutter.
  Association dropped = truth;
  for (auto& step : dropped) {
    for (int& a : step) a = a == 2 ? kUnassociated : a;
  }
  // A clutter point is associated with the nearest landmark.
  Association clutter_kept = truth;
  for (std::size_t k = 0; k < s.steps.size(); ++k) {
    for (std::size_t j = 0; j < truth[k].size(); ++j) {
      if (truth[k][j] == kUnassociated) clutter_kept[k][j] = 3;
    }
  }
  for (const Association* a : {&swapped, &dropped, &clutter_kept}) {
    EXPECT_GT(NegativeLogPosterior(s, odometry.spec, s.truth.poses, s.truth.landmarks, *a).Total(),
              at_truth);
  }
}

TEST(AssociationPosterior, TheSmootherReportsTheScoreOfItsSolution) {
  CircleScenarioOptions o;
  o.clutter_rate = 1.0;
  const datasets::Scenario s = MakeCircleScenario(o);
  BatchSmoother smoother(SmootherOptions{});
  const datasets::BatchResult r = smoother.Solve(s);
  ASSERT_TRUE(r.neg_log_posterior);
  EXPECT_DOUBLE_EQ(*r.neg_log_posterior, smoother.report().posterior.Total());
  const Odometry odometry(s, smoother.options());
  EXPECT_DOUBLE_EQ(
      *r.neg_log_posterior,
      NegativeLogPosterior(s, odometry.spec, r.poses, r.map.means, smoother.association()).Total());
  // The solution optimises the odometry and measurement terms: the truth, at the same
  // association and map labels, is no better in those.
  const PosteriorTerms at_solution = smoother.report().posterior;
  std::vector<Landmark> truth_map;
  for (int label : smoother.landmark_labels()) {
    truth_map.push_back(s.truth.landmarks[static_cast<std::size_t>(label)]);
  }
  const PosteriorTerms at_truth =
      NegativeLogPosterior(s, odometry.spec, s.truth.poses, truth_map, smoother.association());
  EXPECT_LT(at_solution.odometry + at_solution.measurements,
            at_truth.odometry + at_truth.measurements);
}

TEST(AssociationPosterior, RejectsInputsThatDoNotMatchTheScenario) {
  CircleScenarioOptions o;
  o.steps = 10;
  const datasets::Scenario s = MakeCircleScenario(o);
  const Odometry odometry(s);
  const Association truth = TrueAssociation(s);
  std::vector<Pose> short_poses(s.truth.poses.begin(), s.truth.poses.end() - 1);
  EXPECT_THROW(NegativeLogPosterior(s, odometry.spec, short_poses, s.truth.landmarks, truth),
               std::invalid_argument);
  Association out_of_range = truth;
  for (auto& step : out_of_range) {
    if (!step.empty()) {
      step[0] = static_cast<int>(s.truth.landmarks.size());
      break;
    }
  }
  EXPECT_THROW(
      NegativeLogPosterior(s, odometry.spec, s.truth.poses, s.truth.landmarks, out_of_range),
      std::invalid_argument);
  Association missing_measurement = truth;
  for (auto& step : missing_measurement) {
    if (!step.empty()) {
      step.pop_back();
      break;
    }
  }
  EXPECT_THROW(
      NegativeLogPosterior(s, odometry.spec, s.truth.poses, s.truth.landmarks, missing_measurement),
      std::invalid_argument);
}

}  // namespace
}  // namespace phdslam::reference
