#include "validation/runner/interchange/external_run_reader.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>

#include "datasets/map_io.h"
#include "datasets/text_fields.h"
#include "datasets/trajectory_io.h"

namespace phdslam::validation {
namespace {

namespace text = datasets::text;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
/// Largest difference (s) between a trajectory's time stamp and the step's.
constexpr double kTimeTolerance = 1e-6;
/// Relative tolerance of the positive semi-definiteness test of a covariance.
constexpr double kDefinitenessTolerance = 1e-9;

[[noreturn]] void Fail(const std::filesystem::path& path, std::size_t line,
                       const std::string& what) {
  throw std::runtime_error(text::Where(path, line) + ": " + what);
}

// The lines of a text file; throws naming the file when it cannot be read.
std::vector<std::string> ReadLines(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path.string() + ": cannot be read");
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

bool Skipped(std::string_view line) {
  const std::string_view t = text::Trim(line);
  return t.empty() || t.front() == '#';
}

// A CSV file of numbers with named columns: the values of `columns` per data line, with the
// line's number. Every value must be a finite number.
struct NumericRows {
  std::vector<std::vector<double>> values;
  std::vector<std::size_t> lines;
};

NumericRows ReadNumericCsv(const std::filesystem::path& path,
                           const std::vector<std::string>& columns) {
  const std::vector<std::string> lines = ReadLines(path);
  std::size_t i = 0;
  while (i < lines.size() && Skipped(lines[i])) ++i;
  if (i == lines.size()) throw std::runtime_error(path.string() + ": no header line");
  const std::vector<std::string_view> header = text::SplitFields(lines[i], ',');
  std::vector<std::size_t> index;
  for (const std::string& c : columns) {
    std::size_t found = header.size();
    for (std::size_t h = 0; h < header.size(); ++h) {
      if (header[h] == c) found = h;
    }
    if (found == header.size()) Fail(path, i + 1, "no column '" + c + "' in the header");
    index.push_back(found);
  }
  NumericRows rows;
  for (++i; i < lines.size(); ++i) {
    if (Skipped(lines[i])) continue;
    const std::vector<std::string_view> fields = text::SplitFields(lines[i], ',');
    if (fields.size() != header.size()) {
      Fail(path, i + 1,
           std::to_string(fields.size()) + " fields, the header has " +
               std::to_string(header.size()));
    }
    std::vector<double> row;
    for (std::size_t c = 0; c < columns.size(); ++c) {
      const std::optional<double> v = text::ParseDouble(fields[index[c]]);
      if (!v || !std::isfinite(*v)) {
        Fail(path, i + 1,
             "column '" + columns[c] + "': '" + text::Printable(fields[index[c]]) +
                 "' is not a finite number");
      }
      if (std::abs(*v) > kMaxIngestedValue) {
        Fail(path, i + 1,
             "column '" + columns[c] + "': " + text::FormatDouble(*v) + " is beyond +-" +
                 text::FormatDouble(kMaxIngestedValue));
      }
      row.push_back(*v);
    }
    rows.values.push_back(std::move(row));
    rows.lines.push_back(i + 1);
  }
  return rows;
}

// An index column's value as an integer in [0, limit).
std::size_t IndexValue(double v, std::size_t limit, const std::filesystem::path& path,
                       std::size_t line, const std::string& column) {
  if (v < 0 || v != std::floor(v) || v >= static_cast<double>(limit)) {
    Fail(path, line,
         column + " " + text::FormatDouble(v) + " is not an integer in [0, " +
             std::to_string(limit) + ")");
  }
  return static_cast<std::size_t>(v);
}

// The 1-based line numbers of a TUM file's data lines.
std::vector<std::size_t> TumDataLines(const std::filesystem::path& path) {
  const std::vector<std::string> lines = ReadLines(path);
  std::vector<std::size_t> numbers;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (!Skipped(lines[i])) numbers.push_back(i + 1);
  }
  return numbers;
}

void ReadTrajectory(const std::filesystem::path& path, RunRecord& record) {
  const std::vector<datasets::StampedPose> poses = datasets::ReadTumTrajectory(path);
  const std::size_t n = record.step_times.size();
  if (poses.size() != n) {
    throw std::runtime_error(path.string() + ": " + std::to_string(poses.size()) +
                             " poses, the scenario has " + std::to_string(n) +
                             " steps (one pose per step, at the step's time stamp)");
  }
  const std::vector<std::size_t> lines = TumDataLines(path);
  for (std::size_t k = 0; k < n; ++k) {
    const double t = record.step_times[k];
    if (std::abs(poses[k].t - t) > kTimeTolerance * std::max(1.0, std::abs(t))) {
      Fail(path, k < lines.size() ? lines[k] : 0,
           "time stamp " + text::FormatDouble(poses[k].t) + " of pose " + std::to_string(k) +
               ", step " + std::to_string(k) + " is at t = " + text::FormatDouble(t));
    }
    if (std::abs(poses[k].pose(0)) > kMaxIngestedValue ||
        std::abs(poses[k].pose(1)) > kMaxIngestedValue) {
      Fail(path, k < lines.size() ? lines[k] : 0,
           "position of pose " + std::to_string(k) + " is beyond +-" +
               text::FormatDouble(kMaxIngestedValue) + " m");
    }
    record.poses.push_back(poses[k].pose);
  }
}

void ReadMap(const std::filesystem::path& path, RunRecord& record) {
  datasets::MapValueLimits limits;
  limits.max_weight = 1.0;
  limits.max_abs_value = kMaxIngestedValue;
  const std::vector<datasets::MapPoint> points = datasets::ReadMapCsv(path, limits);
  filters::MapEstimate& map = record.final_map;
  std::size_t with_cov = 0;
  for (const datasets::MapPoint& p : points) {
    map.means.push_back(p.position);
    // weight > 0: its log; absent or 0: a map without weights (written as weight 1).
    map.log_weights.push_back(p.weight > 0.0 ? std::log(p.weight) : 0.0);
    if (p.cov) {
      map.covs.push_back(*p.cov);
      ++with_cov;
    }
  }
  if (with_cov != 0 && with_cov != points.size()) {
    throw std::runtime_error(path.string() + ": " + std::to_string(with_cov) + " of " +
                             std::to_string(points.size()) +
                             " landmarks have a covariance; give it for all or none");
  }
}

// The rule map.csv applies to its covariances, for a 3 x 3 pose covariance: variances (pxx, pyy,
// ptt) >= 0 and the matrix positive semi-definite (smallest eigenvalue >= -1e-9 x the largest
// variance).
void CheckPoseCovariance(const Mat3& p, const std::filesystem::path& path, std::size_t line) {
  const std::array<const char*, 3> names = {"pxx", "pyy", "ptt"};
  for (int i = 0; i < 3; ++i) {
    if (p(i, i) < 0.0) {
      Fail(path, line,
           std::string("column '") + names[static_cast<std::size_t>(i)] + "': the variance " +
               text::FormatDouble(p(i, i)) + " is negative");
    }
  }
  const Eigen::SelfAdjointEigenSolver<Mat3> eigen(p, Eigen::EigenvaluesOnly);
  if (eigen.eigenvalues().minCoeff() < -kDefinitenessTolerance * p.diagonal().maxCoeff()) {
    Fail(path, line,
         "columns 'pxy', 'pxt', 'pyt': the covariance is not positive semi-definite (smallest "
         "eigenvalue " +
             text::FormatDouble(eigen.eigenvalues().minCoeff()) + ")");
  }
}

void ReadPoseCovariances(const std::filesystem::path& path, RunRecord& record) {
  const std::size_t n = record.poses.size();
  const NumericRows rows = ReadNumericCsv(path, {"step", "pxx", "pxy", "pxt", "pyy", "pyt", "ptt"});
  record.pose_covs.assign(n, std::nullopt);
  for (std::size_t r = 0; r < rows.values.size(); ++r) {
    const std::vector<double>& v = rows.values[r];
    const std::size_t k = IndexValue(v[0], n, path, rows.lines[r], "step");
    if (record.pose_covs[k]) Fail(path, rows.lines[r], "step " + std::to_string(k) + " repeated");
    Mat3 p;
    p << v[1], v[2], v[3], v[2], v[4], v[5], v[3], v[5], v[6];
    CheckPoseCovariance(p, path, rows.lines[r]);
    record.pose_covs[k] = p;
  }
}

void ReadTiming(const std::filesystem::path& path, RunRecord& record) {
  const std::size_t n = record.poses.size();
  const NumericRows rows = ReadNumericCsv(path, {"step", "ms"});
  std::vector<double> ms(n, kNaN);
  for (std::size_t r = 0; r < rows.values.size(); ++r) {
    const std::size_t k = IndexValue(rows.values[r][0], n, path, rows.lines[r], "step");
    if (!std::isnan(ms[k])) Fail(path, rows.lines[r], "step " + std::to_string(k) + " repeated");
    if (rows.values[r][1] < 0.0) Fail(path, rows.lines[r], "ms is negative");
    ms[k] = rows.values[r][1];
  }
  for (std::size_t k = 0; k < n; ++k) {
    if (std::isnan(ms[k])) {
      throw std::runtime_error(path.string() + ": no row for step " + std::to_string(k) +
                               " (timing needs every step)");
    }
    record.total_ms += ms[k];
  }
  record.step_ms = std::move(ms);
}

void ReadStepMaps(const std::filesystem::path& path, RunRecord& record) {
  const NumericRows rows = ReadNumericCsv(path, {"step", "x", "y"});
  record.step_maps.assign(record.poses.size(), {});
  for (std::size_t r = 0; r < rows.values.size(); ++r) {
    const std::vector<double>& v = rows.values[r];
    const std::size_t k = IndexValue(v[0], record.poses.size(), path, rows.lines[r], "step");
    record.step_maps[k].push_back(Landmark(v[1], v[2]));
  }
}

void ReadAssociations(const std::filesystem::path& path, const datasets::Scenario& scenario,
                      RunRecord& record) {
  const NumericRows rows = ReadNumericCsv(path, {"step", "index", "x", "y"});
  record.associations.clear();
  for (const datasets::ScenarioStep& step : scenario.steps) {
    record.associations.emplace_back(step.data.measurements.size(), Landmark(kNaN, kNaN));
  }
  for (std::size_t r = 0; r < rows.values.size(); ++r) {
    const std::vector<double>& v = rows.values[r];
    const std::size_t k = IndexValue(v[0], record.poses.size(), path, rows.lines[r], "step");
    const std::size_t i =
        IndexValue(v[1], record.associations[k].size(), path, rows.lines[r], "index");
    if (!std::isnan(record.associations[k][i](0))) {
      Fail(path, rows.lines[r],
           "measurement " + std::to_string(i) + " of step " + std::to_string(k) + " repeated");
    }
    record.associations[k][i] = Landmark(v[2], v[3]);
  }
}

}  // namespace

