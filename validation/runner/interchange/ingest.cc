#include "validation/runner/interchange/ingest.h"

#include <algorithm>
#include <chrono>
#include <map>
#include <stdexcept>

#include "datasets/sha256.h"
#include "datasets/text_fields.h"
#include "validation/runner/execution/monte_carlo.h"
#include "validation/runner/interchange/scenario_export.h"
#include "validation/runner/io/results_io.h"
#include "validation/runner/io/results_layout.h"
#include "validation/runner/registry/estimator_registry.h"
#include "validation/runner/results/results_config.h"
#include "validation/runner/results/results_lock.h"
#include "validation/runner/results/run_files.h"
#include "validation/runner/results/summary.h"

namespace phdslam::validation {
namespace {

namespace text = datasets::text;

// Regenerates the seed's export files and compares them with the export's checksums.
void CheckAgainstExport(const std::filesystem::path& export_dir,
                        const std::map<std::string, std::string>& sums,
                        const datasets::Scenario& scenario) {
  for (const auto& [path, content] : ExportFiles(scenario)) {
    const auto it = sums.find(path);
    if (it == sums.end()) {
      throw std::runtime_error((export_dir / kExportChecksumFile).string() + ": no checksum of " +
                               path + " (seed " + std::to_string(scenario.seed) +
                               " is not in this export)");
    }
    if (it->second != datasets::Sha256Hex(content)) {
      throw std::invalid_argument(
          (export_dir / path).string() +
          ": the scenario rebuilt here differs from the exported one (other scenario options, "
          "data files or program version); export again or give the options it was made with");
    }
  }
}

nlohmann::json ReadParameters(const std::filesystem::path& from) {
  const std::filesystem::path path = from / kExternalParametersFile;
  if (!std::filesystem::exists(path)) return nlohmann::json::object();
  return ReadJsonObject(path);
}

void CheckName(const std::string& name) {
  if (name.empty() || name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                             "0123456789._-") != std::string::npos) {
    throw std::invalid_argument("ingest: estimator name '" + text::Printable(name) +
                                "' must be letters, digits, '.', '_' or '-'");
  }
  for (const EstimatorEntry& e : EstimatorTable()) {
    if (e.name == name) {
      throw std::invalid_argument("ingest: '" + name +
                                  "' is a registered estimator; give the external one its own "
                                  "name");
    }
  }
}

struct IngestedRun {
  datasets::Scenario scenario;
  RunRecord record;
  RunEvaluation evaluation;
  nlohmann::json identity;
};

nlohmann::json IngestConfig(const IngestRequest& request, const nlohmann::json& parameters) {
  std::vector<std::uint64_t> seeds = request.seeds;
  std::sort(seeds.begin(), seeds.end());
  const nlohmann::json estimator = {
      {"description", request.description},
      {"batch", false},
      {"overrides", nlohmann::json::object()},
      {"parameters", {{std::to_string(request.particles), parameters}}}};
  return {{"program", {{"name", "phdslam"}, {"version", ProgramVersion()}}},
          {"experiment", request.experiment},
          {"scenario", {{"name", request.scenario.name}, {"options", request.scenario.options}}},
          {"seeds", seeds},
          {"particles", {request.particles}},
          {"estimators", {{request.estimator, estimator}}},
          {"metrics",
           {{"gospa_c", request.metrics.gospa_c},
            {"gospa_p", request.metrics.gospa_p},
            {"gps_window_s", request.metrics.gps_window_s}}}};
}

// config.json of `out` joined with the ingested estimator's; throws when they conflict.
nlohmann::json JoinedConfig(const std::filesystem::path& out, const nlohmann::json& fresh) {
  const std::filesystem::path path = out / kConfigFile;
  if (!std::filesystem::exists(path)) return fresh;
  const nlohmann::json existing = ReadJsonObject(path);
  const std::string conflict = ConfigConflict(existing, fresh, path.string());
  if (!conflict.empty()) {
    throw std::invalid_argument(out.string() + " holds results made with other settings: " +
                                conflict + "; use another --out or remove it");
  }
  nlohmann::json joined = UnionConfig(existing, fresh);
  for (const auto& [key, value] : existing.items()) {
    if (!fresh.contains(key)) joined[key] = value;  // jobs, experiment_file, seed_derivation
  }
  return joined;
}

IngestedRun IngestSeed(const IngestRequest& request, const nlohmann::json& parameters,
                       const std::map<std::string, std::string>* sums, std::uint64_t seed) {
  IngestedRun run;
  run.scenario = request.scenario.make(seed);
  if (sums != nullptr) CheckAgainstExport(*request.export_dir, *sums, run.scenario);
  const std::filesystem::path folder = request.from / SeedFolderName(seed);
  if (!std::filesystem::is_directory(folder)) {
    throw std::runtime_error(folder.string() + ": missing (no output for seed " +
                             std::to_string(seed) + ")");
  }
  run.record = ReadExternalRun(folder, run.scenario, request.estimator, request.particles);
  run.record.stream_seed =
      RunStreamSeed(request.experiment, seed, request.estimator, request.particles);
  run.evaluation = EvaluateRun(run.record, run.scenario, request.metrics);
  if (const std::string why = NonFiniteMetrics(run.evaluation.metrics); !why.empty()) {
    throw std::runtime_error(folder.string() + ": " + why);
  }
  run.identity = {{"estimator", request.estimator},
                  {"particles", request.particles},
                  {"seed", seed},
                  {"stream_seed", run.record.stream_seed},
                  {"experiment", request.experiment},
                  {"scenario", request.scenario.name},
                  {"scenario_options", request.scenario.options},
                  {"parameters", parameters},
                  {"program_version", ProgramVersion()},
                  {"ingested_from", std::filesystem::absolute(folder).lexically_normal().string()}};
  return run;
}

// Checks every file SHA256SUMS lists against its bytes on disk (as `sha256sum -c` does), so an
// export edited after it was written is refused; paths must stay inside the export folder.
void VerifyExportOnDisk(const std::filesystem::path& export_dir,
                        const std::map<std::string, std::string>& sums) {
  const std::filesystem::path list = export_dir / kExportChecksumFile;
  for (const auto& [name, hex] : sums) {
    const std::filesystem::path relative(name);
    bool escapes = relative.is_absolute() || relative.has_root_name();
    for (const std::filesystem::path& part : relative) escapes = escapes || part == "..";
    if (escapes) {
      throw std::runtime_error(list.string() + ": '" + text::Printable(name) +
                               "' is not a path inside the export folder");
    }
    const std::filesystem::path file = export_dir / relative;
    if (!std::filesystem::is_regular_file(file)) {
      throw std::runtime_error(file.string() + ": listed in " + list.string() + " but missing");
    }
    if (datasets::FileSha256Hex(file) != hex) {
      throw std::runtime_error(file.string() + ": its SHA-256 differs from " + list.string() +
                               " (the file was changed after export; export again)");
    }
  }
}

// The run folders of `estimator` (any particle count) already in `out`.
std::vector<std::filesystem::path> ExistingRunFolders(const std::filesystem::path& out,
                                                      const std::string& estimator) {
  std::vector<std::filesystem::path> folders;
  const std::filesystem::path runs = out / kRunsFolder;
  if (!std::filesystem::is_directory(runs)) return folders;
  const std::string prefix = estimator + "-N";
  for (const auto& group : std::filesystem::directory_iterator(runs)) {
    const std::string name = group.path().filename().string();
    if (!group.is_directory() || name.rfind(prefix, 0) != 0 || name.size() == prefix.size() ||
        name.find_first_not_of("0123456789", prefix.size()) != std::string::npos) {
      continue;
    }
    for (const auto& run : std::filesystem::directory_iterator(group.path())) {
      if (run.is_directory()) folders.push_back(run.path());
    }
  }
  std::sort(folders.begin(), folders.end());
  return folders;
}

// "runs/a-N1/seed-1, runs/a-N1/seed-2, ..." (at most five named).
std::string DescribeFolders(const std::filesystem::path& out,
                            const std::vector<std::filesystem::path>& folders) {
  std::string text;
  for (std::size_t i = 0; i < folders.size() && i < 5; ++i) {
    text += (i > 0 ? ", " : "") + folders[i].lexically_relative(out).generic_string();
  }
  if (folders.size() > 5) text += ", ... (" + std::to_string(folders.size()) + " in all)";
  return text;
}

}  // namespace

