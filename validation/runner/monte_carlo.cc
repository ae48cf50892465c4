#include "validation/runner/monte_carlo.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <map>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <utility>

#include "validation/runner/parameter_overrides.h"
#include "validation/runner/progress_line.h"
#include "validation/runner/results_io.h"
#include "validation/runner/results_layout.h"
#include "validation/runner/run_estimator.h"
#include "validation/runner/run_files.h"

namespace phdslam::validation {
namespace {

constexpr const char* kSeedDerivation =
    "scenario: generated from the Monte Carlo seed itself; estimator stream seed = "
    "DeriveSeed(HashName(experiment), seed, DeriveSeed(HashName(estimator), particles))";

struct Job {
  std::size_t estimator = 0;  ///< index into plan.estimators
  int particles = 1;
  std::uint64_t seed = 0;
};

using ParameterKey = std::pair<std::string, int>;

nlohmann::json WithoutDataDir(nlohmann::json options) {
  if (options.is_object()) options.erase("data_dir");
  return options;
}

// The first path at which a and b differ ("" when equal), for error messages.
std::string FirstDifference(const nlohmann::json& a, const nlohmann::json& b,
                            const std::string& path) {
  if (a == b) return "";
  if (a.is_object() && b.is_object()) {
    std::set<std::string> keys;
    for (const auto& [key, value] : a.items()) keys.insert(key);
    for (const auto& [key, value] : b.items()) keys.insert(key);
    for (const std::string& key : keys) {
      const std::string sub = path.empty() ? key : path + "." + key;
      if (!a.contains(key)) return sub + " (absent before, now " + b.at(key).dump() + ")";
      if (!b.contains(key)) return sub + " (was " + a.at(key).dump() + ", now absent)";
      const std::string d = FirstDifference(a.at(key), b.at(key), sub);
      if (!d.empty()) return d;
    }
  }
  return (path.empty() ? std::string("value") : path) + " (was " + a.dump() + ", now " + b.dump() +
         ")";
}

void ValidatePlan(const MonteCarloPlan& plan) {
  if (plan.experiment.empty()) throw std::invalid_argument("experiment name is empty");
  if (!plan.scenario.make) throw std::invalid_argument("no scenario given");
  if (plan.estimators.empty()) throw std::invalid_argument("no estimator given");
  if (plan.particles.empty()) throw std::invalid_argument("no particle count given");
  if (plan.seeds.empty()) throw std::invalid_argument("no seed given");
  std::set<std::string> names;
  for (const EstimatorSelection& s : plan.estimators) {
    if (!names.insert(s.entry.name).second) {
      throw std::invalid_argument("estimator '" + s.entry.name + "' is listed twice");
    }
    if (s.entry.batch ? !s.entry.make_batch : !s.entry.make_online) {
      throw std::invalid_argument("estimator '" + s.entry.name + "' has no factory");
    }
  }
  for (int n : plan.particles) {
    if (n < 1) throw std::invalid_argument("particle count " + std::to_string(n) + " is < 1");
  }
  if (std::set<int>(plan.particles.begin(), plan.particles.end()).size() != plan.particles.size()) {
    throw std::invalid_argument("a particle count is listed twice");
  }
  if (std::set<std::uint64_t>(plan.seeds.begin(), plan.seeds.end()).size() != plan.seeds.size()) {
    throw std::invalid_argument("a seed is listed twice");
  }
}

std::map<ParameterKey, nlohmann::json> ResolveParameters(const MonteCarloPlan& plan) {
  std::map<ParameterKey, nlohmann::json> params;
  for (const EstimatorSelection& s : plan.estimators) {
    for (int n : plan.particles) {
      EstimatorRequest request;
      request.name = s.entry.name;
      request.particles = n;
      request.overrides = s.overrides;
      request.scenario_name = plan.scenario.name;
      params[{s.entry.name, n}] = s.entry.resolved_parameters
                                      ? s.entry.resolved_parameters(request)
                                      : ApplyOverrides(nlohmann::json::object(), s.overrides,
                                                       "estimator '" + s.entry.name + "'");
    }
  }
  return params;
}

nlohmann::json MetricSettingsJson(const MetricSettings& m) {
  return {{"gospa_c", m.gospa_c}, {"gospa_p", m.gospa_p}, {"gps_window_s", m.gps_window_s}};
}

nlohmann::json BuildConfig(const MonteCarloPlan& plan,
                           const std::map<ParameterKey, nlohmann::json>& params,
                           const MonteCarloSettings& settings, int jobs) {
  nlohmann::json estimators = nlohmann::json::object();
  for (const EstimatorSelection& s : plan.estimators) {
    nlohmann::json by_particles = nlohmann::json::object();
    for (int n : plan.particles) by_particles[std::to_string(n)] = params.at({s.entry.name, n});
    estimators[s.entry.name] = {{"description", s.entry.description},
                                {"batch", s.entry.batch},
                                {"overrides", s.overrides},
                                {"parameters", by_particles}};
  }
  std::vector<std::uint64_t> seeds = plan.seeds;
  std::sort(seeds.begin(), seeds.end());
  std::vector<int> particles = plan.particles;
  std::sort(particles.begin(), particles.end());
  return {{"program", {{"name", "phdslam"}, {"version", ProgramVersion()}}},
          {"experiment", plan.experiment},
          {"scenario", {{"name", plan.scenario.name}, {"options", plan.scenario.options}}},
          {"seeds", seeds},
          {"particles", particles},
          {"estimators", estimators},
          {"metrics", MetricSettingsJson(settings.metrics)},
          {"seed_derivation", kSeedDerivation},
          {"jobs", jobs}};
}

[[noreturn]] void ThrowIncompatible(const std::filesystem::path& out, const std::string& what) {
  throw std::invalid_argument(out.string() + " holds results made with other settings: " + what +
                              "; use another --out or remove it");
}

// Checks that `fresh` may add runs to the results described by `existing` and returns the
// merged config (union of seeds, particle counts and estimators).
nlohmann::json MergeConfig(const std::filesystem::path& out, const nlohmann::json& existing,
                           const nlohmann::json& fresh) {
  try {
    if (existing.at("experiment") != fresh.at("experiment")) {
      ThrowIncompatible(out, "experiment " + existing.at("experiment").dump() + ", now " +
                                 fresh.at("experiment").dump());
    }
    const nlohmann::json& old_scenario = existing.at("scenario");
    const nlohmann::json& new_scenario = fresh.at("scenario");
    if (old_scenario.at("name") != new_scenario.at("name")) {
      ThrowIncompatible(out, "scenario " + old_scenario.at("name").dump() + ", now " +
                                 new_scenario.at("name").dump());
    }
    const std::string scenario_diff =
        FirstDifference(WithoutDataDir(old_scenario.at("options")),
                        WithoutDataDir(new_scenario.at("options")), "scenario option");
    if (!scenario_diff.empty()) ThrowIncompatible(out, scenario_diff);
    const std::string metrics_diff =
        FirstDifference(existing.at("metrics"), fresh.at("metrics"), "metric setting");
    if (!metrics_diff.empty()) ThrowIncompatible(out, metrics_diff);

    nlohmann::json merged = fresh;
    merged["estimators"] = existing.at("estimators");
    for (const auto& [name, entry] : fresh.at("estimators").items()) {
      if (!merged["estimators"].contains(name)) {
        merged["estimators"][name] = entry;
        continue;
      }
      nlohmann::json& old_entry = merged["estimators"][name];
      for (const auto& [n, parameters] : entry.at("parameters").items()) {
        if (old_entry.at("parameters").contains(n)) {
          const std::string d = FirstDifference(old_entry["parameters"][n], parameters,
                                                name + " N=" + n + " parameter");
          if (!d.empty()) ThrowIncompatible(out, d);
        }
        old_entry["parameters"][n] = parameters;
      }
      old_entry["overrides"] = entry.at("overrides");
      old_entry["description"] = entry.at("description");
    }
    std::set<std::uint64_t> seeds = existing.at("seeds").get<std::set<std::uint64_t>>();
    for (std::uint64_t s : fresh.at("seeds")) seeds.insert(s);
    merged["seeds"] = seeds;
    std::set<int> particles = existing.at("particles").get<std::set<int>>();
    for (int n : fresh.at("particles")) particles.insert(n);
    merged["particles"] = particles;
    return merged;
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error((out / kConfigFile).string() + ": unexpected content (" + e.what() +
                             ")");
  }
}

nlohmann::json ReadJson(const std::filesystem::path& path) {
  nlohmann::json j = nlohmann::json::parse(ReadTextFile(path), nullptr, false);
  if (j.is_discarded() || !j.is_object()) {
    throw std::runtime_error(path.string() + ": not a JSON object");
  }
  return j;
}

// True when the run folder holds a finished run with this identity; throws when it holds a
// finished run made with other settings.
bool IsFinished(const std::filesystem::path& folder, const nlohmann::json& identity) {
  const std::filesystem::path path = folder / kMetricsFile;
  if (!std::filesystem::exists(path)) return false;
  const nlohmann::json stored = ReadJson(path);
  for (const char* key : {"estimator", "particles", "seed", "stream_seed", "experiment", "scenario",
                          "scenario_options", "parameters"}) {
    const nlohmann::json a = stored.contains(key) ? stored.at(key) : nlohmann::json();
    const nlohmann::json& b = identity.at(key);
    const bool same =
        std::string(key) == "scenario_options" ? WithoutDataDir(a) == WithoutDataDir(b) : a == b;
    if (!same) {
      throw std::invalid_argument(path.string() +
                                  " was made with other settings: " + FirstDifference(a, b, key) +
                                  "; use another --out or delete that run");
    }
  }
  return true;
}

std::string UtcNow() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  gmtime_r(&now, &utc);
  char buffer[32];
  std::strftime(buffer, sizeof(buffer), "%Y-%m-%dT%H:%M:%SZ", &utc);
  return buffer;
}

std::string HostName() {
  char buffer[256] = {};
  if (gethostname(buffer, sizeof(buffer) - 1) != 0) return "";
  return buffer;
}

}  // namespace

