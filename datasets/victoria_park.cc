#include "datasets/victoria_park.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <initializer_list>
#include <numbers>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>

#include "datasets/covariance_option.h"
#include "datasets/mat_file.h"
#include "datasets/range_bearing_simulator.h"
#include "datasets/simulation_limits.h"
#include "datasets/text_fields.h"
#include "src/core/random.h"

namespace phdslam::datasets {
namespace {

constexpr std::string_view kFolderName = "victoria-park";

/// One parsed line of a whitespace-separated numeric text file.
template <std::size_t N>
struct TextRow {
  std::size_t line = 0;  ///< 1-based line number in the file
  std::array<double, N> values{};
};

/// Concatenates message parts. (Building messages by appending also avoids a GCC 12 -Wrestrict
/// false positive on `"literal" + std::string(...)` at -O3.)
std::string Cat(std::initializer_list<std::string_view> parts) {
  std::string out;
  for (std::string_view part : parts) out += part;
  return out;
}

std::string Quote(const std::filesystem::path& path) { return Cat({"'", path.string(), "'"}); }

/// Reads a text file of N whitespace-separated finite numbers per line. Blank lines are skipped;
/// anything else that is not exactly N numbers is an error naming the file and the line.
template <std::size_t N>
std::vector<TextRow<N>> ReadNumberRows(const std::filesystem::path& path,
                                       std::string_view columns) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open " + Quote(path) + " for reading");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();

  std::vector<TextRow<N>> rows;
  std::size_t line_number = 0;
  std::size_t pos = 0;
  while (pos < text.size()) {
    const std::size_t end = std::min(text.find('\n', pos), text.size());
    std::string_view line(text.data() + pos, end - pos);
    pos = end + 1;
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);

    const auto is_space = [](char c) { return c == ' ' || c == '\t'; };
    const auto fail = [&](const std::string& what) {
      throw std::runtime_error(Cat({path.string(), ":", std::to_string(line_number), ": ", what,
                                    " (expected ", std::to_string(N), " numbers: ", columns,
                                    "; line is '", text::Printable(line), "')"}));
    };
    TextRow<N> row;
    row.line = line_number;
    std::size_t count = 0;
    const char* p = line.data();
    const char* const last = line.data() + line.size();
    while (true) {
      while (p != last && is_space(*p)) ++p;
      if (p == last) break;
      if (count == N) fail("too many values");
      double value = 0.0;
      const auto [next, ec] = std::from_chars(p, last, value);
      if (ec != std::errc() || (next != last && !is_space(*next))) {
        const char* token_end = p;
        while (token_end != last && !is_space(*token_end)) ++token_end;
        fail(
            Cat({"'", text::Printable(std::string_view(p, static_cast<std::size_t>(token_end - p))),
                 "' is not a number"}));
      }
      if (!std::isfinite(value)) fail("value " + std::to_string(count + 1) + " is not finite");
      row.values[count++] = value;
      p = next;
    }
    if (count == 0) continue;  // blank line
    if (count != N) fail("only " + std::to_string(count) + " values");
    rows.push_back(row);
  }
  if (rows.empty()) throw std::runtime_error(Quote(path) + " holds no data lines");
  return rows;
}

/// Groups measurements.dat rows by time into scans and applies the detector limits
/// (docs/algorithms/models.md section 6.2).
std::vector<VictoriaParkData::Scan> ReadScans(const std::filesystem::path& path) {
  const auto rows = ReadNumberRows<4>(path, "t [s], range [m], bearing [rad], diameter [m]");
  std::vector<VictoriaParkData::Scan> scans;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto& [t, range, raw_bearing, diameter] = rows[i].values;
    if (i > 0) {
      const double prev = rows[i - 1].values[0];
      if (t < prev) {
        throw std::runtime_error(path.string() + ":" + std::to_string(rows[i].line) + ": time " +
                                 std::to_string(t) + " is earlier than the previous line's " +
                                 std::to_string(prev) + " (rows must be in time order)");
      }
    }
    if (range < 0.0) {
      throw std::runtime_error(path.string() + ":" + std::to_string(rows[i].line) + ": range " +
                               std::to_string(range) + " m is negative (a range is >= 0)");
    }
    if (scans.empty() || t != scans.back().t) {
      scans.emplace_back();
      scans.back().t = t;
    }
    const double bearing = raw_bearing - std::numbers::pi / 2.0;
    if (range <= kVictoriaParkMaxRange && std::abs(bearing) <= kVictoriaParkMaxAbsBearing &&
        diameter >= 0.0) {
      scans.back().trees.emplace_back(range, bearing);
      scans.back().diameters.push_back(diameter);
    }
  }
  return scans;
}

