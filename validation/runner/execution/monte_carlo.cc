#include "validation/runner/execution/monte_carlo.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <memory>
#include <mutex>
#include <new>
#include <set>
#include <stdexcept>
#include <system_error>
#include <thread>
#include <utility>

#include "src/core/malloc_name.h"
#include "validation/runner/evaluation/map_ospa_trace.h"
#include "validation/runner/execution/out_of_memory_valve.h"
#include "validation/runner/execution/progress_line.h"
#include "validation/runner/execution/run_estimator.h"
#include "validation/runner/execution/seed_scenarios.h"
#include "validation/runner/io/list_arguments.h"
#include "validation/runner/io/results_io.h"
#include "validation/runner/io/results_layout.h"
#include "validation/runner/registry/parameter_overrides.h"
#include "validation/runner/results/results_config.h"
#include "validation/runner/results/results_lock.h"
#include "validation/runner/results/run_files.h"

namespace phdslam::validation {
namespace {

constexpr const char* kSeedDerivation =
    "scenario: generated from the Monte Carlo seed itself; estimator stream seed = "
    "DeriveSeed(HashName(experiment), seed, DeriveSeed(HashName(estimator), particles))";

using ParameterKey = std::pair<std::string, int>;

const std::vector<int>& ParticlesOf(const MonteCarloPlan& plan, const EstimatorSelection& s) {
  return s.particles.empty() ? plan.particles : s.particles;
}

void ValidatePlan(const MonteCarloPlan& plan) {
  if (plan.experiment.empty()) throw std::invalid_argument("experiment name is empty");
  if (!plan.scenario.make) throw std::invalid_argument("no scenario given");
  if (plan.estimators.empty()) throw std::invalid_argument("no estimator given");
  if (plan.seeds.empty()) throw std::invalid_argument("no seed given");
  std::set<std::string> names;
  for (const EstimatorSelection& s : plan.estimators) {
    if (!names.insert(s.entry.name).second) {
      throw std::invalid_argument("estimator '" + s.entry.name + "' is listed twice");
    }
    if (!s.entry.HasFactory()) {
      throw std::invalid_argument("estimator '" + s.entry.name + "' has no factory");
    }
    const std::vector<int>& particles = ParticlesOf(plan, s);
    if (particles.empty()) {
      throw std::invalid_argument("no particle count given for estimator '" + s.entry.name + "'");
    }
    for (int n : particles) {
      if (n < 1) throw std::invalid_argument("particle count " + std::to_string(n) + " is < 1");
    }
    if (std::set<int>(particles.begin(), particles.end()).size() != particles.size()) {
      throw std::invalid_argument("a particle count is listed twice");
    }
  }
  std::uint64_t runs = 0;
  for (const EstimatorSelection& s : plan.estimators) runs += ParticlesOf(plan, s).size();
  if (plan.seeds.size() > kMaxSeeds / runs) {
    throw std::invalid_argument(
        std::to_string(plan.seeds.size()) + " seeds x " + std::to_string(runs) +
        " estimator and particle counts is more than " + std::to_string(kMaxSeeds) +
        " runs in one results folder; split the seeds over several results folders");
  }
  std::vector<std::uint64_t> sorted = plan.seeds;
  std::sort(sorted.begin(), sorted.end());
  if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) {
    throw std::invalid_argument("a seed is listed twice");
  }
}

// The run length the options fix (steps > 0), so that parameters bounded by it are checked with
// the plan; 0 when it is known only once the scenario is built.
std::size_t PlannedSteps(const nlohmann::json& options) {
  const auto steps = options.find("steps");
  if (steps == options.end() || !steps->is_number_integer() || steps->get<std::int64_t>() <= 0) {
    return 0;
  }
  return static_cast<std::size_t>(steps->get<std::int64_t>());
}

// The run's length for the parameters bounded by it: when an estimator has such parameters,
// that of the first seed's scenario (which holds when the data fix the length, steps = 0, or
// are shorter than --steps), else what the options fix (0: not known).
std::size_t RunLengthForChecks(const MonteCarloPlan& plan) {
  const bool needed =
      std::any_of(plan.estimators.begin(), plan.estimators.end(),
                  [](const EstimatorSelection& s) { return s.entry.bounded_by_run_length; });
  if (!needed || plan.seeds.empty() || !plan.scenario.make) {
    return PlannedSteps(plan.scenario.options);
  }
  return plan.scenario.make(plan.seeds.front()).steps.size();
}

std::map<ParameterKey, nlohmann::json> ResolveParameters(const MonteCarloPlan& plan) {
  std::map<ParameterKey, nlohmann::json> params;
  const std::size_t run_steps = RunLengthForChecks(plan);
  for (const EstimatorSelection& s : plan.estimators) {
    for (int n : ParticlesOf(plan, s)) {
      EstimatorRequest request;
      request.name = s.entry.name;
      request.particles = n;
      request.overrides = s.overrides;
      request.scenario_name = plan.scenario.name;
      request.detection_probability = NominalDetectionProbability(plan.scenario.options);
      request.steps = run_steps;
      params[{s.entry.name, n}] = s.entry.resolved_parameters
                                      ? s.entry.resolved_parameters(request)
                                      : ApplyOverrides(nlohmann::json::object(), s.overrides,
                                                       "estimator '" + s.entry.name + "'");
    }
  }
  return params;
}

nlohmann::json MetricSettingsJson(const MetricSettings& m) {
  nlohmann::json j = {
      {"gospa_c", m.gospa_c}, {"gospa_p", m.gospa_p}, {"gps_window_s", m.gps_window_s}};
  // Written only when it is not the default, so folders made before the setting existed keep
  // their config.json and can be resumed; a folder is never resumed with another cut-off.
  if (m.map_ospa_c != kMapOspaCutoff) j["map_ospa_c"] = m.map_ospa_c;
  return j;
}

nlohmann::json BuildConfig(const MonteCarloPlan& plan,
                           const std::map<ParameterKey, nlohmann::json>& params,
                           const MonteCarloSettings& settings, int jobs) {
  nlohmann::json estimators = nlohmann::json::object();
  std::set<int> particles;
  for (const EstimatorSelection& s : plan.estimators) {
    nlohmann::json by_particles = nlohmann::json::object();
    for (int n : ParticlesOf(plan, s)) {
      by_particles[std::to_string(n)] = params.at({s.entry.name, n});
      particles.insert(n);
    }
    estimators[s.entry.name] = {{"description", s.entry.description},
                                {"batch", s.entry.batch},
                                {"overrides", s.overrides},
                                {"parameters", by_particles}};
  }
  std::vector<std::uint64_t> seeds = plan.seeds;
  std::sort(seeds.begin(), seeds.end());
  nlohmann::json config = {
      {"program", {{"name", "phdslam"}, {"version", ProgramVersion()}}},
      {"experiment", plan.experiment},
      {"scenario", {{"name", plan.scenario.name}, {"options", plan.scenario.options}}},
      {"seeds", seeds},
      {"particles", particles},
      {"estimators", estimators},
      {"metrics", MetricSettingsJson(settings.metrics)},
      {"seed_derivation", kSeedDerivation},
      {"jobs", jobs}};
  if (!plan.experiment_file.is_null()) config["experiment_file"] = plan.experiment_file;
  return config;
}

// True when a run folder under <out>/runs holds a metrics.json (a finished run).
bool HoldsFinishedRun(const std::filesystem::path& out) {
  std::error_code ec;
  for (auto it = std::filesystem::recursive_directory_iterator(out / kRunsFolder, ec);
       !ec && it != std::filesystem::recursive_directory_iterator(); it.increment(ec)) {
    if (it.depth() == 2 && it->path().filename() == kMetricsFile) return true;
    if (it.depth() >= 2) it.disable_recursion_pending();
  }
  return false;
}

[[noreturn]] void ThrowIncompatible(const std::filesystem::path& out, const std::string& what) {
  throw std::invalid_argument(out.string() + " holds results made with other settings: " + what +
                              "; use another --out or remove it");
}

// True when the run folder holds a finished run with this identity; throws when it holds a
// finished run made with other settings.
bool IsFinished(const std::filesystem::path& folder, const nlohmann::json& identity) {
  const std::filesystem::path path = folder / kMetricsFile;
  if (!std::filesystem::exists(path)) return false;
  const nlohmann::json stored = ReadJsonObject(path);
  for (const char* key : {"estimator", "particles", "seed", "stream_seed", "experiment", "scenario",
                          "scenario_options", "parameters"}) {
    const nlohmann::json a = stored.contains(key) ? stored.at(key) : nlohmann::json();
    const nlohmann::json& b = identity.at(key);
    // data_dir is not compared (the same data may move), so it is left out of the message too.
    const bool options = std::string(key) == "scenario_options";
    const nlohmann::json stored_value = options ? WithoutDataDir(a) : a;
    const nlohmann::json wanted_value = options ? WithoutDataDir(b) : b;
    if (stored_value != wanted_value) {
      throw std::invalid_argument(path.string() + " was made with other settings: " +
                                  FirstDifference(stored_value, wanted_value, key) +
                                  "; use another --out or delete that run");
    }
  }
  return true;
}

/// Address space held back for out-of-memory handling (out_of_memory_valve.h): 16 x 4 MB.
constexpr std::size_t kOutOfMemoryReserveChunks = 16;
constexpr std::size_t kOutOfMemoryReserveChunkBytes = std::size_t{4} << 20;

// An exception's message; out-of-memory gets words instead of the bare "std::bad_alloc".
std::string DescribeException(const std::exception& e) {
  if (dynamic_cast<const std::bad_alloc*>(&e) != nullptr) {
    return std::string("out of memory (") + e.what() +
           "): fewer particles, a lower clutter rate or fewer --jobs need less";
  }
  return e.what();
}

// The message of the exception being handled (DescribeException for std::exception types).
std::string DescribeCurrentException() {
  try {
    throw;
  } catch (const std::exception& e) {
    return DescribeException(e);
  } catch (...) {
    return "unknown exception";
  }
}

std::string HostName() {
  char buffer[256] = {};
  if (gethostname(buffer, sizeof(buffer) - 1) != 0) return "";
  return buffer;
}

unsigned HardwareThreads() {
  const unsigned hardware = std::thread::hardware_concurrency();
  return hardware == 0 ? 1 : hardware;
}

// What is known before any run starts: the jobs left to compute, the resolved parameters their
// identities are made from (one identity is made when needed, not kept per job: a million jobs
// would hold gigabytes), the counts and the config.json to write.
struct PreparedRuns {
  std::vector<PlannedJob> todo;
  std::map<ParameterKey, nlohmann::json> params;
  bool interrupted = false;  ///< the stop flag was set while planning: todo is incomplete
  MonteCarloReport report;
  nlohmann::json config;
};

// metrics.json's identity fields of one job.
nlohmann::json RunIdentity(const MonteCarloPlan& plan,
                           const std::map<ParameterKey, nlohmann::json>& params,
                           const PlannedJob& job) {
  const std::string& name = plan.estimators[job.estimator].entry.name;
  return {{"estimator", name},
          {"particles", job.particles},
          {"seed", job.seed},
          {"stream_seed", RunStreamSeed(plan.experiment, job.seed, name, job.particles)},
          {"experiment", plan.experiment},
          {"scenario", plan.scenario.name},
          {"scenario_options", plan.scenario.options},
          {"parameters", params.at({name, job.particles})},
          {"program_version", ProgramVersion()}};
}

PreparedRuns Prepare(const MonteCarloPlan& plan, const MonteCarloSettings& settings) {
  ValidatePlan(plan);
  if (settings.out.empty()) throw std::invalid_argument("no output folder given");
  if (settings.shard.count < 1 || settings.shard.index < 1 ||
      settings.shard.index > settings.shard.count) {
    throw std::invalid_argument("shard " + settings.shard.ToString() + " is not i/n with 1<=i<=n");
  }
  PreparedRuns prepared;
  prepared.params = ResolveParameters(plan);
  MonteCarloReport& report = prepared.report;
  const std::vector<PlannedJob> jobs = PlanJobs(plan);
  for (std::size_t j = 0; j < jobs.size(); ++j) {
    if (settings.stop != nullptr && settings.stop->load()) {
      prepared.interrupted = true;  // no run starts; answer Ctrl-C now, not after planning
      break;
    }
    const PlannedJob& job = jobs[j];
    if (!settings.shard.Contains(settings.job_index_offset + j)) {
      ++report.outside_shard;
      continue;
    }
    const std::string& name = plan.estimators[job.estimator].entry.name;
    ++report.planned;
    const std::filesystem::path folder = RunFolder(settings.out, name, job.particles, job.seed);
    if (std::filesystem::exists(folder / kMetricsFile) &&
        IsFinished(folder, RunIdentity(plan, prepared.params, job))) {
      ++report.skipped;
      continue;
    }
    prepared.todo.push_back(job);
  }

  int threads = settings.jobs > 0 ? settings.jobs : static_cast<int>(HardwareThreads());
  threads = std::max(
      1, std::min(threads, static_cast<int>(std::max<std::size_t>(prepared.todo.size(), 1))));
  report.jobs = threads;

  // config.json, merged with what the folder already holds.
  prepared.config = BuildConfig(plan, prepared.params, settings, threads);
  if (const auto path = settings.out / kConfigFile; std::filesystem::exists(path)) {
    const nlohmann::json existing = ReadJsonObject(path);
    const std::string conflict = ConfigConflict(existing, prepared.config, path.string());
    // A folder whose runs all failed before computing anything (a missing data file, a bad
    // option) holds no result its config.json describes: the corrected rerun replaces it.
    const bool computed = HoldsFinishedRun(settings.out);
    if (!conflict.empty() && computed) ThrowIncompatible(settings.out, conflict);
    prepared.config = conflict.empty() ? UnionConfig(existing, prepared.config) : prepared.config;
  }
  return prepared;
}

}  // namespace