std::string ProgramVersion() { return PHDSLAM_VERSION; }

MonteCarloReport RunMonteCarlo(const MonteCarloPlan& plan, const MonteCarloSettings& settings) {
  const auto start = std::chrono::steady_clock::now();
  const std::string started_utc = UtcNow();
  ValidatePlan(plan);
  if (settings.out.empty()) throw std::invalid_argument("no output folder given");
  const std::map<ParameterKey, nlohmann::json> params = ResolveParameters(plan);

  // Jobs, seed by seed; identities; which are finished already.
  std::vector<Job> todo;
  std::vector<nlohmann::json> identities;
  MonteCarloReport report;
  for (std::uint64_t seed : plan.seeds) {
    for (std::size_t e = 0; e < plan.estimators.size(); ++e) {
      for (int n : plan.particles) {
        const std::string& name = plan.estimators[e].entry.name;
        nlohmann::json identity = {{"estimator", name},
                                   {"particles", n},
                                   {"seed", seed},
                                   {"stream_seed", RunStreamSeed(plan.experiment, seed, name, n)},
                                   {"experiment", plan.experiment},
                                   {"scenario", plan.scenario.name},
                                   {"scenario_options", plan.scenario.options},
                                   {"parameters", params.at({name, n})},
                                   {"program_version", ProgramVersion()}};
        ++report.planned;
        if (IsFinished(RunFolder(settings.out, name, n, seed), identity)) {
          ++report.skipped;
          continue;
        }
        todo.push_back({e, n, seed});
        identities.push_back(std::move(identity));
      }
    }
  }

  unsigned hardware = std::thread::hardware_concurrency();
  if (hardware == 0) hardware = 1;
  int jobs = settings.jobs > 0 ? settings.jobs : static_cast<int>(hardware);
  jobs = std::max(1, std::min(jobs, static_cast<int>(std::max<std::size_t>(todo.size(), 1))));
  report.jobs = jobs;

  // config.json, merged with what the folder already holds.
  std::filesystem::create_directories(settings.out);
  nlohmann::json config = BuildConfig(plan, params, settings, jobs);
  if (const auto path = settings.out / kConfigFile; std::filesystem::exists(path)) {
    config = MergeConfig(settings.out, ReadJson(path), config);
  }
  WriteFileAtomically(settings.out / kConfigFile, config.dump(2) + "\n");

  ProgressLine progress(todo.size(), settings.show_progress);
  std::atomic<std::size_t> next{0};
  std::mutex results_mutex;  // guards report.finished and report.failures
  const auto run_job = [&](std::size_t i) {
    const Job& job = todo[i];
    const EstimatorSelection& selection = plan.estimators[job.estimator];
    const nlohmann::json& identity = identities[i];
    const std::filesystem::path folder =
        RunFolder(settings.out, selection.entry.name, job.particles, job.seed);
    try {
      const datasets::Scenario scenario = plan.scenario.make(job.seed);
      progress.RunStarted(scenario.steps.size());
      WriteTruthFiles(settings.out, scenario, std::to_string(i));
      EstimatorRequest request;
      request.name = selection.entry.name;
      request.particles = job.particles;
      request.stream_seed = identity.at("stream_seed").get<std::uint64_t>();
      request.scenario = &scenario;
      request.scenario_name = plan.scenario.name;
      request.overrides = selection.overrides;
      const RunRecord record = RunEstimator(selection.entry, request, scenario,
                                            [&](std::size_t n) { progress.StepsDone(n); });
      const RunEvaluation evaluation = EvaluateRun(record, scenario, settings.metrics);
      WriteRunFiles(folder, record, scenario, evaluation, identity);
      progress.RunFinished(false);
      const std::lock_guard<std::mutex> lock(results_mutex);
      ++report.finished;
    } catch (const std::exception& e) {
      std::string message = e.what();
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
  const auto worker = [&] {
    while (settings.stop == nullptr || !settings.stop->load()) {
      const std::size_t i = next.fetch_add(1);
      if (i >= todo.size()) return;
      run_job(i);
    }
  };
  std::vector<std::thread> threads;
  for (int t = 1; t < jobs; ++t) threads.emplace_back(worker);
  worker();
  for (std::thread& t : threads) t.join();
  progress.Finish();
  report.interrupted = next.load() < todo.size();
  std::sort(report.failures.begin(), report.failures.end(),
            [](const FailedRun& a, const FailedRun& b) {
              return std::tie(a.estimator, a.particles, a.seed) <
                     std::tie(b.estimator, b.particles, b.seed);
            });

  WriteSummaryFiles(settings.out);
  report.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const nlohmann::json timing = {{"started_utc", started_utc},
                                 {"wall_seconds", report.wall_seconds},
                                 {"jobs", jobs},
                                 {"hardware_concurrency", hardware},
                                 {"host", HostName()},
                                 {"runs_planned", report.planned},
                                 {"runs_skipped", report.skipped},
                                 {"runs_finished", report.finished},
                                 {"runs_failed", report.failures.size()},
                                 {"interrupted", report.interrupted}};
  WriteFileAtomically(settings.out / kTimingFile, timing.dump(2) + "\n");
  return report;
}

}  // namespace phdslam::validation
