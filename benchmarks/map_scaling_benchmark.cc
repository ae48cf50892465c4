// Time per step and map memory of PHD-SLAM 3.0 against the size of the map, at a fixed landmark
// density and field of view.
//
// Scenarios: `generated` scenarios (datasets/scenario_generator.h, seed 1) with the paper's sensor
// and kLandmarksInView landmarks in the field of view on average, whose path is made long enough
// for 10^2, 10^3, 10^4 or 10^5 landmarks at that density (corridor half-width = FOV range, so the
// corridor area is about 2 w L + pi w^2 for a path of length L). Only the first
// kWarmupSteps + kTimedSteps steps are simulated (GenerateScenarioPrefix).
//
// Method: every particle starts with the whole true map as its GM-PHD map (one passive component
// per landmark at its true position, covariance 1 m^2 I, weight 1, in the Z order of 50 m cells),
// as a filter that has already mapped the whole path would hold; so the map the step works on has
// the full size from the first step. The filter runs kWarmupSteps steps untimed, then kTimedSteps
// consecutive steps, one per benchmark iteration.
//
// Counters: ms_per_step, the thread CPU time per timed step (immune to waiting for a core on a
// shared machine); map_bytes, the heap bytes held by all particles' maps after the last step,
// storage shared between particles counted once (ByteTally); map_components, the best particle's
// components. --csv=FILE also writes one row per case: landmarks,particles,ms_per_step,map_bytes.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <ctime>
#include <fstream>
#include <iostream>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "datasets/scenario_generator.h"
#include "src/core/byte_tally.h"
#include "src/core/malloc_name.h"
#include "src/core/random.h"
#include "src/filters/phd_slam_family.h"

namespace phdslam::benchmarks {
namespace {

constexpr int kWarmupSteps = 20;
constexpr int kTimedSteps = 40;
constexpr double kLandmarksInView = 20.0;

struct CaseResult {
  int landmarks = 0;
  int particles = 0;
  double ms_per_step = 0.0;
  std::size_t map_bytes = 0;
};

double ThreadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

/// Generator options whose corridor holds `landmarks` landmarks at the density that puts
/// kLandmarksInView of them in the field of view.
datasets::GeneratorOptions OptionsFor(int landmarks) {
  datasets::GeneratorOptions o;
  o.corridor_half_width = o.fov_range;
  o.landmarks = landmarks;
  const double w = o.corridor_half_width;
  const double density = kLandmarksInView / (o.fov_half_angle * o.fov_range * o.fov_range);
  const double length = (landmarks / density - std::numbers::pi * w * w) / (2.0 * w);
  o.steps = std::max(kWarmupSteps + kTimedSteps + 1,
                     static_cast<int>(std::ceil(length / (o.speed * o.dt))));
  return o;
}

class ScenarioCache {
 public:
  const datasets::Scenario& Get(int landmarks) {
    auto it = scenarios_.find(landmarks);
    if (it == scenarios_.end()) {
      it = scenarios_
               .emplace(landmarks, datasets::GenerateScenarioPrefix(OptionsFor(landmarks), 1,
                                                                    kWarmupSteps + kTimedSteps))
               .first;
    }
    return it->second;
  }

