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
//   phdslam data      fetch the data sets into the data folder, check what it holds
//   phdslam gate      the accuracy gates over a results folder (ci/gates.py, ci/GATES.md)
//
// Exit codes: 0 success, 1 a run or evaluation failed (or a file could not be read), 2 a usage
// error (bad option, experiment file or list; unknown name; conflicting results folders),
// 130 interrupted (Ctrl-C).
#include <CLI/CLI.hpp>
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

#include "apps/phdslam/data_command.h"
#include "apps/phdslam/exit_codes.h"
#include "apps/phdslam/gate_command.h"
#include "apps/phdslam/interchange_commands.h"
#include "apps/phdslam/list_command.h"
#include "apps/phdslam/option_without_value.h"
#include "apps/phdslam/run_command.h"
#include "apps/phdslam/unknown_subcommand.h"
#include "datasets/map_io.h"
#include "datasets/trajectory_io.h"
#include "validation/runner/evaluation/offline_evaluation.h"
#include "validation/runner/evaluation/paired_comparison.h"
#include "validation/runner/execution/monte_carlo.h"
#include "validation/runner/experiment/merge_results.h"
#include "validation/runner/experiment/sweep.h"
#include "validation/runner/io/list_arguments.h"
#include "validation/runner/io/results_io.h"
#include "validation/runner/io/results_layout.h"
#include "validation/runner/registry/estimator_registry.h"
#include "validation/runner/registry/scenario_registry.h"
#include "validation/runner/results/results_lock.h"
#include "validation/runner/studies/parent_weights_output.h"

namespace phdslam::apps {
namespace {

namespace v = phdslam::validation;

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
// A folder without runs.csv: a run still writing it (its lock file is there) or no results.
void RequireRunsTable(const std::filesystem::path& folder) {
  if (std::filesystem::exists(folder / v::kRunsTableFile)) return;
  if (std::filesystem::exists(folder / v::kLockFile)) {
    throw std::runtime_error(folder.string() + " has no " + v::kRunsTableFile + " yet: a run is " +
                             "writing this folder (" + v::kLockFile + "), and " +
                             v::kRunsTableFile + " is written when it ends; compare after it");
  }
  throw std::runtime_error(folder.string() + " has no " + v::kRunsTableFile +
                           " (not a results folder, or its run ended before writing it: rerun "
                           "it with the same --out)");
}

int Compare(const CompareArguments& a) {
  const std::vector<std::string> metrics = v::ParseNameList(a.metrics, "metric");
  for (const std::filesystem::path& folder : v::ResultsFolders(a.out)) {
    RequireRunsTable(folder);
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
  v::ParentWeightsStudy study;
  study.scenario = a.scenario;
  study.seed = a.seed;
  study.settings.step = a.step;
  study.settings.parents = a.parents;
  study.settings.spread = a.spread;
  study.every = a.every;
  study.until = a.until;
  const std::filesystem::path out(a.out);
  const v::ParentWeightsOutput o =
      v::WriteParentWeightsStudy(v::MakeScenario(a.scenario, a.seed, options), study, out);
  std::cout << "parent weights: " << (out / v::kParentWeightsCsvFile).string() << " (ESS "
            << o.at_step.at("ess_single_cluster").get<double>() << " single-cluster, "
            << o.at_step.at("ess_rb_phd").get<double>() << " RB-PHD (46), "
            << o.at_step.at("ess_single_feature").get<double>() << " single-feature RB-PHD of "
            << o.parents << ")\n";
  if (!o.over_steps) return 0;
  std::cout << "parent weights over " << o.steps_compared << " steps: mean ESS "
            << o.over_steps->at("mean_ess_single_cluster").get<double>() << " single-cluster, "
            << o.over_steps->at("mean_ess_rb_phd").get<double>() << " RB-PHD (46), "
            << o.over_steps->at("mean_ess_single_feature").get<double>() << " single-feature\n";
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
  DataArguments data_arguments;
  AddDataCommand(app, data_arguments);
  GateArguments gate_arguments;
  AddGateCommand(app, gate_arguments);
  ListArguments list_arguments;
  AddListCommand(app, list_arguments);
  if (const std::string name = UnknownSubcommand(app, argc, argv); !name.empty()) {
    std::cerr << "phdslam: error: unknown subcommand '" << name
              << "' (the subcommands are listed by phdslam --help)\n";
    return kExitUsage;
  }
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
    if (app.got_subcommand("data")) return Data(app, data_arguments);
    if (app.got_subcommand("gate")) return Gate(gate_arguments);
    return List(list_arguments);
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