std::string ProgramVersion() { return PHDSLAM_VERSION; }

std::vector<PlannedJob> PlanJobs(const MonteCarloPlan& plan) {
  std::vector<PlannedJob> jobs;
  for (std::uint64_t seed : plan.seeds) {
    for (std::size_t e = 0; e < plan.estimators.size(); ++e) {
      for (int n : ParticlesOf(plan, plan.estimators[e])) jobs.push_back({e, n, seed});
    }
  }
  return jobs;
}

void CheckMonteCarlo(const MonteCarloPlan& plan, const MonteCarloSettings& settings) {
  Prepare(plan, settings);
}

MonteCarloReport RunMonteCarlo(const MonteCarloPlan& plan, const MonteCarloSettings& settings) {
  const auto start = std::chrono::steady_clock::now();
  const std::string started_utc = UtcNow();
  PreparedRuns prepared = Prepare(plan, settings);
  const ResultsLock folder_lock(settings.out);
  const std::vector<PlannedJob>& todo = prepared.todo;
  MonteCarloReport report = prepared.report;
  std::filesystem::create_directories(settings.out);
  WriteFileAtomically(settings.out / kConfigFile, JsonFileText(prepared.config));
  // The jobs go seed by seed, so each worker's seed and the next are enough to keep.
  SeedScenarios scenarios(plan.scenario.make,
                          static_cast<std::size_t>(std::max(1, report.jobs)) + 1);
  if (!todo.empty() && !plan.seeds.empty() &&
      !std::filesystem::exists(settings.out / kTruthMapFile)) {
    WriteRootTruthMap(settings.out,
                      *scenarios.Get(*std::min_element(plan.seeds.begin(), plan.seeds.end())));
  }

  ProgressLine progress(todo.size(), settings.show_progress);
  // Out of memory is an orderly stop (out_of_memory_valve.h): no new run starts, the runs in
  // progress finish on the reserve, and the reason is thrown at the end.
  OutOfMemoryValve valve(kOutOfMemoryReserveChunks, kOutOfMemoryReserveChunkBytes);
  if (const std::size_t removed = RemoveLeftoverTemporaries(settings.out); removed > 0) {
    progress.Message("phdslam: removed " + std::to_string(removed) +
                     " temporary file(s) a killed process left in " + settings.out.string());
  }
  std::atomic<std::size_t> next{0};
  std::mutex results_mutex;  // guards report.finished and report.failures
  const auto run_job = [&](std::size_t i) {
    const PlannedJob& job = todo[i];
    const EstimatorSelection& selection = plan.estimators[job.estimator];
    const nlohmann::json identity = RunIdentity(plan, prepared.params, job);
    const std::filesystem::path folder =
        RunFolder(settings.out, selection.entry.name, job.particles, job.seed);
    try {
      const std::shared_ptr<const datasets::Scenario> kept = scenarios.Get(job.seed);
      const datasets::Scenario& scenario = *kept;
      progress.RunStarted(scenario.steps.size());
      WriteTruthFiles(settings.out, scenario, std::to_string(i));
      const filters::EstimatorContext context = scenario.PublicContext();
      EstimatorRequest request;
      request.name = selection.entry.name;
      request.particles = job.particles;
      request.stream_seed = identity.at("stream_seed").get<std::uint64_t>();
      request.context = &context;
      request.steps = scenario.steps.size();
      request.scenario_name = plan.scenario.name;
      request.detection_probability = NominalDetectionProbability(plan.scenario.options);
      request.overrides = selection.overrides;
      const RunRecord record = RunEstimator(
          selection.entry, request, scenario, [&](std::size_t n) { progress.StepsDone(n); },
          settings.particles_trace, settings.map_ospa_trace);
      const RunEvaluation evaluation = EvaluateRun(record, scenario, settings.metrics);
      if (const std::string why = NonFiniteMetrics(evaluation.metrics); !why.empty()) {
        throw std::runtime_error(why);
      }
      WriteRunFiles(folder, record, scenario, evaluation, identity);
      progress.RunFinished(false);
      const std::lock_guard<std::mutex> lock(results_mutex);
      ++report.finished;
    } catch (const std::exception& e) {
      if (dynamic_cast<const std::bad_alloc*>(&e) != nullptr) valve.Trip();
      std::string message = DescribeException(e);
      try {
        WriteRunError(folder, identity, message);
      } catch (const std::exception& write_error) {
        message +=
            " (and error.json could not be written: " + std::string(write_error.what()) + ")";
      }
      progress.RunFinished(true);
      if (settings.report_failures) {
        progress.Message("phdslam: run failed: " + selection.entry.name +
                         " N=" + std::to_string(job.particles) + " seed " +
                         std::to_string(job.seed) + ": " + message);
      }
      const std::lock_guard<std::mutex> lock(results_mutex);
      report.failures.push_back({selection.entry.name, job.particles, job.seed, message});
    }
  };
  // A failure outside a run (out of memory while reporting one, say) stops every worker in order:
  // runs in progress finish, the summary is written, and the reason is thrown at the end. Nothing
  // may escape a worker (that would terminate the program): when even the reason cannot be kept
  // (out of memory again), the flag alone says so.
  std::atomic<bool> aborted{false};
  std::string abort_reason;  // guarded by results_mutex
  const auto worker = [&]() noexcept {
    try {
      while ((settings.stop == nullptr || !settings.stop->load()) && !aborted.load() &&
             !valve.tripped()) {
        const std::size_t i = next.fetch_add(1);
        if (i >= todo.size()) return;
        run_job(i);
      }
    } catch (...) {
      valve.Trip();
      aborted.store(true);
      try {
        const std::lock_guard<std::mutex> lock(results_mutex);
        if (abort_reason.empty()) abort_reason = DescribeCurrentException();
      } catch (...) {  // the flag is set; the reason is given after the join
      }
    }
  };
  std::vector<std::thread> threads;
  threads.reserve(static_cast<std::size_t>(report.jobs));
  // A thread that cannot be created (std::system_error, or std::bad_alloc for its state) leaves
  // the work to those that were; nothing may escape here while threads are running.
  for (int t = 1; t < report.jobs; ++t) {
    try {
      threads.emplace_back(worker);
    } catch (const std::exception& e) {
      try {
        progress.Message("phdslam: could not start worker thread " + std::to_string(t + 1) +
                         " of " + std::to_string(report.jobs) + " (" + e.what() +
                         "); continuing with " + std::to_string(t));
      } catch (const std::exception&) {  // out of memory for the message: go on without it
      }
      report.jobs = t;
      break;
    }
  }
  worker();
  for (std::thread& t : threads) t.join();
  progress.Finish();
  report.interrupted = prepared.interrupted || next.load() < todo.size();
  std::sort(report.failures.begin(), report.failures.end(),
            [](const FailedRun& a, const FailedRun& b) {
              return std::tie(a.estimator, a.particles, a.seed) <
                     std::tie(b.estimator, b.particles, b.seed);
            });

  WriteSummaryFiles(settings.out);
  if (valve.tripped() && !aborted.load()) {
    throw std::runtime_error(
        "memory ran out (a run that failed for it says so in its error.json); no further run "
        "was started. The runs finished so far are kept in " +
        settings.out.string() +
        ": rerun the same command with fewer --jobs (or fewer particles, a lower clutter rate) "
        "to compute the rest");
  }
  if (aborted.load()) {
    throw std::runtime_error(
        (abort_reason.empty() ? std::string("out of memory while reporting a run") : abort_reason) +
        "; the runs finished so far are kept in " + settings.out.string());
  }
  report.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const nlohmann::json timing = {
      {"started_utc", started_utc},
      {"wall_seconds", report.wall_seconds},
      {"jobs", report.jobs},
      {"hardware_concurrency", HardwareThreads()},
      {"host", HostName()},
      {"malloc", MallocName()},
      {"shard", settings.shard.IsWhole() ? nlohmann::json(nullptr)
                                         : nlohmann::json(settings.shard.ToString())},
      {"runs_outside_shard", report.outside_shard},
      {"runs_planned", report.planned},
      {"runs_skipped", report.skipped},
      {"runs_finished", report.finished},
      {"runs_failed", report.failures.size()},
      {"interrupted", report.interrupted}};
  WriteFileAtomically(settings.out / kTimingFile, JsonFileText(timing));
  return report;
}

}  // namespace phdslam::validation