 private:
  std::map<int, datasets::Scenario> scenarios_;
};

/// Position of the cell of `m` (kMortonCell m cells) on the Z-order curve (bits interleaved).
std::uint64_t MortonKey(const Landmark& m) {
  constexpr double kMortonCell = 50.0;
  constexpr double kOffset = 1 << 20;  // cells; keeps the indices non-negative
  const auto spread = [](std::uint64_t v) {
    std::uint64_t out = 0;
    for (int b = 0; b < 32; ++b) out |= ((v >> b) & 1U) << (2 * b);
    return out;
  };
  const auto ix = static_cast<std::uint64_t>(std::floor(m(0) / kMortonCell) + kOffset);
  const auto iy = static_cast<std::uint64_t>(std::floor(m(1) / kMortonCell) + kOffset);
  return spread(ix) | (spread(iy) << 1);
}

/// The true map as passive components in Z order (spatially coherent, as the order in which a
/// filter passing them would have left them behind).
filters::PhdParticleMap TrueMap(const datasets::Scenario& scenario) {
  std::vector<Landmark> landmarks = scenario.truth.landmarks;
  std::stable_sort(landmarks.begin(), landmarks.end(), [](const Landmark& a, const Landmark& b) {
    return MortonKey(a) < MortonKey(b);
  });
  std::vector<phd::GaussianComponent> components;
  components.reserve(landmarks.size());
  for (const Landmark& m : landmarks) components.push_back({m, Mat2::Identity(), 0.0});
  filters::PhdParticleMap map;
  map.gm.SetPassive(std::move(components));
  return map;
}

CaseResult RunCase(benchmark::State& state, const datasets::Scenario& scenario, int particles) {
  filters::PhdSlamParams params;
  params.particles = particles;
  const auto filter = filters::MakePhdSlam("phd3", scenario.PublicContext(), params,
                                           DeriveSeed(HashName("phd3"), 1));
  filter->ResetMaps(TrueMap(scenario));
  std::size_t k = 0;
  for (; k < kWarmupSteps; ++k) filter->Step(scenario.steps[k].data);
  double cpu = 0.0;
  double components = 0.0;
  for (auto _ : state) {
    const double t0 = ThreadCpuSeconds();
    const filters::StepOutput out = filter->Step(scenario.steps[k++].data);
    cpu += ThreadCpuSeconds() - t0;
    components += out.diag.map_components;
  }
  ByteTally tally;
  for (const auto& p : filter->particles()) p.map.CountBytes(tally);
  const double n = static_cast<double>(state.iterations());
  CaseResult r{static_cast<int>(scenario.truth.landmarks.size()), particles, 1e3 * cpu / n,
               tally.bytes()};
  state.counters["ms_per_step"] = r.ms_per_step;
  state.counters["map_bytes"] = static_cast<double>(r.map_bytes);
  state.counters["map_components"] = components / n;
  return r;
}

/// Removes --csv=FILE from the arguments and returns FILE (empty when absent).
std::string TakeCsvFlag(int& argc, char** argv) {
  std::string file;
  int out = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.starts_with("--csv=")) {
      file = arg.substr(6);
    } else {
      argv[out++] = argv[i];
    }
  }
  argc = out;
  return file;
}

}  // namespace
}  // namespace phdslam::benchmarks

int main(int argc, char** argv) {
  using namespace phdslam::benchmarks;
  const std::string csv = TakeCsvFlag(argc, argv);
  benchmark::Initialize(&argc, argv);
  benchmark::AddCustomContext("malloc", phdslam::MallocName());
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  ScenarioCache cache;
  std::vector<CaseResult> results;
  const auto add = [&](int landmarks, int particles) {
    const std::string name =
        "MapScaling/landmarks:" + std::to_string(landmarks) + "/N:" + std::to_string(particles);
    benchmark::RegisterBenchmark(name.c_str(),
                                 [&cache, &results, landmarks, particles](benchmark::State& s) {
                                   results.push_back(RunCase(s, cache.Get(landmarks), particles));
                                 })
        ->Iterations(kTimedSteps)
        ->Unit(benchmark::kMillisecond);
  };
  for (const int landmarks : {100, 1000, 10000, 100000}) {
    for (const int particles : {1, 10, 100}) add(landmarks, particles);
  }
  add(100, 1000);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  if (!csv.empty()) {
    std::ofstream f(csv);
    if (!f) {
      std::cerr << "map_scaling_benchmark: cannot write --csv file " << csv << "\n";
      return 1;
    }
    f << "landmarks,particles,ms_per_step,map_bytes\n";
    for (const CaseResult& r : results) {
      f << r.landmarks << ',' << r.particles << ',' << r.ms_per_step << ',' << r.map_bytes << '\n';
    }
  }
  return 0;
}
