#include "validation/runner/experiment_runner.h"

#include <stdexcept>

#include "validation/runner/results_io.h"
#include "validation/runner/results_layout.h"
#include "validation/runner/scenario_registry.h"

namespace phdslam::validation {
namespace {

// Prefixes an error with the experiment file's path, when the experiment has one.
[[noreturn]] void Rethrow(const Experiment& experiment, const std::invalid_argument& e) {
  if (experiment.source.is_object() && experiment.source.contains("path")) {
    throw std::invalid_argument(experiment.source.at("path").get<std::string>() + ": " + e.what());
  }
  throw e;
}

MonteCarloPlan BuildPlan(const Experiment& experiment, const ScenarioOptions& options,
                         const std::vector<EstimatorEntry>& table) {
  MonteCarloPlan plan;
  plan.experiment = experiment.name;
  plan.particles = experiment.particles;
  plan.seeds = experiment.seeds;
  for (const ExperimentEstimator& e : experiment.estimators) {
    plan.estimators.push_back({FindEstimator(table, e.name), e.overrides, e.particles});
  }
  plan.scenario = MakeScenarioSource(experiment.scenario, options);
  plan.experiment_file = experiment.source;
  return plan;
}

}  // namespace

std::string SweepFolderName(const std::string& parameter, double value) {
  return "sweep-" + parameter + "-" + FormatNumber(value);
}

std::vector<ExperimentPart> PlanExperiment(const Experiment& experiment,
                                           const std::filesystem::path& out,
                                           const std::vector<EstimatorEntry>& table) {
  try {
    ScenarioOptions options;
    options.data_dir = experiment.data_dir;
    options.steps = experiment.steps;
    options.detection_probability = experiment.pd;
    options.clutter_rate = experiment.clutter_rate;
    if (!experiment.sweep) return {{std::nullopt, out, BuildPlan(experiment, options, table)}};

    const ExperimentSweep& sweep = *experiment.sweep;
    const bool is_pd = sweep.parameter == kSweepParameterPd;
    if (!is_pd && sweep.parameter != kSweepParameterClutterRate) {
      throw std::invalid_argument("sweep parameter '" + sweep.parameter +
                                  "' is not one of: pd, clutter_rate");
    }
    if (sweep.values.empty()) throw std::invalid_argument("the sweep has no values");
    if ((is_pd && experiment.pd) || (!is_pd && experiment.clutter_rate)) {
      throw std::invalid_argument("'" + sweep.parameter + "' is swept; it cannot also be set (" +
                                  (is_pd ? "--pd" : "--clutter-rate") + " or scenario_options)");
    }
    std::vector<ExperimentPart> parts;
    for (double value : sweep.values) {
      ScenarioOptions swept = options;
      (is_pd ? swept.detection_probability : swept.clutter_rate) = value;
      parts.push_back({value, out / SweepFolderName(sweep.parameter, value),
                       BuildPlan(experiment, swept, table)});
    }
    return parts;
  } catch (const std::invalid_argument& e) {
    Rethrow(experiment, e);
  }
}

ExperimentReport RunExperiment(const Experiment& experiment, const ExperimentSettings& settings,
                               const std::vector<EstimatorEntry>& table) {
  ExperimentReport report;
  report.parts = PlanExperiment(experiment, settings.out, table);
  std::vector<MonteCarloSettings> part_settings;
  std::size_t offset = 0;
  for (const ExperimentPart& part : report.parts) {
    MonteCarloSettings s;
    s.out = part.out;
    s.jobs = experiment.jobs.value_or(0);
    s.show_progress = settings.show_progress;
    s.report_failures = settings.report_failures;
    s.stop = settings.stop;
    s.metrics = settings.metrics;
    s.shard = settings.shard;
    s.job_index_offset = offset;
    s.particles_trace = settings.particles_trace;
    s.map_ospa_trace = settings.map_ospa_trace;
    try {
      CheckMonteCarlo(part.plan, s);
    } catch (const std::invalid_argument& e) {
      Rethrow(experiment, e);
    }
    offset += PlanJobs(part.plan).size();
    part_settings.push_back(std::move(s));
  }
  for (std::size_t i = 0; i < report.parts.size(); ++i) {
    if (settings.stop != nullptr && settings.stop->load()) {
      report.interrupted = true;
      break;
    }
    report.reports.push_back(RunMonteCarlo(report.parts[i].plan, part_settings[i]));
    if (report.reports.back().interrupted) {
      report.interrupted = true;
      break;
    }
  }
  if (experiment.sweep) {
    WriteSweepFiles(settings.out, experiment.sweep->parameter, experiment.sweep->values);
  }
  return report;
}

void WriteSweepFiles(const std::filesystem::path& root, const std::string& parameter,
                     const std::vector<double>& values) {
  std::filesystem::create_directories(root);
  std::string table;
  std::string header;
  std::string header_source;
  nlohmann::json folders = nlohmann::json::array();
  for (double value : values) {
    const std::string folder = SweepFolderName(parameter, value);
    folders.push_back(folder);
    const std::filesystem::path summary = root / folder / kSummaryFile;
    if (!std::filesystem::exists(summary)) continue;
    const std::string text = ReadTextFile(summary);
    const std::size_t end = text.find('\n');
    const std::string first = text.substr(0, end);
    if (header.empty()) {
      header = first;
      header_source = summary.string();
      table = parameter + "," + header + "\n";
    } else if (first != header) {
      throw std::runtime_error(summary.string() + ": header differs from " + header_source);
    }
    std::size_t start = end == std::string::npos ? text.size() : end + 1;
    while (start < text.size()) {
      std::size_t stop = text.find('\n', start);
      if (stop == std::string::npos) stop = text.size();
      if (stop > start)
        table += FormatNumber(value) + "," + text.substr(start, stop - start) + "\n";
      start = stop + 1;
    }
  }
  if (header.empty()) table = CsvRow({parameter});
  const nlohmann::json sweep = {{"parameter", parameter}, {"values", values}, {"folders", folders}};
  WriteFileAtomically(root / kSweepFile, sweep.dump(2) + "\n");
  WriteFileAtomically(root / kSweepTableFile, table);
}

}  // namespace phdslam::validation