/// Throws when times are not strictly increasing; `where(i)` names the i-th entry.
template <typename Where>
void CheckStrictlyIncreasing(const std::vector<double>& times, const Where& where) {
  for (std::size_t i = 1; i < times.size(); ++i) {
    if (!(times[i] > times[i - 1])) {
      throw std::runtime_error(
          where(i) + ": time " + std::to_string(times[i]) + " s does not come after the previous " +
          std::to_string(times[i - 1]) + " s (times must be strictly increasing)");
    }
  }
}

double MsToSeconds(double ms) { return (ms - kVictoriaParkClockOriginMs) / 1000.0; }

/// Reads the named variables of a MAT-file as equally long finite vectors.
std::vector<Eigen::VectorXd> ReadMatVectors(const std::filesystem::path& path,
                                            const std::vector<std::string>& names) {
  const MatFile file(path);
  std::vector<Eigen::VectorXd> out;
  for (const std::string& name : names) {
    const std::string where = path.string() + ", variable '" + name + "'";
    if (!file.Has(name)) throw std::runtime_error(where + ": missing");
    const Eigen::MatrixXd m = file.ReadMatrix(name);
    if (m.rows() != 1 && m.cols() != 1) {
      throw std::runtime_error(where + ": expected a vector, found a " + std::to_string(m.rows()) +
                               " x " + std::to_string(m.cols()) + " matrix");
    }
    const Eigen::VectorXd v = m.reshaped();
    if (!out.empty() && v.size() != out.front().size()) {
      throw std::runtime_error(where + ": has " + std::to_string(v.size()) + " elements but '" +
                               names.front() + "' has " + std::to_string(out.front().size()));
    }
    for (Eigen::Index i = 0; i < v.size(); ++i) {
      if (!std::isfinite(v(i))) {
        throw std::runtime_error(where + ": element " + std::to_string(i + 1) + " is not finite");
      }
    }
    out.push_back(v);
  }
  if (out.front().size() == 0) throw std::runtime_error(Quote(path) + ": the vectors are empty");
  return out;
}

void ReadControlsFromMat(const std::filesystem::path& path, VictoriaParkData& data) {
  const auto v = ReadMatVectors(path, {"time", "speed", "steering"});
  for (Eigen::Index i = 0; i < v[0].size(); ++i) {
    data.control_times.push_back(MsToSeconds(v[0](i)));
    data.controls.emplace_back(v[1](i), v[2](i));
  }
  CheckStrictlyIncreasing(data.control_times, [&](std::size_t i) {
    return path.string() + ", variable 'time', element " + std::to_string(i + 1);
  });
}

void ReadControlsFromText(const std::filesystem::path& path, VictoriaParkData& data) {
  const auto rows = ReadNumberRows<3>(path, "t [s], speed [m/s], steering [rad]");
  for (const auto& row : rows) {
    data.control_times.push_back(row.values[0]);
    data.controls.emplace_back(row.values[1], row.values[2]);
  }
  CheckStrictlyIncreasing(data.control_times, [&](std::size_t i) {
    return path.string() + ":" + std::to_string(rows[i].line);
  });
}

std::vector<GpsFix> ReadGps(const std::filesystem::path& path) {
  const auto v = ReadMatVectors(path, {"timeGps", "Lo_m", "La_m"});
  std::vector<GpsFix> gps;
  std::vector<double> times;
  for (Eigen::Index i = 0; i < v[0].size(); ++i) {
    GpsFix fix;
    fix.t = MsToSeconds(v[0](i));
    fix.position = Vec2(v[1](i), v[2](i));
    gps.push_back(fix);
    times.push_back(fix.t);
  }
  CheckStrictlyIncreasing(times, [&](std::size_t i) {
    return path.string() + ", variable 'timeGps', element " + std::to_string(i + 1);
  });
  return gps;
}

