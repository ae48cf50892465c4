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
// RbMoments/N times the Rao-Blackwellised pose moments alone (particle_filter.h: per particle
// the moments of its proposal, then the weighted match over the particles) for N particles with
// `components`-component proposals, to be read as a ratio to Step/phd3/N of the same run.
#include <benchmark/benchmark.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "datasets/data_dir.h"
#include "datasets/paper_synthetic.h"
#include "src/core/malloc_name.h"
#include "src/core/random.h"
#include "src/filters/phd_slam_family.h"
#include "src/filters/pose_mixture_moments.h"

namespace phdslam::benchmarks {
namespace {

constexpr int kWarmupSteps = 500;
constexpr int kTimedSteps = 200;

const datasets::Scenario& PaperScenario() {
  static const datasets::Scenario scenario = [] {
    const auto env =
        datasets::LoadPaperSyntheticEnvironment(datasets::ResolveDataDir(std::nullopt));
    return datasets::MakePaperSyntheticScenario(env, 1);
  }();
  return scenario;
}

void BenchmarkStep(benchmark::State& state, const std::string& variant, int particles) {
  const datasets::Scenario& scenario = PaperScenario();
  filters::PhdSlamParams params;
  params.particles = particles;
  const auto filter = filters::MakePhdSlam(variant, scenario.PublicContext(), params,
                                           DeriveSeed(HashName(variant), 1));
  std::size_t k = 0;
  for (; k < kWarmupSteps; ++k) filter->Step(scenario.steps[k].data);
  double components = 0.0;
  double hypotheses = 0.0;
  int resampled = 0;
  for (auto _ : state) {
    const filters::StepOutput out = filter->Step(scenario.steps[k++].data);
    components += out.diag.map_components;
    hypotheses += out.diag.hypotheses;
    resampled += out.diag.resampled ? 1 : 0;
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["map_components"] = components / n;
  state.counters["hypotheses"] = hypotheses / n;
  state.counters["resampled_pct"] = 100.0 * resampled / n;
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
