#include "validation/runner/experiment/sweep.h"

#include <algorithm>
#include <stdexcept>

#include "datasets/simulation_limits.h"
#include "src/core/parameter_table.h"
#include "validation/runner/io/results_io.h"
#include "validation/runner/io/results_layout.h"
#include "validation/runner/registry/parameter_overrides.h"
#include "validation/runner/registry/scenario_shorthands.h"
#include "validation/runner/results/results_config.h"

namespace phdslam::validation {
namespace {

bool IsScenarioOption(const std::string& parameter, const std::vector<std::string>& options) {
  return FindScenarioShorthand(parameter) != nullptr ||
         std::find(options.begin(), options.end(), parameter) != options.end();
}

bool IsEstimatorParameter(const std::string& parameter, const std::vector<std::string>& options) {
  return parameter != kSweepParameterParticles && parameter != kSweepParameterSteps &&
         !IsScenarioOption(parameter, options);
}

// True when `overrides` already sets a key that `assignment` (a nested one-key object) sets.
bool SetsSameKey(const nlohmann::json& overrides, const nlohmann::json& assignment) {
  for (const auto& [key, value] : assignment.items()) {
    if (!overrides.is_object() || !overrides.contains(key)) continue;
    if (!value.is_object()) return true;
    if (SetsSameKey(overrides.at(key), value)) return true;
  }
  return false;
}

// Applies an estimator parameter's value as `--set parameter=value` would.
void SetEstimatorParameter(const std::string& parameter, const nlohmann::json& value,
                           Experiment& x) {
  const ParameterAssignment a = ParseParameterAssignment(parameter + "=" + value.dump());
  bool matched = false;
  for (ExperimentEstimator& e : x.estimators) {
    if (a.estimator.empty() || a.estimator == e.name) {
      MergeJsonObjects(e.overrides, a.overrides);
      matched = true;
    }
  }
  if (!matched) {
    throw std::invalid_argument("sweep parameter '" + parameter + "': estimator '" + a.estimator +
                                "' is not among the experiment's estimators");
  }
}

void SetSweptValue(const std::string& parameter, const nlohmann::json& value,
                   const std::vector<std::string>& options, Experiment& x) {
  const std::string where = "sweep parameter '" + parameter + "'";
  try {
    if (parameter == kSweepParameterParticles) {
      x.particles = {params::ReadInt(value, parameter, params::AtLeast(1))};
      for (ExperimentEstimator& e : x.estimators) e.particles.clear();
    } else if (parameter == kSweepParameterSteps) {
      x.steps = params::ReadInt(value, parameter, params::Between(0, datasets::kMaxSimulatedSteps));
    } else if (IsScenarioOption(parameter, options)) {
      SetScenarioOption(x, parameter, value);
    } else {
      SetEstimatorParameter(parameter, value, x);
    }
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    if (message.rfind("sweep parameter", 0) == 0) throw;
    throw std::invalid_argument(where + ": " + message);
  }
}

// The point's values as the leading cells of a sweep.csv row (with the trailing comma).
std::string SweepRow(const SweepPoint& point) {
  std::vector<std::string> cells;
  for (const nlohmann::json& value : point) cells.push_back(SweepValueText(value));
  std::string row = CsvRow(cells);
  row.back() = ',';
  return row;
}

// The non-empty lines of a text.
std::vector<std::string> NonEmptyLines(const std::string& text) {
  std::vector<std::string> lines;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t stop = text.find('\n', start);
    if (stop == std::string::npos) stop = text.size();
    if (stop > start) lines.push_back(text.substr(start, stop - start));
    start = stop + 1;
  }
  return lines;
}

}  // namespace

std::vector<SweepPoint> SweepPoints(const std::vector<ExperimentSweep>& sweep) {
  double grid = 1.0;
  std::string product;
  for (const ExperimentSweep& dimension : sweep) {
    grid *= static_cast<double>(dimension.values.size());
    product += (product.empty() ? "" : " x ") + dimension.parameter + " (" +
               std::to_string(dimension.values.size()) + ")";
  }
  if (grid > kMaxSweepPoints) {
    throw std::invalid_argument("sweep: the grid " + product + " has " + FormatNumber(grid) +
                                " points, more than the cap of " + FormatNumber(kMaxSweepPoints) +
                                "; split it over several experiments");
  }
  std::vector<SweepPoint> points = {{}};
  for (const ExperimentSweep& dimension : sweep) {
    std::vector<SweepPoint> longer;
    for (const SweepPoint& prefix : points) {
      for (const nlohmann::json& value : dimension.values) {
        SweepPoint p = prefix;
        p.push_back(value);
        longer.push_back(std::move(p));
      }
    }
    points = std::move(longer);
  }
  return points;
}

std::string SweepValueText(const nlohmann::json& value) {
  if (value.is_number()) return FormatNumber(value.get<double>());
  if (value.is_string()) return value.get<std::string>();
  return value.dump();
}

std::string SweepFolderName(const std::vector<ExperimentSweep>& sweep, const SweepPoint& point) {
  std::string name = "sweep";
  for (std::size_t i = 0; i < sweep.size() && i < point.size(); ++i) {
    std::string parameter = sweep[i].parameter;
    std::replace(parameter.begin(), parameter.end(), ':', '.');
    std::string value = SweepValueText(point[i]);
    std::replace(value.begin(), value.end(), '/', '_');
    name += "-" + parameter + "-" + value;
  }
  return name;
}

