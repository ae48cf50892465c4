#include "apps/phdslam/run_command.h"

#include <cstddef>
#include <filesystem>
#include <iostream>
#include <optional>

#include "apps/phdslam/exit_codes.h"
#include "validation/runner/execution/interrupt_flag.h"
#include "validation/runner/execution/monte_carlo.h"
#include "validation/runner/execution/shard.h"
#include "validation/runner/experiment/experiment_runner.h"
#include "validation/runner/experiment/sweep.h"
#include "validation/runner/io/results_layout.h"
#include "validation/runner/results/summary.h"

namespace phdslam::apps {

namespace v = phdslam::validation;

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

namespace {

template <typename T>
std::optional<T> IfGiven(const CLI::Option* option, const T& value) {
  return option->count() > 0 ? std::optional<T>(value) : std::nullopt;
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

}  // namespace

v::ExperimentOptions GivenOptions(const RunArguments& a) {
  v::ExperimentOptions o;
  o.file = IfGiven(a.experiment_file_option, a.experiment_file);
  o.scenario = IfGiven(a.scenario_option, a.scenario);
  o.estimators = IfGiven(a.estimator_option, a.estimators);
  o.particles = IfGiven(a.particles_option, a.particles);
  o.seeds = IfGiven(a.seeds_option, a.seeds);
  o.steps = IfGiven(a.steps_option, a.steps);
  o.jobs = IfGiven(a.jobs_option, a.jobs);
  o.name = IfGiven(a.experiment_name_option, a.experiment);
  o.pd = IfGiven(a.pd_option, a.detection_probability);
  o.clutter_rate = IfGiven(a.clutter_option, a.clutter_rate);
  o.data_dir = IfGiven(a.data_dir_option, a.data_dir);
  o.assignments = a.assignments;
  o.scenario_assignments = a.scenario_assignments;
  return o;
}

int Run(const RunArguments& a) {
  const v::Experiment experiment = v::ResolveExperiment(GivenOptions(a));
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

}  // namespace phdslam::apps
