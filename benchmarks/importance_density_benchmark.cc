// Cost of one importance-density Build() against the number of landmarks in the field of view,
// for PHD-SLAM 1.0, 2.0a, 2.0b (with and without its innovation guard) and 3.0 (the paper claims
// O(M^3) for 2.0b's joint IPL against O(M) for 3.0's partitioned IPL, 173.4 us vs 14.0 us per
// particle and component).
//
// Workload, per M in {5, 10, 20, 40, 70, 100}: a generated scenario with about M landmarks in
// view (datasets::OptionsForLandmarksInView(M, ...), seed 1) is filtered by PHD-SLAM 3.0 with one
// particle for kWarmupSteps steps, so that the map is the filter's own (converged landmarks,
// fresh births, clutter components). The next kStoredStates steps are recorded as (map with the
// step's births added, predicted pose mean and covariance, scan): exactly the input Build() gets
// inside RbPhdSlam::Step. Each benchmark iteration calls Build() on the next stored state in turn,
// so a timing is the mean over these states.
//
// Reported, per density and M: CPU time per call (= per particle, one proposal per particle), the
// mean number of associated components (detections in the best association, the same count for
// every density) and the time per associated component; also the mean number of proposal
// mixture components (3.0's hypotheses plus the all-clutter one; 1 otherwise) and the time per
// mixture component, the other reading of the paper's "per particle and component". A final table
// gives the fitted log-log exponent b of time ~ M^b (least squares over the M values, against the
// nominal M and against the mean associated count, and the slope between the two largest M, where
// the leading term dominates); the table is also written as CSV to --scaling_csv=<path> (default
// importance_density_scaling.csv in the working directory). The columns `estimator`,
// `landmarks_in_fov` and `us_per_call` are those the report's scaling section reads: write it as
// `--scaling_csv=RESULTS_DIR/scaling.csv` to have it drawn.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "datasets/scenario_generator.h"
#include "src/core/gaussian.h"
#include "src/core/malloc_name.h"
#include "src/core/random.h"
#include "src/filters/phd2b_density.h"
#include "src/filters/phd_slam_family.h"