RunRecord ReadExternalRun(const std::filesystem::path& folder, const datasets::Scenario& scenario,
                          const std::string& estimator, int particles) {
  RunRecord record;
  record.estimator = estimator;
  record.particles = particles;
  record.seed = scenario.seed;
  for (std::size_t k = 0; k < scenario.steps.size(); ++k) {
    record.step_times.push_back(scenario.StepTime(k));
  }
  for (const char* required : {kExternalTrajectoryFile, kExternalMapFile}) {
    if (!std::filesystem::exists(folder / required)) {
      throw std::runtime_error((folder / required).string() + ": missing");
    }
  }
  ReadTrajectory(folder / kExternalTrajectoryFile, record);
  ReadMap(folder / kExternalMapFile, record);
  const auto optional = [&](const char* name, auto read) {
    if (std::filesystem::exists(folder / name)) read(folder / name);
  };
  optional(kExternalPoseCovFile,
           [&](const std::filesystem::path& p) { ReadPoseCovariances(p, record); });
  optional(kExternalTimingFile, [&](const std::filesystem::path& p) { ReadTiming(p, record); });
  optional(kExternalMapsFile, [&](const std::filesystem::path& p) { ReadStepMaps(p, record); });
  optional(kExternalAssociationFile,
           [&](const std::filesystem::path& p) { ReadAssociations(p, scenario, record); });
  return record;
}

}  // namespace phdslam::validation
