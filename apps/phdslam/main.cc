// phdslam: the command line of the PHD-SLAM 3.0 reproduction and validation suite.
//
//   phdslam run       Monte Carlo runs of estimators on a scenario (or of an experiment file),
//                     into a results folder
//   phdslam merge     join the results folders of shards into one
//   phdslam compare   paired Wilcoxon signed-rank tests between the groups of a results folder
//   phdslam evaluate  GOSPA/OSPA of a map file, RMSE of a trajectory file
//   phdslam list      the known scenarios and estimators
//   phdslam parent-weights  single-cluster vs RB-PHD-SLAM parent weights after one scan
//   phdslam export    a scenario's filter inputs and truth per seed, for external filters
//   phdslam ingest    an external filter's outputs into a results folder
//
// Exit codes: 0 success, 1 a run or evaluation failed (or a file could not be read), 2 a usage
// error (bad option, experiment file or list; unknown name; conflicting results folders),
// 130 interrupted (Ctrl-C).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <new>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/phdslam/option_without_value.h"
#include "datasets/map_io.h"
#include "datasets/simulation_limits.h"
#include "datasets/trajectory_io.h"
#include "src/core/random.h"
#include "validation/runner/evaluation/offline_evaluation.h"
#include "validation/runner/evaluation/paired_comparison.h"
#include "validation/runner/execution/interrupt_flag.h"
#include "validation/runner/execution/monte_carlo.h"
#include "validation/runner/execution/shard.h"
#include "validation/runner/experiment/experiment_file.h"
#include "validation/runner/experiment/experiment_runner.h"
#include "validation/runner/experiment/merge_results.h"
#include "validation/runner/experiment/sweep.h"
#include "validation/runner/interchange/ingest.h"
#include "validation/runner/interchange/scenario_export.h"
#include "validation/runner/io/list_arguments.h"
#include "validation/runner/io/results_io.h"
#include "validation/runner/io/results_layout.h"
#include "validation/runner/registry/estimator_registry.h"
#include "validation/runner/registry/parameter_overrides.h"
#include "validation/runner/registry/scenario_registry.h"
#include "validation/runner/results/results_config.h"
#include "validation/runner/results/summary.h"
#include "validation/runner/studies/parent_weights.h"