std::string DescribeSweepPoint(const std::vector<ExperimentSweep>& sweep, const SweepPoint& point) {
  std::string text;
  for (std::size_t i = 0; i < sweep.size() && i < point.size(); ++i) {
    text += (i > 0 ? ", " : "") + sweep[i].parameter + " = " + SweepValueText(point[i]);
  }
  return text;
}

Experiment ApplySweepPoint(const Experiment& experiment,
                           const std::vector<std::string>& scenario_options,
                           const SweepPoint& point) {
  Experiment x = experiment;
  for (std::size_t i = 0; i < experiment.sweep.size() && i < point.size(); ++i) {
    SetSweptValue(experiment.sweep[i].parameter, point[i], scenario_options, x);
  }
  return x;
}

void CheckSweepNotSet(const Experiment& x, const std::vector<std::string>& scenario_options) {
  for (const ExperimentSweep& d : x.sweep) {
    const std::string& p = d.parameter;
    if (d.values.empty()) throw std::invalid_argument("sweep parameter '" + p + "' has no values");
    bool set = SetsScenarioOption(x, p) || (p == kSweepParameterSteps && x.steps != 0);
    if (IsEstimatorParameter(p, scenario_options)) {
      const ParameterAssignment a = ParseParameterAssignment(p + "=0");
      for (const ExperimentEstimator& e : x.estimators) {
        if ((a.estimator.empty() || a.estimator == e.name) &&
            SetsSameKey(e.overrides, a.overrides)) {
          set = true;
        }
      }
    }
    if (set) {
      throw std::invalid_argument("'" + p +
                                  "' is swept; it cannot also be set (scenario_options, --pd, "
                                  "--clutter-rate, --scenario-set, steps, set or --set)");
    }
  }
}

void WriteSweepFiles(const std::filesystem::path& root, const std::vector<ExperimentSweep>& sweep) {
  std::filesystem::create_directories(root);
  std::string table;
  std::string header;
  std::string header_source;
  nlohmann::json folders = nlohmann::json::array();
  for (const SweepPoint& point : SweepPoints(sweep)) {
    const std::string folder = SweepFolderName(sweep, point);
    folders.push_back(folder);
    const std::filesystem::path summary = root / folder / kSummaryFile;
    if (!std::filesystem::exists(summary)) continue;
    const std::vector<std::string> lines = NonEmptyLines(ReadTextFile(summary));
    if (lines.empty()) continue;
    if (header.empty()) {
      header = lines.front();
      header_source = summary.string();
    } else if (lines.front() != header) {
      throw std::runtime_error(summary.string() + ": header differs from " + header_source);
    }
    for (std::size_t i = 1; i < lines.size(); ++i) table += SweepRow(point) + lines[i] + "\n";
  }
  std::vector<std::string> names;
  nlohmann::json parameters = nlohmann::json::array();
  for (const ExperimentSweep& d : sweep) {
    names.push_back(d.parameter);
    parameters.push_back({{"parameter", d.parameter}, {"values", d.values}});
  }
  std::string first_line = CsvRow(names);
  if (!header.empty()) first_line.insert(first_line.size() - 1, "," + header);
  nlohmann::json json = {{"parameters", parameters}, {"folders", folders}};
  if (sweep.size() == 1) {
    json["parameter"] = sweep.front().parameter;
    json["values"] = sweep.front().values;
  }
  WriteFileAtomically(root / kSweepFile, JsonFileText(json));
  WriteFileAtomically(root / kSweepTableFile, first_line + table);
}

std::vector<ExperimentSweep> ReadSweepFile(const std::filesystem::path& root) {
  const std::filesystem::path path = root / kSweepFile;
  if (!std::filesystem::exists(path)) return {};
  const nlohmann::json j = ReadJsonObject(path);
  std::vector<ExperimentSweep> sweep;
  try {
    if (j.contains("parameters")) {
      for (const nlohmann::json& d : j.at("parameters")) {
        sweep.push_back({d.at("parameter").get<std::string>(),
                         d.at("values").get<std::vector<nlohmann::json>>()});
      }
    } else {
      sweep.push_back({j.at("parameter").get<std::string>(),
                       j.at("values").get<std::vector<nlohmann::json>>()});
    }
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(path.string() + ": expected 'parameters' (or 'parameter' and " +
                             "'values'): " + e.what());
  }
  if (sweep.empty()) throw std::runtime_error(path.string() + ": 'parameters' is empty");
  return sweep;
}

std::vector<std::filesystem::path> ResultsFolders(const std::filesystem::path& root) {
  const std::vector<ExperimentSweep> sweep = ReadSweepFile(root);
  if (sweep.empty()) return {root};
  std::vector<std::filesystem::path> folders;
  for (const SweepPoint& point : SweepPoints(sweep)) {
    const std::filesystem::path folder = root / SweepFolderName(sweep, point);
    if (std::filesystem::exists(folder / kRunsTableFile)) folders.push_back(folder);
  }
  return folders;
}

}  // namespace phdslam::validation