namespace phdslam::benchmarks {
namespace {

constexpr int kWarmupSteps = 100;
constexpr int kStoredStates = 20;
/// The generated path runs on past the stored states, so the landmark corridor covers the whole
/// field of view ahead of the vehicle (a path ending at the last stored state would leave the
/// sector ahead of it nearly empty).
constexpr int kPathBeyondStoredStates = 200;
constexpr int kLandmarksInView[] = {5, 10, 20, 40, 70, 100};
/// The family members, plus 2.0b without the predecessor's innovation guard (the joint IPL as
/// the paper describes it, always running until convergence or L iterations).
const char* const kDensities[] = {"phd1", "phd2a", "phd2b", "phd2b-unguarded", "phd3"};

std::unique_ptr<filters::ImportanceDensity> MakeDensity(const std::string& name,
                                                        const filters::PhdSlamParams& params) {
  if (name == "phd2b-unguarded") return std::make_unique<filters::JointIplDensity>(params, 0.0);
  return filters::MakeImportanceDensity(name, params);
}

struct StoredState {
  Pose predicted_mean;
  Mat3 predicted_cov;
  phd::GmPhdMap map;
  std::vector<Measurement> measurements;
};

struct Workload {
  int landmarks_in_view = 0;
  models::SensorModel sensor;
  std::vector<StoredState> states;
  double mean_active = 0.0;      ///< active components per state
  double mean_associated = 0.0;  ///< detections in the best association per state
};

/// The particle's state as RbPhdSlam::Step hands it to Build(): births at the previous pose,
/// then the pose regularisation and the EKF propagation over the step's sub-intervals.
StoredState PredictParticle(const filters::PhdParticle& particle, const datasets::StepData& step,
                            const filters::EstimatorContext& context,
                            const filters::PhdSlamParams& params) {
  StoredState s{particle.pose, particle.cov, particle.map.gm, step.measurements};
  if (!particle.map.births.empty()) {
    s.map.AddBirths(particle.pose, particle.map.births, context.sensor.noise_cov, params.map);
  }
  if (step.times.size() < 2) return s;
  s.predicted_cov += params.pose_regularisation;
  for (std::size_t i = 0; i + 1 < step.times.size(); ++i) {
    const double dt = step.times[i + 1] - step.times[i];
    const auto j = context.motion->Jacobians(s.predicted_mean, step.controls[i], dt);
    s.predicted_mean = context.motion->Predict(s.predicted_mean, step.controls[i], dt);
    s.predicted_cov = j.fx * s.predicted_cov * j.fx.transpose() +
                      j.fu * context.control_noise_cov * j.fu.transpose();
    Symmetrize(s.predicted_cov);
  }
  return s;
}

Workload MakeWorkload(int landmarks_in_view, const filters::PhdSlamParams& base_params) {
  const datasets::GeneratorOptions options = datasets::OptionsForLandmarksInView(
      landmarks_in_view, kWarmupSteps + kStoredStates + kPathBeyondStoredStates);
  const datasets::Scenario scenario = datasets::GenerateScenario(options, 1);
  const filters::EstimatorContext context = scenario.PublicContext();
  filters::PhdSlamParams params = base_params;
  params.particles = 1;
  const auto filter = filters::MakePhdSlam("phd3", context, params,
                                           DeriveSeed(HashName("importance-density-benchmark"), 1));
  Workload w;
  w.landmarks_in_view = landmarks_in_view;
  w.sensor = context.sensor;
  for (int k = 0; k < kWarmupSteps + kStoredStates; ++k) {
    const datasets::StepData& step = scenario.steps[k].data;
    if (k >= kWarmupSteps) {
      w.states.push_back(PredictParticle(filter->particles()[0], step, context, params));
    }
    filter->Step(step);
  }
  const auto joint = filters::MakeImportanceDensity("phd2b", params);
  for (const StoredState& s : w.states) {
    const filters::ProposalOutput out = joint->Build(
        {s.predicted_mean, s.predicted_cov, s.map.active(), s.measurements, &w.sensor, {}});
    for (int c : out.best_association) w.mean_associated += c >= 0 ? 1.0 : 0.0;
    w.mean_active += static_cast<double>(s.map.active().size());
  }
  w.mean_associated /= static_cast<double>(w.states.size());
  w.mean_active /= static_cast<double>(w.states.size());
  return w;
}

void BenchmarkBuild(benchmark::State& state, const Workload* workload,
                    const filters::ImportanceDensity* density) {
  std::size_t next = 0;
  for (auto _ : state) {
    const StoredState& s = workload->states[next];
    next = (next + 1) % workload->states.size();
    filters::ProposalOutput out = density->Build(
        {s.predicted_mean, s.predicted_cov, s.map.active(), s.measurements, &workload->sensor, {}});
    benchmark::DoNotOptimize(out);
  }
  state.counters["associated"] = workload->mean_associated;
  state.counters["active"] = workload->mean_active;
}

/// Mean number of Gaussian components of the proposal over the stored states (1 for 1.0, 2.0a
/// and 2.0b; the hypotheses plus the all-clutter component for 3.0).
double MeanMixtureSize(const Workload& workload, const filters::ImportanceDensity& density) {
  double total = 0.0;
  for (const StoredState& s : workload.states) {
    total += static_cast<double>(density
                                     .Build({s.predicted_mean,
                                             s.predicted_cov,
                                             s.map.active(),
                                             s.measurements,
                                             &workload.sensor,
                                             {}})
                                     .mixture.size());
  }
  return total / static_cast<double>(workload.states.size());
}

/// Keeps the per-iteration CPU time of every run while printing as the console reporter does.
/// CPU time, not wall time: Build() is single-threaded, and on a shared machine the wall time
/// also counts the time the process waits for a core.
class CollectingReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& reports) override {
    ConsoleReporter::ReportRuns(reports);
    for (const Run& run : reports) {
      if (run.run_type != Run::RT_Iteration || run.error_occurred) continue;
      const double seconds =
          run.GetAdjustedCPUTime() / benchmark::GetTimeUnitMultiplier(run.time_unit);
      auto& entry = seconds_[run.run_name.function_name];
      entry.first += seconds;
      entry.second += 1;
    }
  }
  /// Mean seconds per iteration of the named benchmark, or NaN when it did not run.
  [[nodiscard]] double MeanSeconds(const std::string& name) const {
    const auto it = seconds_.find(name);
    if (it == seconds_.end()) return std::nan("");
    return it->second.first / it->second.second;
  }

 private:
  std::map<std::string, std::pair<double, int>> seconds_;
};

/// Least-squares slope of log(y) against log(x) over the finite pairs; NaN with fewer than two.
double LogLogSlope(const std::vector<double>& x, const std::vector<double>& y) {
  double sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
  int n = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!(x[i] > 0.0) || !(y[i] > 0.0) || !std::isfinite(y[i])) continue;
    const double lx = std::log(x[i]);
    const double ly = std::log(y[i]);
    sx += lx;
    sy += ly;
    sxx += lx * lx;
    sxy += lx * ly;
    ++n;
  }
  if (n < 2) return std::nan("");
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

std::string BenchmarkName(const std::string& density, int m) {
  return "Build/" + density + "/M:" + std::to_string(m);
}

