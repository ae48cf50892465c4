// Wall time of one delta-GLMB joint prediction/update (glmb/joint_update.h: entry terms, eta
// matrices, Gibbs sampling from the optimal association, children, merging, truncation) against
// the number of landmarks in view and the clutter rate, single thread, at the source paper's
// settings (3 m disc FOV, pD 0.7, pS 0.95, sigma_r 0.05 m, sigma_b 0.5 deg, clutter uniform in
// (r, b), H_upd = H_max = 1000, births r_B = 1e-4 from the previous scan).
//
// Method: `landmarks` landmarks are placed on a circle of radius 1.5 m around the pose. The prior
// is built by five warm-up updates at the same pose (each with a fresh scan: every landmark
// detected with probability pD, Poisson clutter), so it holds the hypotheses the filter carries
// into a step; then every benchmark iteration runs one update of that same prior with one fresh
// scan (and its previous scan's births). Counters: prior hypotheses, births offered (rows added to
// every eta matrix), mean posterior hypotheses, and allocations (calls of operator new per update,
// scan included; benchmarks/allocation_counter.h).
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "benchmarks/allocation_counter.h"
#include "src/core/angles.h"
#include "src/core/random.h"
#include "src/glmb/birth.h"
#include "src/glmb/joint_update.h"
#include "src/models/range_bearing_model.h"

namespace phdslam::benchmarks {
namespace {

constexpr double kPi = std::numbers::pi;

struct Setup {
  models::SensorModel sensor;
  glmb::MeasurementSetup measurement;
  glmb::UpdateSettings settings;
  std::vector<Landmark> landmarks;
  double clutter_rate;
};

Setup MakeSetup(int landmarks, double clutter_rate) {
  Setup s;
  s.sensor.fov_range = 3.0;
  s.sensor.fov_half_angle = kPi;
  s.sensor.pd_max = 0.7;
  s.sensor.noise_cov = Vec2(0.05 * 0.05, DegToRad(0.5) * DegToRad(0.5)).asDiagonal();
  s.sensor.clutter_rate = clutter_rate;
  s.measurement.noise_cov = s.sensor.noise_cov;
  s.settings.log_clutter_intensity = std::log(clutter_rate / (3.0 * 2.0 * kPi));
  s.settings.clutter_rate = clutter_rate;
  s.clutter_rate = clutter_rate;
  for (int i = 0; i < landmarks; ++i) {
    const double a = 2.0 * kPi * i / landmarks;
    s.landmarks.emplace_back(1.5 * std::cos(a), 1.5 * std::sin(a));
  }
  return s;
}

std::vector<Measurement> Scan(const Setup& s, const Pose& x, RandomStream& rng) {
  std::vector<Measurement> z;
  const Vec2 sd(0.05, DegToRad(0.5));
  for (const Landmark& m : s.landmarks) {
    if (rng.Uniform() >= 0.7) continue;
    Measurement zm = models::PredictMeasurement(x, m);
    zm += Vec2(sd(0) * rng.Normal(), sd(1) * rng.Normal());
    zm(1) = WrapAngle(zm(1));
    z.push_back(zm);
  }
  const int clutter = rng.Poisson(s.clutter_rate);
  for (int c = 0; c < clutter; ++c) z.emplace_back(rng.Uniform(0.0, 3.0), rng.Uniform(-kPi, kPi));
  return z;
}

void BenchmarkUpdate(benchmark::State& state) {
  const int landmarks = static_cast<int>(state.range(0));
  const double clutter_rate = static_cast<double>(state.range(1));
  Setup s = MakeSetup(landmarks, clutter_rate);
  s.measurement.sensor = &s.sensor;
  const Pose x = Pose::Zero();
  RandomStream rng(
      DeriveSeed(static_cast<std::uint64_t>(landmarks), static_cast<std::uint64_t>(clutter_rate)));
  std::uint64_t next_id = 1;
  std::vector<glmb::Hypothesis> prior = glmb::EmptyDensity();
  // Warm-up: the map starts with every landmark as one confirmed entry.
  {
    glmb::TrackSet set;
    for (int i = 0; i < landmarks; ++i) {
      set.push_back(
          glmb::MakeTrack(next_id++, glmb::Label{0, i}, s.landmarks[i], 1e-3 * Mat2::Identity()));
    }
    prior = {glmb::Hypothesis{std::make_shared<const glmb::TrackSet>(std::move(set)), 0.0}};
  }
  std::vector<glmb::BirthTrack> births;
  for (int k = 1; k <= 5; ++k) {
    const std::vector<Measurement> z = Scan(s, x, rng);
    glmb::UpdateResult r =
        glmb::JointUpdate(prior, {}, births, x, z, s.measurement, s.settings, rng, next_id);
    prior = std::move(r.hypotheses);
    births = glmb::MakeBirths(x, z, s.sensor.noise_cov, r, glmb::BirthSettings{}, k + 1, next_id);
  }
  double posterior = 0.0;
  const std::uint64_t allocations_before = AllocationCount().load();
  for (auto _ : state) {
    const std::vector<Measurement> z = Scan(s, x, rng);
    std::uint64_t id = next_id;
    const glmb::UpdateResult r =
        glmb::JointUpdate(prior, {}, births, x, z, s.measurement, s.settings, rng, id);
    posterior += static_cast<double>(r.hypotheses.size());
    benchmark::DoNotOptimize(r.log_normaliser);
  }
  state.counters["prior_hypotheses"] = static_cast<double>(prior.size());
  state.counters["births"] = static_cast<double>(births.size());
  state.counters["posterior_hypotheses"] = posterior / static_cast<double>(state.iterations());
  state.counters["allocations"] =
      static_cast<double>(AllocationCount().load() - allocations_before) /
      static_cast<double>(state.iterations());
}

BENCHMARK(BenchmarkUpdate)
    ->ArgNames({"landmarks", "clutter"})
    ->ArgsProduct({{2, 5, 10, 20}, {1, 5, 10, 15}})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace phdslam::benchmarks

BENCHMARK_MAIN();