void RequireFile(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw std::runtime_error("Victoria Park file " + Quote(path) + " is missing");
  }
}

}  // namespace

VictoriaParkData LoadVictoriaParkData(const std::filesystem::path& data_dir) {
  const std::filesystem::path dir = data_dir / kFolderName;
  const std::filesystem::path measurements = dir / "measurements.dat";
  const std::filesystem::path dr_mat = dir / "aa3_dr.mat";
  const std::filesystem::path inputs = dir / "inputs.dat";
  const std::filesystem::path gps = dir / "aa3_gpsx.mat";

  VictoriaParkData data;
  RequireFile(measurements);
  data.scans = ReadScans(measurements);

  // aa3_dr.mat holds the odometry at full precision; inputs.dat (the same samples with speed
  // rounded to 3 decimals and steering to 4, already on the common clock) is the fallback when the
  // MAT-file is absent.
  std::error_code ec;
  if (std::filesystem::is_regular_file(dr_mat, ec)) {
    ReadControlsFromMat(dr_mat, data);
  } else if (std::filesystem::is_regular_file(inputs, ec)) {
    ReadControlsFromText(inputs, data);
  } else {
    throw std::runtime_error("Victoria Park controls missing: neither " + Quote(dr_mat) + " nor " +
                             Quote(inputs) + " exists");
  }

  RequireFile(gps);
  data.gps = ReadGps(gps);
  return data;
}

std::vector<std::filesystem::path> VictoriaParkDataFiles(const std::filesystem::path& data_dir) {
  const std::filesystem::path folder(kFolderName);
  std::vector<std::filesystem::path> files;
  std::error_code ec;
  const auto add_if_present = [&](const char* name) {
    if (std::filesystem::is_regular_file(data_dir / folder / name, ec)) {
      files.push_back(folder / name);
      return true;
    }
    return false;
  };
  add_if_present("measurements.dat");
  if (!add_if_present("aa3_dr.mat")) add_if_present("inputs.dat");
  add_if_present("aa3_gpsx.mat");
  return files;
}

VictoriaParkOptions::VictoriaParkOptions() {
  const double one_deg = DegToRad(1.0);
  const double four_deg = DegToRad(4.0);
  measurement_noise_cov << 1.0, 0.0, 0.0, one_deg * one_deg;
  control_noise_cov << 1.0, 0.0, 0.0, four_deg * four_deg;
}

void VictoriaParkOptions::Validate() const {
  const auto fail = [](const std::string& field, const std::string& expected, double value) {
    throw std::invalid_argument("VictoriaParkOptions." + field + " = " + CompactNumber(value) +
                                ": expected " + expected);
  };
  if (!(clutter_rate >= 0.0 && clutter_rate <= kMaxClutterRate)) {
    fail("clutter_rate", "in [0, " + CompactNumber(kMaxClutterRate) + "]", clutter_rate);
  }
  if (!std::isfinite(fov_range) || fov_range <= 0.0) fail("fov_range", "> 0", fov_range);
  if (!(fov_half_angle > 0.0 && fov_half_angle <= std::numbers::pi)) {
    fail("fov_half_angle", "in (0, pi]", fov_half_angle);
  }
  if (!std::isfinite(range_buffer) || range_buffer < 0.0) {
    fail("range_buffer", "a finite value >= 0", range_buffer);
  }
  if (!std::isfinite(angle_buffer) || angle_buffer < 0.0) {
    fail("angle_buffer", "a finite value >= 0", angle_buffer);
  }
  if (!(detection_probability_max > 0.0 && detection_probability_max <= 1.0)) {
    fail("detection_probability_max", "in (0, 1]", detection_probability_max);
  }
  if (!(detection_probability_nominal > 0.0 && detection_probability_nominal < 1.0)) {
    fail("detection_probability_nominal", "in (0, 1)", detection_probability_nominal);
  }
  RequireCovarianceOption(measurement_noise_cov, "VictoriaParkOptions.measurement_noise_cov");
  RequireCovarianceOption(control_noise_cov, "VictoriaParkOptions.control_noise_cov");
  if (max_steps < 0) fail("max_steps", ">= 0 (0 = all scans)", max_steps);
}

