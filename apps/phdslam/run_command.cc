#include "apps/phdslam/run_command.h"

#include <cstddef>
#include <filesystem>
#include <iostream>

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
      "validation/README.md). At most 10^6 runs (seeds x estimators x particle counts x sweep "
      "points) per results folder.");
  a.experiment_file_option =
      run->add_option("--experiment", a.experiment_file,
                      "Experiment file (YAML, e.g. validation/experiments/quick.yaml); "
                      "--scenario, --estimator and --seeds are then optional")
          ->check(CLI::ExistingFile);
  a.experiment.AddTo(run, ExperimentOptionSet::Keys::kAll);
  run->add_option("--out", a.out, "Results folder (created if needed)")->required();
  run->add_option("--shard", a.shard,
                  "Run only shard i of n: the jobs whose index in the experiment's job order is "
                  "i-1 modulo n (join the shards' folders with `phdslam merge`)");
  run->add_flag("--particles-trace", a.particles_trace,
                "Also write particles.csv (step,particle,x,y,log_weight) per run, for estimators "
                "that expose their particles");
  run->add_flag("--quiet", a.quiet, "No progress line and no summary table");
}

namespace {

// A deterministic estimator beside particle filters runs at N = 1 whatever --particles lists:
// said under the table, so that N = 1 in its row is not taken for a lost setting.
void PrintHeldAtOneParticle(const v::MonteCarloPlan& plan) {
  for (const v::EstimatorSelection& s : plan.estimators) {
    if (!s.held_at_one_particle) continue;
    std::cout << "note: " << s.entry.name << " is deterministic (no particles) and ran at N = 1 "
              << "only; the other particle counts are for the other estimators\n";
  }
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
    PrintHeldAtOneParticle(part.plan);
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
  if (a.experiment_file_option->count() > 0) o.file = a.experiment_file;
  o.given = a.experiment.Given();
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
  settings.map_ospa_trace =
      experiment.map_ospa.value_or(false) || experiment.map_ospa_cutoff.has_value();
  if (experiment.map_ospa_cutoff) settings.metrics.map_ospa_c = *experiment.map_ospa_cutoff;
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