namespace phdslam::apps {
namespace {

namespace v = phdslam::validation;

constexpr int kExitRunFailed = 1;
constexpr int kExitUsage = 2;
constexpr int kExitInterrupted = 130;

struct RunArguments {
  std::string experiment_file;
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
  std::vector<std::string> scenario_assignments;
  std::string shard;
  bool particles_trace = false;
  bool map_ospa = false;
  double map_ospa_cutoff = 0.0;
  bool quiet = false;
  // Options whose presence matters (command-line values override an experiment file's).
  CLI::Option* experiment_file_option = nullptr;
  CLI::Option* scenario_option = nullptr;
  CLI::Option* estimator_option = nullptr;
  CLI::Option* particles_option = nullptr;
  CLI::Option* seeds_option = nullptr;
  CLI::Option* steps_option = nullptr;
  CLI::Option* jobs_option = nullptr;
  CLI::Option* experiment_name_option = nullptr;
  CLI::Option* data_dir_option = nullptr;
  CLI::Option* pd_option = nullptr;
  CLI::Option* clutter_option = nullptr;
  CLI::Option* map_ospa_cutoff_option = nullptr;
};

// The scenario options of `export` and `ingest`, as `run` takes them.
struct ScenarioArguments {
  std::string scenario;
  std::string seeds;
  std::string data_dir;
  int steps = 0;
  double detection_probability = 0.0;
  double clutter_rate = 0.0;
  std::vector<std::string> scenario_assignments;
  CLI::Option* scenario_option = nullptr;
  CLI::Option* seeds_option = nullptr;
  CLI::Option* data_dir_option = nullptr;
  CLI::Option* steps_option = nullptr;
  CLI::Option* pd_option = nullptr;
  CLI::Option* clutter_option = nullptr;
};

struct ExportArguments {
  ScenarioArguments scenario;
  std::string out;
};

struct IngestArguments {
  ScenarioArguments scenario;
  std::string from;
  std::string estimator;
  std::string out;
  std::string export_dir;
  std::string description = "external estimator (phdslam ingest)";
  std::string experiment = "default";
  int particles = 1;
  bool replace = false;
};

struct MergeArguments {
  std::string out;
  std::vector<std::string> inputs;
};

struct CompareArguments {
  std::string out;
  std::string metrics = "gospa_m,pos_rmse_m";
};

struct ParentWeightsArguments {
  std::string scenario = "paper-synthetic";
  std::uint64_t seed = 1;
  std::size_t step = 100;
  int parents = 300;
  double spread = 10.0;
  std::size_t every = 0;
  std::size_t until = 0;
  std::string out;
  std::string data_dir;
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
      "Monte Carlo runs of one or more estimators on a scenario, given by options or by an "
      "experiment file (--experiment; options given with it override the file's values). Each "
      "finished run is written to <out>/runs/<estimator>-N<particles>/seed-<seed>/; rerunning "
      "with the same --out skips finished runs. Ends with <out>/summary.csv, runs.csv, "
      "config.json and timing.json; a sweep writes one such folder per sweep point, "
      "<out>/sweep-<parameter>-<value>[-<parameter>-<value>...]/, and <out>/sweep.csv (layout: "
      "validation/README.md).");
  a.experiment_file_option =
      run->add_option("--experiment", a.experiment_file,
                      "Experiment file (YAML, e.g. validation/experiments/quick.yaml); "
                      "--scenario, --estimator and --seeds are then optional")
          ->check(CLI::ExistingFile);
  a.scenario_option =
      run->add_option("--scenario", a.scenario, "Scenario name (see `phdslam list`)");
  a.estimator_option = run->add_option(
      "--estimator", a.estimators, "Estimator name, or a comma list of names (see `phdslam list`)");
  a.particles_option =
      run->add_option("--particles", a.particles,
                      "Particle count (1 to 100000), or a comma list such as 1,10,100")
          ->capture_default_str();
  a.seeds_option =
      run->add_option("--seeds", a.seeds,
                      "Monte Carlo seeds: a range a-b (inclusive), a single seed, or "
                      "a comma list such as 1,3,10-12; at most 10^6 runs (seeds x estimators x "
                      "particle counts) per results folder");
  run->add_option("--out", a.out, "Results folder (created if needed)")->required();
  a.data_dir_option =
      run->add_option("--data-dir", a.data_dir,
                      "Data sets folder (default: $PHDSLAM_DATA, else the folder compiled in)");
  a.steps_option =
      run->add_option("--steps", a.steps, "Use only the first N filter steps of each run (0 = all)")
          ->capture_default_str()
          ->check(CLI::NonNegativeNumber);
  a.jobs_option = run->add_option("--jobs", a.jobs,
                                  "Worker threads (0 = one per hardware thread); results do not "
                                  "depend on it")
                      ->capture_default_str()
                      ->check(CLI::NonNegativeNumber);
  a.experiment_name_option =
      run->add_option("--experiment-name", a.experiment,
                      "Experiment name, part of every estimator's random stream seed (default: "
                      "the experiment file's name, else 'default')")
          ->capture_default_str();
  a.pd_option = run->add_option("--pd", a.detection_probability,
                                "Override the scenario's detection probability (0, 1]");
  a.clutter_option =
      run->add_option("--clutter-rate", a.clutter_rate,
                      "Override the scenario's mean clutter count per scan (0 to 1000)");
  run->add_option("--set", a.assignments,
                  "Estimator parameter override [estimator:]key=value (repeatable; dotted keys "
                  "reach nested parameters; the value is JSON when it parses, else a string)");
  run->add_option("--scenario-set", a.scenario_assignments,
                  "Scenario option key=value (repeatable; the keys of each scenario are listed "
                  "by `phdslam list`; pd and clutter_rate as --pd and --clutter-rate; the value "
                  "is JSON when it parses, else a string)");
  run->add_option("--shard", a.shard,
                  "Run only shard i of n: the jobs whose index in the experiment's job order is "
                  "i-1 modulo n (join the shards' folders with `phdslam merge`)");
  run->add_flag("--particles-trace", a.particles_trace,
                "Also write particles.csv (step,particle,x,y,log_weight) per run, for estimators "
                "that expose their particles");
  run->add_flag("--map-ospa", a.map_ospa,
                "Also write the map OSPA (p = 1, c = 5 m unless --map-ospa-cutoff) after every "
                "step, against the true landmarks detected so far, as the last steps.csv column "
                "map_ospa_m (online estimators on scenarios with a true map; also the experiment "
                "key map_ospa: true)");
  a.map_ospa_cutoff_option =
      run->add_option("--map-ospa-cutoff", a.map_ospa_cutoff,
                      "Cut-off c (m, > 0) of the per-step map OSPA; implies --map-ospa (also the "
                      "experiment key map_ospa_cutoff; default 5)")
          ->check(CLI::PositiveNumber);
  run->add_flag("--quiet", a.quiet, "No progress line and no summary table");
}

void AddScenarioOptions(CLI::App* command, ScenarioArguments& a) {
  a.scenario_option =
      command->add_option("--scenario", a.scenario, "Scenario name (see `phdslam list`)");
  a.seeds_option = command->add_option(
      "--seeds", a.seeds, "Monte Carlo seeds: a range a-b, a single seed, or a comma list");
  a.data_dir_option =
      command->add_option("--data-dir", a.data_dir,
                          "Data sets folder (default: $PHDSLAM_DATA, else the folder compiled in)");
  a.steps_option = command
                       ->add_option("--steps", a.steps,
                                    "Use only the first N filter steps of each seed (0 = all)")
                       ->check(CLI::NonNegativeNumber);
  a.pd_option = command->add_option("--pd", a.detection_probability,
                                    "Override the scenario's detection probability (0, 1]");
  a.clutter_option = command->add_option("--clutter-rate", a.clutter_rate,
                                         "Override the scenario's mean clutter count per scan");
  command->add_option("--scenario-set", a.scenario_assignments,
                      "Scenario option key=value (repeatable), as for `run`");
}

void AddExportCommand(CLI::App& app, ExportArguments& a) {
  CLI::App* command = app.add_subcommand(
      "export",
      "Write the inputs of a filter for every seed of a scenario, as `run` would give them to "
      "an estimator, into --out: seed-<s>/steps.csv (step,t,controls,measurements), "
      "seed-<s>/controls.csv (step,t_start,t_end,u1,u2), seed-<s>/measurements.csv "
      "(step,index,range,bearing), seed-<s>/models.json (initial pose, motion and sensor models, "
      "noise, field of view, detection and clutter); the truth in truth/seed-<s>/ "
      "(trajectory.tum, map.csv id,x,y, gps.csv t,x,y, origins.csv step,index,origin; those the "
      "scenario has); export.json (format "
      "version, scenario and options, seeds) and SHA256SUMS (`sha256sum -c SHA256SUMS`). "
      "Format: validation/EXPORT_FORMAT.md.");
  AddScenarioOptions(command, a.scenario);
  command->add_option("--out", a.out, "Export folder (created if needed; must be empty)")
      ->required();
}

void AddIngestCommand(CLI::App& app, IngestArguments& a) {
  CLI::App* command = app.add_subcommand(
      "ingest",
      "Read an external filter's outputs, --from DIR with DIR/seed-<s>/trajectory.tum (one "
      "pose per step, at the step's time stamp) and DIR/seed-<s>/map.csv (x,y[,weight,pxx,pxy,"
      "pyy]), optionally pose_cov.csv (step,pxx,pxy,pxt,pyy,pyt,ptt), maps.csv (step,x,y: the "
      "map after each step), association.csv (step,index,x,y) and timing.csv (step,ms) per "
      "seed and DIR/parameters.json, score them against the scenario and write them as the runs "
      "of estimator --estimator into the results folder --out, as `run` writes runs (the folder "
      "may already hold `run` results of the same scenario and experiment name). The scenario "
      "comes from --export (the export folder the filter read; its checksums are verified) or "
      "from the scenario options, as for `run`. Format: validation/EXPORT_FORMAT.md.");
  AddScenarioOptions(command, a.scenario);
  command->add_option("--from", a.from, "Folder of the external filter's outputs")
      ->required()
      ->check(CLI::ExistingDirectory);
  command->add_option("--estimator", a.estimator, "Name the external filter's runs are filed under")
      ->required();
  command->add_option("--out", a.out, "Results folder (created if needed)")->required();
  command
      ->add_option("--export", a.export_dir,
                   "Export folder the filter read: scenario, options and seeds (default: all of "
                   "its seeds) come from its export.json")
      ->check(CLI::ExistingDirectory);
  command->add_option("--description", a.description, "Description stored in config.json")
      ->capture_default_str();
  command
      ->add_option("--experiment-name", a.experiment,
                   "Experiment name; must be that of the results folder's runs")
      ->capture_default_str();
  command->add_option("--particles", a.particles, "Particle count the runs are filed under")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  command->add_flag("--replace", a.replace,
                    "Replace the runs the estimator already has in --out (without it an estimator "
                    "name that already has runs there is refused); the replaced run folders are "
                    "listed");
}

void AddMergeCommand(CLI::App& app, MergeArguments& a) {
  CLI::App* merge = app.add_subcommand(
      "merge",
      "Join results folders (the shards of one experiment, or runs of one experiment made "
      "elsewhere) into --out: finished runs are hard-linked or copied, folders made with "
      "conflicting settings are refused, and summary.csv/runs.csv are written as a single run "
      "would write them. Sweep roots are merged value by value.");
  merge->add_option("--out", a.out, "Merged results folder (created if needed)")->required();
  merge->add_option("folders", a.inputs, "Results folders to merge (e.g. the shards' --out)")
      ->required()
      ->check(CLI::ExistingDirectory);
}

void AddCompareCommand(CLI::App& app, CompareArguments& a) {
  CLI::App* compare = app.add_subcommand(
      "compare",
      "Paired comparisons: for every metric and every pair of (estimator, particles) groups of "
      "<out>/runs.csv, the two-sided Wilcoxon signed-rank test over their common seeds, written "
      "to <out>/comparison.csv (for a sweep, in every sweep folder).");
  compare->add_option("--out", a.out, "Results folder holding runs.csv")
      ->required()
      ->check(CLI::ExistingDirectory);
  compare->add_option("--metric", a.metrics, "runs.csv column(s) to compare, a comma list")
      ->capture_default_str();
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

void AddParentWeightsCommand(CLI::App& app, ParentWeightsArguments& a) {
  CLI::App* pw = app.add_subcommand(
      "parent-weights",
      "The parent weighting figure of single-cluster PHD SLAM (Lee, Clark & Salvi 2012, Fig. 4): "
      "runs scphd with one parent up to --step, draws --parents poses from its predicted pose "
      "Gaussian (standard deviations scaled by --spread), updates the same predicted map with the "
      "scan of --step, and writes the "
      "normalised weights under the single-cluster likelihood (with exp(-sum pD w)) and under "
      "the RB-PHD-SLAM weighting (46) and under Mullane et al.'s single-feature RB-PHD-SLAM "
      "weighting to OUT/parent_weights.csv "
      "(parent,x,y,theta,sc_weight,rb_weight,sc_log_weight,rb_log_weight,missed_mass,sf_weight,"
      "sf_log_weight: the log-weights normalised to log-sum-exp 0, the missed-detection mass "
      "sum pD w of the predicted map seen from each parent) and OUT/parent_weights.json (step, "
      "predicted Gaussian, true pose, ESS of each weighting). With --every N it also compares at "
      "steps N, 2N, ... up to --until (one filter run) and writes OUT/parent_weights_steps.csv "
      "(step,measurements,map_components,ess_single_cluster,ess_rb_phd,ess_single_feature) and "
      "OUT/parent_weights_steps.json (mean ESS, paired Wilcoxon tests over the steps). The "
      "report draws it when OUT is a results folder.");
  pw->add_option("--scenario", a.scenario, "Scenario")->capture_default_str();
  pw->add_option("--seed", a.seed, "Monte Carlo seed of the scenario and of the draws")
      ->capture_default_str();
  pw->add_option("--step", a.step, "0-based step whose scan is compared (needs measurements)")
      ->capture_default_str();
  pw->add_option("--parents", a.parents, "Parent poses drawn (2 to 100000)")->capture_default_str();
  pw->add_option("--spread", a.spread,
                 "Scale of the draws' standard deviations relative to the one-step prediction "
                 "(wider parents differ in which map components they see)")
      ->capture_default_str();
  pw->add_option("--every", a.every,
                 "Also compare at every N-th step (0 = only --step) and write the ESS per step")
      ->capture_default_str();
  pw->add_option("--until", a.until, "Last step of --every (0 = the scenario's last step)")
      ->capture_default_str();
  pw->add_option("--out", a.out, "Output folder (created if needed)")->required();
  pw->add_option("--data-dir", a.data_dir,
                 "Data sets folder (default: $PHDSLAM_DATA, then the compiled default)");
}

// Applies the --set arguments to the experiment's estimators.
void ApplyAssignments(const std::vector<std::string>& sets, v::Experiment& x) {
  for (const std::string& text : sets) {
    const v::ParameterAssignment assignment = v::ParseParameterAssignment(text);
    bool matched = assignment.estimator.empty();
    for (v::ExperimentEstimator& e : x.estimators) {
      if (assignment.estimator.empty() || assignment.estimator == e.name) {
        v::MergeJsonObjects(e.overrides, assignment.overrides);
        matched = true;
      }
    }
    if (!matched) {
      throw std::invalid_argument("--set '" + text + "': estimator '" + assignment.estimator +
                                  "' is not among the experiment's estimators");
    }
  }
}

// Applies the --scenario-set arguments (key=value) to the experiment's scenario options.
void ApplyScenarioAssignments(const std::vector<std::string>& sets, v::Experiment& x) {
  for (const std::string& text : sets) {
    const v::ParameterAssignment assignment = v::ParseParameterAssignment(text, "--scenario-set");
    if (!assignment.estimator.empty() || assignment.overrides.size() != 1 ||
        assignment.overrides.begin()->is_object()) {
      throw std::invalid_argument("--scenario-set '" + text + "': expected key=value");
    }
    try {
      const std::string& key = assignment.overrides.begin().key();
      const nlohmann::json& value = *assignment.overrides.begin();
      if (!x.scenario.empty()) v::CheckScenarioOption(x.scenario, key, value);
      v::SetScenarioOption(x, key, value);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("--scenario-set '" + text + "': " + e.what());
    }
  }
}

// `value` of command-line option `option` (scenario option `key`), checked against the
// scenario's option table; errors name the option as typed.
double CheckedScenarioNumber(const v::Experiment& x, const std::string& option,
                             const std::string& key, double value) {
  try {
    if (!x.scenario.empty()) v::CheckScenarioOption(x.scenario, key, value);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(option + " " + datasets::CompactNumber(value) + ": " + e.what());
  }
  return value;
}

// The experiment of a `run` command: the experiment file, if any, with every option given on
// the command line taking precedence over the file's value.
v::Experiment ResolveExperiment(const RunArguments& a) {
  const bool from_file = a.experiment_file_option->count() > 0;
  v::Experiment x;
  if (from_file) {
    x = v::ReadExperimentFile(a.experiment_file);
  } else {
    for (const CLI::Option* o : {a.scenario_option, a.estimator_option, a.seeds_option}) {
      if (o->count() == 0) {
        throw std::invalid_argument("run: " + o->get_name() +
                                    " is required (or give --experiment)");
      }
    }
  }
  std::vector<std::string> overridden;
  const auto given = [&](const CLI::Option* o) {
    if (o->count() == 0) return false;
    overridden.push_back(o->get_name());
    return true;
  };
  if (given(a.scenario_option)) x.scenario = a.scenario;
  if (given(a.estimator_option)) {
    std::vector<v::ExperimentEstimator> selected;
    for (const std::string& name : v::ParseNameList(a.estimators, "estimator")) {
      v::ExperimentEstimator e{name};
      for (const v::ExperimentEstimator& in_file : x.estimators) {
        if (in_file.name == name) e = in_file;  // keeps the file's `set` and `particles`
      }
      selected.push_back(std::move(e));
    }
    x.estimators = std::move(selected);
  }
  if (given(a.particles_option)) x.particles = v::ParseParticleList(a.particles);
  if (given(a.seeds_option)) x.seeds = v::ParseSeedList(a.seeds);
  if (given(a.steps_option)) x.steps = a.steps;
  if (given(a.jobs_option)) x.jobs = a.jobs;
  if (given(a.experiment_name_option) || !from_file) x.name = a.experiment;
  if (given(a.pd_option)) x.pd = CheckedScenarioNumber(x, "--pd", "pd", a.detection_probability);
  if (given(a.clutter_option)) {
    x.clutter_rate = CheckedScenarioNumber(x, "--clutter-rate", "clutter_rate", a.clutter_rate);
  }
  if (a.data_dir_option->count() > 0) x.data_dir = a.data_dir;  // a machine setting
  if (!a.assignments.empty()) overridden.push_back("--set");
  ApplyAssignments(a.assignments, x);
  if (!a.scenario_assignments.empty()) overridden.push_back("--scenario-set");
  ApplyScenarioAssignments(a.scenario_assignments, x);
  if (from_file) x.source["command_line"] = overridden;
  return x;
}

void PrintRunReport(const v::ExperimentPart& part, const v::MonteCarloReport& report,
                    const std::vector<v::ExperimentSweep>& sweep, bool quiet) {
  if (!quiet) {
    for (std::size_t i = 0; i < part.sweep_point.size() && i < sweep.size(); ++i) {
      std::cout << (i > 0 ? ", " : "") << sweep[i].parameter << " = "
                << v::SweepValueText(part.sweep_point[i]);
    }
    if (!part.sweep_point.empty()) std::cout << ":\n";
    std::cout << v::FormatSummaryTable(v::SummariseGroups(v::ReadResults(part.out)));
    std::cout << "runs: " << report.planned << " planned, " << report.skipped
              << " already finished, " << report.finished << " computed, " << report.failures.size()
              << " failed";
    if (report.outside_shard > 0) std::cout << ", " << report.outside_shard << " in other shards";
    std::cout << "; " << report.jobs << " jobs, " << report.wall_seconds << " s\n";
  }
  std::cout << "summary: " << (part.out / v::kSummaryFile).string() << "\n";
}

int Run(const RunArguments& a) {
  const v::Experiment experiment = ResolveExperiment(a);
  const v::InterruptFlag interrupt;
  v::ExperimentSettings settings;
  settings.out = a.out;
  settings.show_progress = !a.quiet;
  settings.stop = &interrupt.flag();
  settings.particles_trace = a.particles_trace;
  settings.map_ospa_trace = a.map_ospa || experiment.map_ospa.value_or(false) ||
                            experiment.map_ospa_cutoff.has_value() ||
                            a.map_ospa_cutoff_option->count() > 0;
  if (a.map_ospa_cutoff_option->count() > 0) {
    settings.metrics.map_ospa_c = a.map_ospa_cutoff;
  } else if (experiment.map_ospa_cutoff) {
    settings.metrics.map_ospa_c = *experiment.map_ospa_cutoff;
  }
  if (!a.shard.empty()) settings.shard = v::ParseShard(a.shard);
  const v::ExperimentReport report = v::RunExperiment(experiment, settings);

  std::size_t failures = 0;
  std::size_t attempted = 0;
  for (std::size_t i = 0; i < report.reports.size(); ++i) {
    PrintRunReport(report.parts[i], report.reports[i], experiment.sweep, a.quiet);
    failures += report.reports[i].failures.size();
    attempted += report.reports[i].planned - report.reports[i].skipped;
  }
  if (!experiment.sweep.empty()) {
    std::cout << "sweep: " << (std::filesystem::path(a.out) / v::kSweepTableFile).string() << "\n";
  }
  // Each failure was reported on stderr as it happened; its error is kept in its error.json.
  if (failures > 0) {
    std::cerr << "phdslam: " << failures << " of " << attempted
              << " runs failed (their folders hold error.json; rerun to retry them)\n";
  }
  if (report.interrupted) {
    std::cerr << "phdslam: interrupted; finished runs are kept, rerun the same command to "
                 "resume\n";
    return kExitInterrupted;
  }
  return failures == 0 ? 0 : kExitRunFailed;
}

// The experiment holding a scenario and its options, as `run` would resolve them.
v::Experiment ScenarioExperiment(const ScenarioArguments& a) {
  v::Experiment x;
  x.scenario = a.scenario;
  if (a.seeds_option->count() > 0) x.seeds = v::ParseSeedList(a.seeds);
  x.steps = a.steps;
  if (a.pd_option->count() > 0) {
    x.pd = CheckedScenarioNumber(x, "--pd", "pd", a.detection_probability);
  }
  if (a.clutter_option->count() > 0) {
    x.clutter_rate = CheckedScenarioNumber(x, "--clutter-rate", "clutter_rate", a.clutter_rate);
  }
  if (a.data_dir_option->count() > 0) x.data_dir = a.data_dir;
  ApplyScenarioAssignments(a.scenario_assignments, x);
  return x;
}

v::ScenarioSource SourceOf(const v::Experiment& x) {
  return v::PlanExperiment(x, {}, v::EstimatorTable()).front().plan.scenario;
}

int Export(const ExportArguments& a) {
  for (const CLI::Option* o : {a.scenario.scenario_option, a.scenario.seeds_option}) {
    if (o->count() == 0) throw std::invalid_argument("export: " + o->get_name() + " is required");
  }
  v::RequireEmptyExportFolder(a.out);
  const v::Experiment x = ScenarioExperiment(a.scenario);
  const v::ScenarioSource source = SourceOf(x);
  std::vector<datasets::Scenario> scenarios;
  for (std::uint64_t seed : x.seeds) scenarios.push_back(source.make(seed));
  v::ExportDescription description;
  description.scenario = source.name;
  description.options = source.options;
  description.request = {
      {"steps", x.steps},
      {"pd", x.pd ? nlohmann::json(*x.pd) : nlohmann::json()},
      {"clutter_rate", x.clutter_rate ? nlohmann::json(*x.clutter_rate) : nlohmann::json()},
      {"settings", x.scenario_settings}};
  description.seeds = x.seeds;
  v::WriteExport(a.out, description, scenarios);
  std::cout << "export: " << a.out << " (" << scenarios.size() << " seeds of " << source.name
            << ", format version " << v::kExportFormatVersion << "; checksums in "
            << (std::filesystem::path(a.out) / v::kExportChecksumFile).string() << ")\n";
  return 0;
}

// The scenario of an export folder, from its export.json.
v::Experiment ExportedExperiment(const IngestArguments& a) {
  const ScenarioArguments& s = a.scenario;
  for (const CLI::Option* o : {s.scenario_option, s.steps_option, s.pd_option, s.clutter_option}) {
    if (o->count() > 0) {
      throw std::invalid_argument("ingest: " + o->get_name() +
                                  " and --export both give the scenario; give one");
    }
  }
  if (!s.scenario_assignments.empty()) {
    throw std::invalid_argument("ingest: --scenario-set and --export both give the scenario");
  }
  const std::filesystem::path path = std::filesystem::path(a.export_dir) / v::kExportManifestFile;
  const nlohmann::json manifest = v::ReadJsonObject(path);
  try {
    if (manifest.at("format_version").get<int>() != v::kExportFormatVersion) {
      throw std::runtime_error(path.string() + ": format_version " +
                               manifest.at("format_version").dump() + ", this program reads " +
                               std::to_string(v::kExportFormatVersion));
    }
    v::Experiment x;
    x.scenario = manifest.at("scenario").get<std::string>();
    const nlohmann::json& request = manifest.at("request");
    x.steps = request.at("steps").get<int>();
    if (!request.at("pd").is_null()) x.pd = request.at("pd").get<double>();
    if (!request.at("clutter_rate").is_null()) {
      x.clutter_rate = request.at("clutter_rate").get<double>();
    }
    x.scenario_settings = request.at("settings");
    x.seeds = s.seeds_option->count() > 0 ? v::ParseSeedList(s.seeds)
                                          : manifest.at("seeds").get<std::vector<std::uint64_t>>();
    if (s.data_dir_option->count() > 0) x.data_dir = s.data_dir;
    return x;
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(path.string() + ": unexpected content (" + e.what() + ")");
  }
}

int Ingest(const IngestArguments& a) {
  const bool from_export = !a.export_dir.empty();
  if (!from_export) {
    for (const CLI::Option* o : {a.scenario.scenario_option, a.scenario.seeds_option}) {
      if (o->count() == 0) {
        throw std::invalid_argument("ingest: " + o->get_name() + " is required (or give --export)");
      }
    }
  }
  const v::Experiment x = from_export ? ExportedExperiment(a) : ScenarioExperiment(a.scenario);
  v::IngestRequest request;
  request.from = a.from;
  request.estimator = a.estimator;
  request.description = a.description;
  request.particles = a.particles;
  request.experiment = a.experiment;
  request.scenario = SourceOf(x);
  request.seeds = x.seeds;
  if (from_export) request.export_dir = a.export_dir;
  request.replace = a.replace;
  const v::IngestReport report = v::IngestResults(request, a.out);
  for (const std::filesystem::path& replaced : report.replaced) {
    std::cout << "replaced: " << replaced.string() << "\n";
  }
  std::cout << "ingested " << report.runs << " runs of " << a.estimator << " into " << a.out
            << "\nsummary: " << (std::filesystem::path(a.out) / v::kSummaryFile).string() << "\n";
  return 0;
}

int Merge(const MergeArguments& a) {
  std::vector<std::filesystem::path> inputs(a.inputs.begin(), a.inputs.end());
  const v::MergeReport report = v::MergeResults(a.out, inputs);
  std::cout << "merged " << inputs.size() << " folders: " << report.runs_copied << " runs copied, "
            << report.runs_already_present << " already present, " << report.failed_runs_copied
            << " failed runs copied\n";
  const std::filesystem::path out(a.out);
  if (std::filesystem::exists(out / v::kSweepTableFile)) {
    std::cout << "sweep: " << (out / v::kSweepTableFile).string() << "\n";
  } else {
    std::cout << "summary: " << (out / v::kSummaryFile).string() << "\n";
  }
  return 0;
}

int Compare(const CompareArguments& a) {
  const std::vector<std::string> metrics = v::ParseNameList(a.metrics, "metric");
  const std::filesystem::path out(a.out);
  std::vector<std::filesystem::path> folders;
  if (std::filesystem::exists(out / v::kSweepFile)) {
    const nlohmann::json sweep = v::ReadJsonObject(out / v::kSweepFile);
    for (const auto& folder : sweep.at("folders")) {
      const std::filesystem::path path = out / folder.get<std::string>();
      if (std::filesystem::exists(path / v::kRunsTableFile)) folders.push_back(path);
    }
  } else {
    folders.push_back(out);
  }
  for (const std::filesystem::path& folder : folders) {
    const std::vector<v::PairedComparison> rows = v::WriteComparison(folder, metrics);
    std::size_t significant = 0;
    for (const v::PairedComparison& c : rows) {
      if (c.test.p_value && *c.test.p_value < 0.05) ++significant;
    }
    std::cout << "comparison: " << (folder / v::kComparisonFile).string() << " (" << rows.size()
              << " comparisons, " << significant << " with p < 0.05)\n";
  }
  return 0;
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
  std::cout << v::JsonFileText(result);
  return 0;
}

int ParentWeights(const ParentWeightsArguments& a) {
  v::ScenarioOptions options;
  if (!a.data_dir.empty()) options.data_dir = a.data_dir;
  const datasets::Scenario scenario = v::MakeScenario(a.scenario, a.seed, options);
  v::ParentWeightsSettings settings;
  settings.step = a.step;
  settings.parents = a.parents;
  settings.spread = a.spread;
  settings.stream_seed = DeriveSeed(HashName("parent-weights"), a.seed);
  const v::ParentWeights w = v::CompareParentWeightingAtStep(scenario, settings);
  const std::filesystem::path out(a.out);
  std::filesystem::create_directories(out);
  nlohmann::json meta = v::ParentWeightsJson(w);
  meta["scenario"] = a.scenario;
  meta["seed"] = a.seed;
  v::WriteFileAtomically(out / "parent_weights.csv", v::ParentWeightsCsv(w));
  v::WriteFileAtomically(out / "parent_weights.json", v::JsonFileText(meta));
  std::cout << "parent weights: " << (out / "parent_weights.csv").string() << " (ESS "
            << meta.at("ess_single_cluster").get<double>() << " single-cluster, "
            << meta.at("ess_rb_phd").get<double>() << " RB-PHD (46), "
            << meta.at("ess_single_feature").get<double>() << " single-feature RB-PHD of "
            << w.poses.size() << ")\n";
  if (a.every == 0) return 0;
  const std::size_t last =
      a.until == 0 ? scenario.steps.size() - 1 : std::min(a.until, scenario.steps.size() - 1);
  std::vector<std::size_t> steps;
  for (std::size_t k = a.every; k <= last; k += a.every) steps.push_back(k);
  const std::vector<v::StepEss> rows =
      v::CompareParentWeightingOverSteps(scenario, settings, steps);
  nlohmann::json summary = v::StepEssJson(rows);
  summary["scenario"] = a.scenario;
  summary["seed"] = a.seed;
  summary["parents"] = a.parents;
  summary["spread"] = a.spread;
  summary["every"] = a.every;
  v::WriteFileAtomically(out / "parent_weights_steps.csv", v::StepEssCsv(rows));
  v::WriteFileAtomically(out / "parent_weights_steps.json", v::JsonFileText(summary));
  std::cout << "parent weights over " << rows.size() << " steps: mean ESS "
            << summary.at("mean_ess_single_cluster").get<double>() << " single-cluster, "
            << summary.at("mean_ess_rb_phd").get<double>() << " RB-PHD (46), "
            << summary.at("mean_ess_single_feature").get<double>() << " single-feature\n";
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
  for (const auto& s : v::ScenarioTable()) {
    line(s.name, s.description);
    for (const v::ScenarioOptionHelp& o : s.option_keys) {
      std::cout << "  " << std::string(width + 2, ' ') << "  " << o.key << ": " << o.help << "\n";
    }
  }
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
  MergeArguments merge_arguments;
  CompareArguments compare_arguments;
  EvaluateArguments evaluate_arguments;
  ParentWeightsArguments parent_weights_arguments;
  ExportArguments export_arguments;
  IngestArguments ingest_arguments;
  AddRunCommand(app, run_arguments);
  AddMergeCommand(app, merge_arguments);
  AddCompareCommand(app, compare_arguments);
  AddEvaluateCommand(app, evaluate_arguments);
  AddParentWeightsCommand(app, parent_weights_arguments);
  AddExportCommand(app, export_arguments);
  AddIngestCommand(app, ingest_arguments);
  app.add_subcommand("list", "List the known scenarios (with their options) and estimators");
  if (const std::string option = OptionWithoutValue(app, argc, argv); !option.empty()) {
    std::cerr << "phdslam: error: " << option << " needs a value (see phdslam --help)\n";
    return kExitUsage;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(e);
    std::cerr << "phdslam: error: " << e.what() << " (see phdslam --help)\n";
    return kExitUsage;
  }
  try {
    if (app.got_subcommand("run")) return Run(run_arguments);
    if (app.got_subcommand("merge")) return Merge(merge_arguments);
    if (app.got_subcommand("compare")) return Compare(compare_arguments);
    if (app.got_subcommand("evaluate")) return Evaluate(evaluate_arguments);
    if (app.got_subcommand("parent-weights")) return ParentWeights(parent_weights_arguments);
    if (app.got_subcommand("export")) return Export(export_arguments);
    if (app.got_subcommand("ingest")) return Ingest(ingest_arguments);
    return List();
  } catch (const std::bad_alloc& e) {
    std::cerr << "phdslam: error: out of memory (" << e.what() << ") in 'phdslam "
              << app.get_subcommands().front()->get_name()
              << "': fewer seeds, particles or --jobs, or a lower clutter rate, need less\n";
    return kExitRunFailed;
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

int main(int argc, char** argv) {
  try {
    return phdslam::apps::Main(argc, argv);
  } catch (...) {
    std::cerr << "phdslam: error: an unexpected exception ended the program\n";
    return 1;
  }
}