Scenario MakeVictoriaParkScenario(const VictoriaParkData& data, std::uint64_t seed,
                                  const VictoriaParkOptions& options) {
  options.Validate();
  if (data.control_times.size() != data.controls.size()) {
    throw std::invalid_argument("VictoriaParkData: " + std::to_string(data.control_times.size()) +
                                " control times but " + std::to_string(data.controls.size()) +
                                " controls");
  }
  for (const auto& scan : data.scans) {
    if (scan.trees.size() != scan.diameters.size()) {
      throw std::invalid_argument("VictoriaParkData: scan at t = " + std::to_string(scan.t) +
                                  " has " + std::to_string(scan.trees.size()) + " trees but " +
                                  std::to_string(scan.diameters.size()) + " diameters");
    }
  }

  Scenario scenario;
  scenario.name = std::string(kFolderName);
  scenario.seed = seed;
  // docs/algorithms/models.md section 6.5, P0 = 0:
  scenario.initial_pose = Pose(-67.6493, -41.7142, DegToRad(35.5));
  scenario.motion = MotionKind::kCar;
  scenario.car = models::CarGeometry{};
  scenario.control_noise_cov = options.control_noise_cov;
  scenario.sensor.fov_range = options.fov_range;
  scenario.sensor.fov_half_angle = options.fov_half_angle;
  scenario.sensor.range_buffer = options.range_buffer;
  scenario.sensor.angle_buffer = options.angle_buffer;
  scenario.sensor.profile = models::DetectionProfile::kLinearRange;
  scenario.sensor.pd_max = options.detection_probability_max;
  scenario.sensor.pd_nominal = options.detection_probability_nominal;
  scenario.sensor.noise_cov = options.measurement_noise_cov;
  scenario.sensor.clutter_rate = options.clutter_rate;
  scenario.truth.gps = data.gps;

  RandomStream rng(DeriveSeed(HashName(kFolderName), seed));
  const auto max_steps = static_cast<std::size_t>(options.max_steps);
  std::optional<double> previous_scan_time;  // set only once a step is taken at k > 0
  Control held_control = Control::Zero();
  std::size_t k_last = 0;
  std::size_t j = 0;
  const auto limit_reached = [&] { return max_steps > 0 && scenario.steps.size() >= max_steps; };
  for (std::size_t k = 0; k < data.control_times.size(); ++k) {
    if (j >= data.scans.size() || limit_reached()) break;
    // Normally at most one scan falls before t_k here (scans are ~0.2 s apart, controls 25 ms);
    // a second one is taken at the same k, so its only sub-interval runs from the previous scan
    // with the held control instead of going backwards in time.
    while (j < data.scans.size() && data.scans[j].t < data.control_times[k] && !limit_reached()) {
      const VictoriaParkData::Scan& scan = data.scans[j];
      ScenarioStep step;
      StepData& d = step.data;
      if (previous_scan_time.has_value()) {
        d.times.push_back(*previous_scan_time);
        d.controls.push_back(held_control);
      }
      for (std::size_t i = k_last; i < k; ++i) {
        d.times.push_back(data.control_times[i]);
        d.controls.push_back(data.controls[i]);
      }
      d.times.push_back(scan.t);
      if (k > 0) {
        previous_scan_time = scan.t;
        held_control = data.controls[k - 1];
      }
      k_last = k;
      ++j;

      d.measurements = scan.trees;
      step.origin.assign(scan.trees.size(), kUnknownOrigin);
      const int clutter_count = rng.Poisson(options.clutter_rate);
      for (int c = 0; c < clutter_count; ++c) {
        const double range = rng.Uniform(0.0, options.fov_range);
        const double bearing = rng.Uniform(-options.fov_half_angle, options.fov_half_angle);
        d.measurements.emplace_back(range, bearing);
        step.origin.push_back(kClutter);
      }
      scenario.steps.push_back(std::move(step));
    }
  }
  return scenario;
}

}  // namespace phdslam::datasets
