// Wall time of one full filter recursion (RbPhdSlam::Step: prediction, proposal, sampling, PHD
// update, reduction, estimate, resampling) on the paper's synthetic scenario, single thread.
// Paper (MATLAB + C MEX, i7-9850H): PHD-SLAM 3.0 takes 0.14 / 1.17 / 10.94 ms per recursion at
// N = 1 / 10 / 100; at N = 10, 1.0 takes 0.59, 2.0a 0.65 and 2.0b 2.28 ms.
//
// Method: the scenario (Monte Carlo seed 1, all 4000 steps) is built once. Each benchmark creates
// its filter, runs it over the first kWarmupSteps steps outside the timed loop, and then times
// kTimedSteps **consecutive** steps (steps 501-700), one step per benchmark iteration. The filter
// is not copied back to a saved state between iterations (it owns its importance density and is
// not copyable); timing consecutive steps of one run is also what the paper's per-recursion mean
// is. The iteration count is fixed, so every benchmark times exactly the same steps. Step() is
// single-threaded: on a shared machine read the CPU column, since the wall time also counts
// waiting for a core. Counters: mean proposal components, map components, resampling rate.
//
// Every Step benchmark also reports `allocations`: the calls of operator new per timed step
// (benchmarks/allocation_counter.h), a steady-state step's allocations.
//
// Step/<labelled filter>/N:10/clutter:15 times delta-GLMB-SLAM 2.0 (glmb2), 1.0 (glmb1) and
// LMB-SLAM (lmb) with their default parameters on the glmb-sim scenario (Monte Carlo seed 1,
// clutter rate 15, 10 particles): kGlmbWarmupSteps steps untimed, then kGlmbTimedSteps
// consecutive steps.
//
// RbMoments/N times the Rao-Blackwellised pose moments alone (particle_filter.h: per particle
// the moments of its proposal, then the weighted match over the particles) for N particles with
// `components`-component proposals, to be read as a ratio to Step/phd3/N of the same run.
#include <benchmark/benchmark.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "benchmarks/allocation_counter.h"
#include "datasets/data_dir.h"
#include "datasets/glmb_simulation.h"
#include "datasets/paper_synthetic.h"
#include "src/core/malloc_name.h"
#include "src/core/random.h"
#include "src/filters/phd_slam_family.h"
#include "src/filters/pose_mixture_moments.h"
#include "src/glmb/glmb_slam.h"