void PrintAndWriteScaling(const CollectingReporter& reporter,
                          const std::vector<std::unique_ptr<Workload>>& workloads,
                          const std::map<std::string, double>& mixture_sizes,
                          const std::string& csv_path) {
  std::ofstream csv(csv_path);
  if (!csv) throw std::runtime_error("cannot write the scaling CSV '" + csv_path + "'");
  csv << "estimator,landmarks_in_fov,mean_active,mean_associated,mean_mixture_components,"
         "us_per_call,us_per_associated_component,us_per_mixture_component\n";
  std::printf("\n%-15s %5s %7s %10s %8s %11s %13s %13s\n", "density", "M", "active", "associated",
              "mixture", "us/call", "us/assoc.comp", "us/mix.comp");
  std::vector<std::string> fits;
  for (const char* density : kDensities) {
    std::vector<double> nominal, associated, seconds;
    for (const auto& w : workloads) {
      const double s = reporter.MeanSeconds(BenchmarkName(density, w->landmarks_in_view));
      if (std::isnan(s)) continue;
      nominal.push_back(w->landmarks_in_view);
      associated.push_back(w->mean_associated);
      seconds.push_back(s);
      const double us = 1e6 * s;
      const double mixture = mixture_sizes.at(BenchmarkName(density, w->landmarks_in_view));
      std::printf("%-15s %5d %7.1f %10.1f %8.1f %11.2f %13.3f %13.3f\n", density,
                  w->landmarks_in_view, w->mean_active, w->mean_associated, mixture, us,
                  us / w->mean_associated, us / mixture);
      csv << density << ',' << w->landmarks_in_view << ',' << w->mean_active << ','
          << w->mean_associated << ',' << mixture << ',' << us << ',' << us / w->mean_associated
          << ',' << us / mixture << '\n';
    }
    if (seconds.size() < 2) continue;
    const std::size_t last = seconds.size() - 1;
    const std::vector<double> tail_x = {associated[last - 1], associated[last]};
    const std::vector<double> tail_y = {seconds[last - 1], seconds[last]};
    char line[200];
    std::snprintf(line, sizeof(line),
                  "%-15s exponent b (time ~ M^b): %.2f vs nominal M, %.2f vs associated count; "
                  "%.2f between the two largest M",
                  density, LogLogSlope(nominal, seconds), LogLogSlope(associated, seconds),
                  LogLogSlope(tail_x, tail_y));
    fits.emplace_back(line);
    csv << "# " << line << '\n';
  }
  std::printf("\nFitted log-log exponents over M = 5..100 (paper: 2.0b O(M^3), 3.0 O(M)):\n");
  for (const std::string& f : fits) std::printf("  %s\n", f.c_str());
  std::printf("Scaling table written to %s\n", csv_path.c_str());
}

}  // namespace
}  // namespace phdslam::benchmarks

int RunBenchmarks(int argc, char** argv) {
  using namespace phdslam;
  using namespace phdslam::benchmarks;
  // Our own flag, removed before Google Benchmark parses the rest.
  std::string csv_path = "importance_density_scaling.csv";
  const std::string flag = "--scaling_csv=";
  int kept = 1;
  for (int i = 1; i < argc; ++i) {
    if (std::strncmp(argv[i], flag.c_str(), flag.size()) == 0) {
      csv_path = argv[i] + flag.size();
    } else {
      argv[kept++] = argv[i];
    }
  }
  argc = kept;
  benchmark::Initialize(&argc, argv);
  benchmark::AddCustomContext("malloc", phdslam::MallocName());
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;

  const filters::PhdSlamParams params;
  std::vector<std::unique_ptr<Workload>> workloads;
  std::vector<std::unique_ptr<filters::ImportanceDensity>> densities;
  std::map<std::string, double> mixture_sizes;
  for (int m : kLandmarksInView) {
    workloads.push_back(std::make_unique<Workload>(MakeWorkload(m, params)));
  }
  for (const char* name : kDensities) {
    densities.push_back(MakeDensity(name, params));
    for (const auto& w : workloads) {
      mixture_sizes[BenchmarkName(name, w->landmarks_in_view)] =
          MeanMixtureSize(*w, *densities.back());
      benchmark::RegisterBenchmark(BenchmarkName(name, w->landmarks_in_view).c_str(),
                                   BenchmarkBuild, w.get(), densities.back().get())
          ->Unit(benchmark::kMicrosecond);
    }
  }
  CollectingReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  PrintAndWriteScaling(reporter, workloads, mixture_sizes, csv_path);
  benchmark::Shutdown();
  return 0;
}

int main(int argc, char** argv) {
  try {
    return RunBenchmarks(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "importance_density_benchmark: %s\n", e.what());
    return 1;
  } catch (...) {
    std::fprintf(stderr, "importance_density_benchmark: an unexpected exception\n");
    return 1;
  }
}
