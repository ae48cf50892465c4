// Sweeps: an experiment run once per point of a one-dimensional list of values or of a grid over
// several parameters, each point into <out>/sweep-<parameter>-<value>[-<parameter>-<value>...]/,
// and the root files sweep.csv (one leading column per swept parameter) and sweep.json.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "validation/runner/experiment/experiment_file.h"

namespace phdslam::validation {

/// One combination of values, one per swept parameter (in the order of the sweep).
using SweepPoint = std::vector<nlohmann::json>;

/// Largest number of points of a sweep grid (the product of its value counts).
inline constexpr double kMaxSweepPoints = 10000;

/// Every point of the sweep: the first parameter varies slowest, the last fastest. One point
/// (empty) without a sweep. Throws std::invalid_argument naming the parameters when the grid has
/// more than kMaxSweepPoints points (checked before any point is built).
std::vector<SweepPoint> SweepPoints(const std::vector<ExperimentSweep>& sweep);

/// A value as it appears in folder names and sweep.csv: numbers as %.10g, true/false, names as
/// given.
std::string SweepValueText(const nlohmann::json& value);

/// "sweep-<parameter>-<value>" for each parameter in turn (':' of an estimator prefix becomes
/// '.'), e.g. "sweep-pd-0.3" or "sweep-clutter_rate-5-pd-0.9".
std::string SweepFolderName(const std::vector<ExperimentSweep>& sweep, const SweepPoint& point);

/// "<parameter> = <value>, ..." of a sweep point, for messages.
std::string DescribeSweepPoint(const std::vector<ExperimentSweep>& sweep, const SweepPoint& point);

/// The experiment of one sweep point: `experiment` with every swept parameter set to the point's
/// value. `scenario_options` are the keys of the scenario's option table. A parameter is, in
/// this order, `particles` (every estimator's count), `steps`, `pd` or `clutter_rate`, an option
/// of the scenario, or an estimator parameter as `--set` names it ([estimator:]key[.subkey]).
/// Throws std::invalid_argument naming the parameter for a value of the wrong type (particles,
/// steps, pd, clutter_rate) or an estimator prefix that is not among the experiment's estimators.
Experiment ApplySweepPoint(const Experiment& experiment,
                           const std::vector<std::string>& scenario_options,
                           const SweepPoint& point);

/// Throws std::invalid_argument naming the parameter when a swept parameter is also set by the
/// experiment (scenario_options, --pd, --clutter-rate, --scenario-set, a `set` or --set of an
/// estimator, steps), or when a parameter has no values.
void CheckSweepNotSet(const Experiment& experiment,
                      const std::vector<std::string>& scenario_options);

/// Writes <root>/sweep.json ({"parameters": [{"parameter", "values"}...], "folders"}, plus
/// "parameter" and "values" for a one-dimensional sweep) and <root>/sweep.csv: one leading
/// column per parameter, then the columns of the first folder's summary.csv, then the rows of
/// every point's summary.csv (in point order) after the point's values. Folders without
/// summary.csv are left out. Throws std::runtime_error when the summaries' headers differ.
void WriteSweepFiles(const std::filesystem::path& root, const std::vector<ExperimentSweep>& sweep);

/// The sweep of a sweep root's sweep.json, or an empty list when the folder has none. Reads both
/// forms (with "parameters", and the one-dimensional "parameter"/"values" of earlier versions).
/// Throws std::runtime_error for a malformed file.
std::vector<ExperimentSweep> ReadSweepFile(const std::filesystem::path& root);

/// The results folders under `root`: for a sweep root (with sweep.json, read by ReadSweepFile),
/// the folder of every sweep point that holds runs.csv, in point order; otherwise `root` itself.
std::vector<std::filesystem::path> ResultsFolders(const std::filesystem::path& root);

}  // namespace phdslam::validation
