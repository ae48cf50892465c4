// phdslam: the command line of the PHD-SLAM 3.0 reproduction and validation suite.
//
//   phdslam run       Monte Carlo runs of estimators on a scenario, into a results folder
//   phdslam evaluate  GOSPA/OSPA of a map file, RMSE of a trajectory file
//   phdslam list      the known scenarios and estimators
//
// Exit codes: 0 success, 1 a run or evaluation failed, 2 a usage error, 130 interrupted (Ctrl-C).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "datasets/map_io.h"
#include "datasets/trajectory_io.h"
#include "validation/runner/estimator_registry.h"
#include "validation/runner/interrupt_flag.h"
#include "validation/runner/list_arguments.h"
#include "validation/runner/monte_carlo.h"
#include "validation/runner/offline_evaluation.h"
#include "validation/runner/parameter_overrides.h"
#include "validation/runner/results_layout.h"
#include "validation/runner/scenario_registry.h"
#include "validation/runner/summary.h"

namespace phdslam::apps {
namespace {

namespace v = phdslam::validation;

constexpr int kExitRunFailed = 1;
constexpr int kExitUsage = 2;
constexpr int kExitInterrupted = 130;

struct RunArguments {
  std::string scenario;
  std::string estimators;
  std::string particles = "1";
  std::string seeds;
  std::string out;
  std::string data_dir;
  int steps = 0;
  int jobs = 0;
  std::string experiment = "default";
  double detection_probability = 0.0;
  double clutter_rate = 0.0;
  std::vector<std::string> assignments;
  bool quiet = false;
  CLI::Option* data_dir_option = nullptr;
  CLI::Option* pd_option = nullptr;
  CLI::Option* clutter_option = nullptr;
};

struct EvaluateArguments {
  std::string truth_map;
  std::string map;
  double c = 20.0;
  double p = 2.0;
  std::string truth_trajectory;
  std::string trajectory;
  double time_tolerance = 0.0;
};

void AddRunCommand(CLI::App& app, RunArguments& a) {
  CLI::App* run = app.add_subcommand(
      "run",
      "Monte Carlo runs of one or more estimators on a scenario. Each finished run is written to "
      "<out>/runs/<estimator>-N<particles>/seed-<seed>/; rerunning with the same --out skips "
      "finished runs. Ends with <out>/summary.csv, runs.csv, config.json and timing.json "
      "(layout: validation/README.md).");
  run->add_option("--scenario", a.scenario, "Scenario name (see `phdslam list`)")->required();
  run->add_option("--estimator", a.estimators,
                  "Estimator name, or a comma list of names (see `phdslam list`)")
      ->required();
  run->add_option("--particles", a.particles, "Particle count, or a comma list such as 1,10,100")
      ->capture_default_str();
  run->add_option("--seeds", a.seeds,
                  "Monte Carlo seeds: a range a-b (inclusive), a single seed, or a comma list "
                  "such as 1,3,10-12")
      ->required();
  run->add_option("--out", a.out, "Results folder (created if needed)")->required();
  a.data_dir_option =
      run->add_option("--data-dir", a.data_dir,
                      "Data sets folder (default: $PHDSLAM_DATA, else the folder compiled in)");
  run->add_option("--steps", a.steps, "Use only the first N filter steps of each run (0 = all)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  run->add_option("--jobs", a.jobs,
                  "Worker threads (0 = one per hardware thread); results do not depend on it")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  run->add_option("--experiment-name", a.experiment,
                  "Experiment name, part of every estimator's random stream seed")
      ->capture_default_str();
  a.pd_option = run->add_option("--pd", a.detection_probability,
                                "Override the scenario's detection probability (0, 1]");
  a.clutter_option = run->add_option("--clutter-rate", a.clutter_rate,
                                     "Override the scenario's mean clutter count per scan");
  run->add_option("--set", a.assignments,
                  "Estimator parameter override [estimator:]key=value (repeatable; dotted keys "
                  "reach nested parameters; the value is JSON when it parses, else a string)");
  run->add_flag("--quiet", a.quiet, "No progress line and no summary table");
}

void AddEvaluateCommand(CLI::App& app, EvaluateArguments& a) {
  CLI::App* evaluate = app.add_subcommand(
      "evaluate",
      "Compare result files with the truth and print JSON: a map CSV (x,y[,weight,pxx,pxy,pyy]) "
      "against a true map (GOSPA with its parts, OSPA), and/or a TUM trajectory against a true "
      "TUM trajectory (position and heading RMSE over poses matched by time stamp).");
  evaluate->add_option("--truth-map", a.truth_map, "True map CSV")->check(CLI::ExistingFile);
  evaluate->add_option("--map", a.map, "Estimated map CSV")->check(CLI::ExistingFile);
  evaluate->add_option("--c", a.c, "GOSPA/OSPA cut-off distance (m)")->capture_default_str();
  evaluate->add_option("--p", a.p, "GOSPA/OSPA order")->capture_default_str();
  evaluate->add_option("--truth-trajectory", a.truth_trajectory, "True trajectory (TUM)")
      ->check(CLI::ExistingFile);
  evaluate->add_option("--trajectory", a.trajectory, "Estimated trajectory (TUM)")
      ->check(CLI::ExistingFile);
  evaluate
      ->add_option("--time-tolerance", a.time_tolerance,
                   "Largest time difference (s) between matched poses; 0 = equal stamps")
      ->capture_default_str();
}

// Per-estimator overrides from the --set arguments.
std::map<std::string, nlohmann::json> CollectOverrides(const std::vector<std::string>& names,
                                                       const std::vector<std::string>& sets) {
  std::map<std::string, nlohmann::json> overrides;
  for (const std::string& name : names) overrides[name] = nlohmann::json::object();
  for (const std::string& text : sets) {
    const v::ParameterAssignment assignment = v::ParseParameterAssignment(text);
    if (!assignment.estimator.empty() && !overrides.contains(assignment.estimator)) {
      throw std::invalid_argument("--set '" + text + "': estimator '" + assignment.estimator +
                                  "' is not among --estimator");
    }
    for (auto& [name, json] : overrides) {
      if (assignment.estimator.empty() || assignment.estimator == name) {
        v::MergeJsonObjects(json, assignment.overrides);
      }
    }
  }
  return overrides;
}

int Run(const RunArguments& a) {
  const std::vector<std::string> names = v::ParseNameList(a.estimators, "estimator");
  v::MonteCarloPlan plan;
  plan.experiment = a.experiment;
  plan.particles = v::ParseParticleList(a.particles);
  plan.seeds = v::ParseSeedList(a.seeds);
  const std::map<std::string, nlohmann::json> overrides = CollectOverrides(names, a.assignments);
  for (const std::string& name : names) {
    plan.estimators.push_back({v::FindEstimator(name), overrides.at(name)});
  }
  v::ScenarioOptions options;
  if (a.data_dir_option->count() > 0) options.data_dir = a.data_dir;
  options.steps = a.steps;
  if (a.pd_option->count() > 0) options.detection_probability = a.detection_probability;
  if (a.clutter_option->count() > 0) options.clutter_rate = a.clutter_rate;
  plan.scenario = v::MakeScenarioSource(a.scenario, options);

  const v::InterruptFlag interrupt;
  v::MonteCarloSettings settings;
  settings.out = a.out;
  settings.jobs = a.jobs;
  settings.show_progress = !a.quiet;
  settings.stop = &interrupt.flag();
  const v::MonteCarloReport report = v::RunMonteCarlo(plan, settings);

  const std::filesystem::path out(a.out);
  if (!a.quiet) {
    std::cout << v::FormatSummaryTable(v::SummariseGroups(v::ReadResults(out)));
    std::cout << "runs: " << report.planned << " planned, " << report.skipped
              << " already finished, " << report.finished << " computed, " << report.failures.size()
              << " failed; " << report.jobs << " jobs, " << report.wall_seconds << " s\n";
  }
  std::cout << "summary: " << (out / v::kSummaryFile).string() << "\n";
  // Each failure was reported on stderr as it happened; its error is kept in its error.json.
  if (!report.failures.empty()) {
    std::cerr << "phdslam: " << report.failures.size() << " of " << report.planned - report.skipped
              << " runs failed (their folders hold error.json; rerun to retry them)\n";
  }
  if (report.interrupted) {
    std::cerr << "phdslam: interrupted; finished runs are kept, rerun the same command to "
                 "resume\n";
    return kExitInterrupted;
  }
  return report.failures.empty() ? 0 : kExitRunFailed;
}

int Evaluate(const EvaluateArguments& a) {
  const bool map_pair = !a.truth_map.empty() || !a.map.empty();
  const bool trajectory_pair = !a.truth_trajectory.empty() || !a.trajectory.empty();
  if (!map_pair && !trajectory_pair) {
    throw std::invalid_argument(
        "evaluate: give --truth-map with --map, and/or --truth-trajectory with "
        "--trajectory");
  }
  if (map_pair && (a.truth_map.empty() || a.map.empty())) {
    throw std::invalid_argument("evaluate: --truth-map and --map go together");
  }
  if (trajectory_pair && (a.truth_trajectory.empty() || a.trajectory.empty())) {
    throw std::invalid_argument("evaluate: --truth-trajectory and --trajectory go together");
  }
  nlohmann::json result = nlohmann::json::object();
  if (map_pair) {
    result.update(
        v::CompareMaps(datasets::ReadMapCsv(a.truth_map), datasets::ReadMapCsv(a.map), a.c, a.p));
  }
  if (trajectory_pair) {
    result.update(v::CompareTrajectories(datasets::ReadTumTrajectory(a.truth_trajectory),
                                         datasets::ReadTumTrajectory(a.trajectory),
                                         a.time_tolerance));
  }
  std::cout << result.dump(2) << "\n";
  return 0;
}

int List() {
  std::size_t width = 0;
  for (const auto& s : v::ScenarioTable()) width = std::max(width, s.name.size());
  for (const auto& e : v::EstimatorTable()) width = std::max(width, e.name.size());
  const auto line = [&](const std::string& name, const std::string& description) {
    std::cout << "  " << name << std::string(width + 2 - name.size(), ' ') << description << "\n";
  };
  std::cout << "scenarios:\n";
  for (const auto& s : v::ScenarioTable()) line(s.name, s.description);
  std::cout << "estimators:\n";
  for (const auto& e : v::EstimatorTable()) {
    line(e.name, e.description + (e.batch ? " [batch]" : ""));
  }
  return 0;
}

int Main(int argc, char** argv) {
  CLI::App app{"phdslam: PHD-SLAM 3.0 reproduction and validation suite", "phdslam"};
  app.require_subcommand(1);
  app.set_version_flag("--version", v::ProgramVersion());
  RunArguments run_arguments;
  EvaluateArguments evaluate_arguments;
  AddRunCommand(app, run_arguments);
  AddEvaluateCommand(app, evaluate_arguments);
  app.add_subcommand("list", "List the known scenarios and estimators");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(e);
    std::cerr << "phdslam: error: " << e.what() << " (see phdslam --help)\n";
    return kExitUsage;
  }
  try {
    if (app.got_subcommand("run")) return Run(run_arguments);
    if (app.got_subcommand("evaluate")) return Evaluate(evaluate_arguments);
    return List();
  } catch (const std::invalid_argument& e) {
    // Bad lists, unknown names and out-of-range options: usage errors.
    std::cerr << "phdslam: error: " << e.what() << "\n";
    return kExitUsage;
  } catch (const std::exception& e) {
    std::cerr << "phdslam: error: " << e.what() << "\n";
    return kExitRunFailed;
  }
}

}  // namespace
}  // namespace phdslam::apps

int main(int argc, char** argv) { return phdslam::apps::Main(argc, argv); }