namespace phdslam::benchmarks {
namespace {

constexpr int kWarmupSteps = 500;
constexpr int kTimedSteps = 200;
constexpr int kGlmbWarmupSteps = 40;
constexpr int kGlmbTimedSteps = 60;
constexpr double kGlmbClutterRate = 15.0;

const datasets::Scenario& PaperScenario() {
  static const datasets::Scenario scenario = [] {
    const auto env = datasets::LoadPaperSyntheticEnvironment(
        datasets::ResolveDataDirFor(std::nullopt, datasets::PaperSyntheticDataFiles()));
    return datasets::MakePaperSyntheticScenario(env, 1);
  }();
  return scenario;
}

/// Runs `warmup` steps untimed, then one step per iteration; the counters are means per step.
void TimeSteps(benchmark::State& state, filters::OnlineEstimator& filter,
               const datasets::Scenario& scenario, int warmup) {
  std::size_t k = 0;
  for (; k < static_cast<std::size_t>(warmup); ++k) filter.Step(scenario.steps[k].data);
  double components = 0.0;
  double hypotheses = 0.0;
  int resampled = 0;
  const std::uint64_t allocations_before = AllocationCount().load();
  for (auto _ : state) {
    const filters::StepOutput out = filter.Step(scenario.steps[k++].data);
    components += out.diag.map_components;
    hypotheses += out.diag.hypotheses;
    resampled += out.diag.resampled ? 1 : 0;
  }
  const double allocations = static_cast<double>(AllocationCount().load() - allocations_before);
  const double n = static_cast<double>(state.iterations());
  state.counters["map_components"] = components / n;
  state.counters["hypotheses"] = hypotheses / n;
  state.counters["resampled_pct"] = 100.0 * resampled / n;
  state.counters["allocations"] = allocations / n;
}

void BenchmarkStep(benchmark::State& state, const std::string& variant, int particles) {
  const datasets::Scenario& scenario = PaperScenario();
  filters::PhdSlamParams params;
  params.particles = particles;
  const auto filter = filters::MakePhdSlam(variant, scenario.PublicContext(), params,
                                           DeriveSeed(HashName(variant), 1));
  TimeSteps(state, *filter, scenario, kWarmupSteps);
}

const datasets::Scenario& GlmbScenario() {
  static const datasets::Scenario scenario = [] {
    datasets::GlmbSimOptions options;
    options.clutter_rate = kGlmbClutterRate;
    return datasets::MakeGlmbSimScenario(options, 1);
  }();
  return scenario;
}

void BenchmarkGlmbStep(benchmark::State& state, const std::string& variant, int particles) {
  const datasets::Scenario& scenario = GlmbScenario();
  glmb::GlmbSlamParams params;
  params.particles = particles;
  const std::uint64_t seed = DeriveSeed(HashName(variant), 1);
  std::unique_ptr<filters::OnlineEstimator> filter;
  if (variant == "lmb") {
    filter = glmb::MakeLmbSlam(scenario.PublicContext(), params, seed);
  } else {
    filter = glmb::MakeGlmbSlam(scenario.PublicContext(), params, variant == "glmb2", seed);
  }
  TimeSteps(state, *filter, scenario, kGlmbWarmupSteps);
}

void BenchmarkRbMoments(benchmark::State& state, int particles, int components) {
  RandomStream rng(3);
  std::vector<filters::PreparedProposal> proposals;
  for (int i = 0; i < particles; ++i) {
    filters::GaussianMixtureProposal g;
    for (int t = 0; t < components; ++t) {
      g.Add(rng.Normal(), Pose(rng.Normal(), rng.Normal(), 0.1 * rng.Normal()),
            Vec3(0.01, 0.02, 1e-4).asDiagonal());
    }
    proposals.push_back(filters::PrepareProposal(std::move(g)));
  }
  std::vector<filters::PoseMoments> moments(static_cast<std::size_t>(particles));
  const Pose fallback = Pose::Zero();
  for (auto _ : state) {
    for (int i = 0; i < particles; ++i) {
      moments[i] = filters::ProposalMoments(proposals[i], fallback);
      moments[i].log_weight = -0.01 * i;
    }
    benchmark::DoNotOptimize(filters::MatchMoments(moments));
  }
}

void Register(const std::string& variant, int particles) {
  const std::string name = "Step/" + variant + "/N:" + std::to_string(particles);
  benchmark::RegisterBenchmark(name.c_str(), BenchmarkStep, variant, particles)
      ->Iterations(kTimedSteps)
      ->Unit(benchmark::kMillisecond);
}

}  // namespace
}  // namespace phdslam::benchmarks

int main(int argc, char** argv) {
  using phdslam::benchmarks::Register;
  benchmark::Initialize(&argc, argv);
  benchmark::AddCustomContext("malloc", phdslam::MallocName());
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  Register("phd3", 1);
  Register("phd3", 10);
  Register("phd3", 100);
  Register("phd1", 10);
  Register("phd2a", 10);
  Register("phd2b", 10);
  for (const char* variant : {"glmb2", "glmb1", "lmb"}) {
    const std::string name = std::string("Step/") + variant + "/N:10/clutter:15";
    benchmark::RegisterBenchmark(name.c_str(), phdslam::benchmarks::BenchmarkGlmbStep,
                                 std::string(variant), 10)
        ->Iterations(phdslam::benchmarks::kGlmbTimedSteps)
        ->Unit(benchmark::kMillisecond);
  }
  for (const int n : {1, 10, 100}) {
    for (const int c : {1, 4}) {
      const std::string name =
          "RbMoments/N:" + std::to_string(n) + "/components:" + std::to_string(c);
      benchmark::RegisterBenchmark(name.c_str(), phdslam::benchmarks::BenchmarkRbMoments, n, c)
          ->Unit(benchmark::kMicrosecond);
    }
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
