#include "apps/phdslam/interchange_commands.h"

#include <cstdint>
#include <filesystem>
#include <iostream>
#include <map>
#include <stdexcept>

#include "apps/phdslam/sign_validators.h"
#include "validation/runner/experiment/experiment_runner.h"
#include "validation/runner/experiment/option_precedence.h"
#include "validation/runner/interchange/ingest.h"
#include "validation/runner/interchange/scenario_export.h"
#include "validation/runner/io/results_layout.h"

namespace phdslam::apps {

namespace v = phdslam::validation;

namespace {

// Throws "<command>: --scenario is required<alternative>" for the first required scenario option
// not given.
void RequireScenarioOptions(const ExperimentOptionSet& options, const std::string& command,
                            const std::string& alternative) {
  const std::map<std::string, nlohmann::json> given = options.Given();
  for (const v::ExperimentKey& key : v::ExperimentKeys()) {
    if (key.export_option && key.required && !given.contains(key.option)) {
      throw std::invalid_argument(command + ": " + key.option + " is required" + alternative);
    }
  }
}

// The experiment holding a scenario and its options, as `run` would resolve them.
v::Experiment ScenarioExperiment(const ExperimentOptionSet& options) {
  v::Experiment x;
  v::ApplyGivenOptions(options.Given(), x);
  return x;
}

v::ScenarioSource SourceOf(const v::Experiment& x) {
  return v::PlanExperiment(x, {}, v::EstimatorTable()).front().plan.scenario;
}

// The scenario of an export folder, from its export.json: the scenario options given with
// --export are refused; --seeds selects among its seeds, --data-dir is a machine setting.
v::Experiment ExportedExperiment(const IngestArguments& a) {
  const std::map<std::string, nlohmann::json> given = a.scenario.Given();
  for (const v::ExperimentKey& key : v::ExperimentKeys()) {
    const bool selects = key.option == "--seeds" || key.machine_setting;
    if (given.contains(key.option) && !selects) {
      throw std::invalid_argument("ingest: " + key.option +
                                  " and --export both give the scenario; give one");
    }
  }
  v::Experiment x = v::ReadExportManifest(a.export_dir);
  v::ApplyGivenOptions(given, x);
  return x;
}

}  // namespace

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
  a.scenario.AddTo(command, ExperimentOptionSet::Keys::kExport);
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
  a.scenario.AddTo(command, ExperimentOptionSet::Keys::kExport);
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
      ->check(SignValidator(true));
  command->add_flag("--replace", a.replace,
                    "Replace the runs the estimator already has in --out (without it an estimator "
                    "name that already has runs there is refused); the replaced run folders are "
                    "listed");
}

int Export(const ExportArguments& a) {
  RequireScenarioOptions(a.scenario, "export", "");
  v::RequireEmptyExportFolder(a.out);
  const v::Experiment x = ScenarioExperiment(a.scenario);
  const v::ScenarioSource source = SourceOf(x);
  std::vector<datasets::Scenario> scenarios;
  for (std::uint64_t seed : x.seeds) scenarios.push_back(source.make(seed));
  v::ExportDescription description;
  description.scenario = source.name;
  description.options = source.options;
  description.request = v::ExportRequest(x);
  description.seeds = x.seeds;
  v::WriteExport(a.out, description, scenarios);
  std::cout << "export: " << a.out << " (" << scenarios.size() << " seeds of " << source.name
            << ", format version " << v::kExportFormatVersion << "; checksums in "
            << (std::filesystem::path(a.out) / v::kExportChecksumFile).string() << ")\n";
  return 0;
}

int Ingest(const IngestArguments& a) {
  const bool from_export = !a.export_dir.empty();
  if (!from_export) RequireScenarioOptions(a.scenario, "ingest", " (or give --export)");
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

}  // namespace phdslam::apps
