// `phdslam export`: the inputs of a filter for each Monte Carlo seed of a scenario, written as
// language-neutral files (CSV, JSON, TUM) that an external filter reads, with the truth in a
// separate folder and a SHA-256 checksum file. The format is documented in
// validation/EXPORT_FORMAT.md; kExportFormatVersion changes with every incompatible change.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "datasets/scenario.h"
#include "validation/runner/experiment/experiment_file.h"

namespace phdslam::validation {

inline constexpr int kExportFormatVersion = 1;
inline constexpr const char* kExportManifestFile = "export.json";
inline constexpr const char* kExportChecksumFile = "SHA256SUMS";

/// The files of one seed's export: path relative to the export folder -> content. Inputs go to
/// seed-<s>/ (steps.csv, controls.csv, measurements.csv, models.json), the truth to
/// truth/seed-<s>/ (trajectory.tum, map.csv, gps.csv, origins.csv; those the scenario has). Numbers
/// are written in the shortest text that reads back as exactly the same double.
std::map<std::string, std::string> ExportFiles(const datasets::Scenario& scenario);

/// models.json of a scenario: initial pose, motion model with its control noise, sensor model
/// with its noise, field of view, detection and clutter model.
nlohmann::json ModelsJson(const datasets::Scenario& scenario);

/// What export.json records besides the seeds: the scenario's name, its resolved options (as
/// config.json stores them) and the options as given (`request`: steps, pd, clutter_rate,
/// settings), from which `phdslam ingest --export` rebuilds the same scenario.
struct ExportDescription {
  std::string scenario;
  nlohmann::json options = nlohmann::json::object();
  nlohmann::json request = nlohmann::json::object();
  std::vector<std::uint64_t> seeds;
};

/// Throws std::invalid_argument when `out` exists and is not an empty folder: an export is
/// written into a new or empty folder only, so that SHA256SUMS lists every file in it and no
/// file of an earlier export is left beside the new one.
void RequireEmptyExportFolder(const std::filesystem::path& out);

/// Writes the export of every scenario in `scenarios` (one per seed, in the order of
/// description.seeds) into `out` (created if needed; RequireEmptyExportFolder): the files of
/// ExportFiles, export.json and SHA256SUMS ("<hex>  <relative path>" per file, as `sha256sum -c`
/// reads it; export.json included). Files are written atomically. Throws std::runtime_error naming
/// a file that cannot be written.
void WriteExport(const std::filesystem::path& out, const ExportDescription& description,
                 const std::vector<datasets::Scenario>& scenarios);

/// The SHA-256 checksums of SHA256SUMS in `folder`: relative path -> hex digest. Throws
/// std::runtime_error naming the file and line for a malformed line or a missing file.
std::map<std::string, std::string> ReadExportChecksums(const std::filesystem::path& folder);

/// export.json's `request` of an experiment: the scenario options as given, one per key of the
/// experiment key table with a manifest_key (steps; pd and clutter_rate, null when not set;
/// settings, the other scenario options), from which ReadExportManifest rebuilds the same
/// experiment.
nlohmann::json ExportRequest(const Experiment& experiment);

/// The experiment of an export folder, from its export.json (as WriteExport writes it): the
/// scenario, the options of its `request` and its seeds. Throws std::runtime_error naming the
/// file when it is missing or not a JSON object, when its format_version is not
/// kExportFormatVersion ("<path>: format_version 2, this program reads 1"), or when a key is
/// missing or of the wrong type.
Experiment ReadExportManifest(const std::filesystem::path& export_dir);

}  // namespace phdslam::validation