IngestReport IngestResults(const IngestRequest& request, const std::filesystem::path& out) {
  const auto start = std::chrono::steady_clock::now();
  CheckName(request.estimator);
  if (request.particles < 1) throw std::invalid_argument("ingest: --particles must be >= 1");
  if (request.seeds.empty()) throw std::invalid_argument("ingest: no seed given");
  if (!std::filesystem::is_directory(request.from)) {
    throw std::runtime_error(request.from.string() + ": not a folder");
  }
  const nlohmann::json parameters = ReadParameters(request.from);
  std::optional<std::map<std::string, std::string>> sums;
  if (request.export_dir) {
    sums = ReadExportChecksums(*request.export_dir);
    VerifyExportOnDisk(*request.export_dir, *sums);
  }
  std::vector<IngestedRun> runs;
  for (std::uint64_t seed : request.seeds) {
    runs.push_back(IngestSeed(request, parameters, sums ? &*sums : nullptr, seed));
  }

  std::filesystem::create_directories(out);
  const ResultsLock lock(out);
  const nlohmann::json config = JoinedConfig(out, IngestConfig(request, parameters));
  IngestReport report;
  report.replaced = ExistingRunFolders(out, request.estimator);
  if (!report.replaced.empty() && !request.replace) {
    throw std::invalid_argument("ingest: " + out.string() + " already holds " +
                                std::to_string(report.replaced.size()) + " runs of estimator '" +
                                request.estimator + "' (" + DescribeFolders(out, report.replaced) +
                                "); give --replace to replace them, or another --estimator name");
  }
  // Every run is written into a staging folder first; only when all are written are they moved
  // into place, so a failure leaves the results folder as it was.
  const std::filesystem::path staging = out / kIngestStagingFolder;
  std::filesystem::remove_all(staging);
  try {
    for (const IngestedRun& run : runs) {
      WriteRunFiles(RunFolder(staging, request.estimator, request.particles, run.scenario.seed),
                    run.record, run.scenario, run.evaluation, run.identity);
    }
  } catch (...) {
    std::filesystem::remove_all(staging);
    throw;
  }
  for (const std::filesystem::path& folder : report.replaced) {
    std::filesystem::remove_all(folder);
    if (std::filesystem::is_empty(folder.parent_path())) {
      std::filesystem::remove(folder.parent_path());
    }
  }
  const std::filesystem::path group =
      out / kRunsFolder / GroupFolderName(request.estimator, request.particles);
  std::filesystem::create_directories(group.parent_path());
  std::filesystem::rename(staging / kRunsFolder / group.filename(), group);
  std::filesystem::remove_all(staging);
  if (!std::filesystem::exists(out / kTruthMapFile)) {
    const auto lowest = std::min_element(
        runs.begin(), runs.end(),
        [](const auto& a, const auto& b) { return a.scenario.seed < b.scenario.seed; });
    WriteRootTruthMap(out, lowest->scenario);
  }
  for (const IngestedRun& run : runs) WriteTruthFiles(out, run.scenario, "ingest");
  WriteFileAtomically(out / kConfigFile, JsonFileText(config));
  WriteSummaryFiles(out);
  report.runs = runs.size();
  report.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const nlohmann::json timing = {
      {"wall_seconds", report.wall_seconds},
      {"ingested_from", std::filesystem::absolute(request.from).lexically_normal().string()},
      {"runs_ingested", report.runs}};
  WriteFileAtomically(out / kTimingFile, JsonFileText(timing));
  return report;
}

}  // namespace phdslam::validation
