#include "datasets/mrclam.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <numbers>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>

#include "datasets/covariance_option.h"
#include "datasets/text_fields.h"
#include "src/core/angles.h"

namespace phdslam::datasets {
namespace {

/// One parsed data line: its 1-based line number and its N values.
template <std::size_t N>
struct Row {
  std::size_t line = 0;
  std::array<double, N> values{};
};

std::string QuotedPath(const std::filesystem::path& path) { return "'" + path.string() + "'"; }

[[noreturn]] void FailAt(const std::filesystem::path& path, std::size_t line,
                         const std::string& what) {
  throw std::runtime_error(text::Where(path, line) + ": " + what);
}

std::string ReadWholeFile(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw std::runtime_error("MRCLAM file " + QuotedPath(path) + " is missing");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open " + QuotedPath(path) + " for reading");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

/// Parses one data line into N finite numbers, or fails naming the file and line.
template <std::size_t N>
Row<N> ParseLine(std::string_view line, std::size_t number, const std::filesystem::path& path,
                 std::string_view columns) {
  const std::vector<std::string_view> tokens = text::SplitWhitespace(line);
  const auto fail = [&](const std::string& what) {
    FailAt(path, number,
           what + " (expected " + std::to_string(N) + " numbers: " + std::string(columns) +
               "; line is '" + text::Printable(line) + "')");
  };
  if (tokens.size() != N) fail(std::to_string(tokens.size()) + " values");
  Row<N> row;
  row.line = number;
  for (std::size_t i = 0; i < N; ++i) {
    const std::optional<double> value = text::ParseDouble(tokens[i]);
    if (!value) fail("'" + text::Printable(tokens[i]) + "' is not a number");
    if (!std::isfinite(*value)) fail("value " + std::to_string(i + 1) + " is not finite");
    row.values[i] = *value;
  }
  return row;
}

/// Every data line of a whitespace-separated file with N numbers per line. Lines whose first
/// non-blank character is '#' (the four header lines) and blank lines are skipped.
template <std::size_t N>
std::vector<Row<N>> ReadRows(const std::filesystem::path& path, std::string_view columns) {
  const std::string content = ReadWholeFile(path);
  std::vector<Row<N>> rows;
  std::size_t number = 0;
  std::size_t pos = 0;
  while (pos < content.size()) {
    const std::size_t end = std::min(content.find('\n', pos), content.size());
    const std::string_view line(content.data() + pos, end - pos);
    pos = end + 1;
    ++number;
    const std::string_view trimmed = text::Trim(line);
    if (trimmed.empty() || trimmed.front() == '#') continue;
    rows.push_back(ParseLine<N>(line, number, path, columns));
  }
  if (rows.empty()) throw std::runtime_error(QuotedPath(path) + " holds no data lines");
  return rows;
}

/// A value that must be a positive integer (a subject or a barcode).
int PositiveInteger(double value, const std::filesystem::path& path, std::size_t line,
                    std::string_view what) {
  if (value != std::floor(value) || value < 1.0 || value > 1e6) {
    FailAt(path, line,
           std::string(what) + " " + text::FormatDouble(value) + " is not a positive integer");
  }
  return static_cast<int>(value);
}

/// A time stamp (s, Unix epoch) must lie in [0, kMrclamMaxTime]: later or negative stamps are
/// corrupt rows (the data sets were recorded in 2009).
constexpr double kMrclamMaxTime = 4e9;

void CheckTime(double t, const std::filesystem::path& path, std::size_t line) {
  if (!(t >= 0.0 && t <= kMrclamMaxTime)) {
    FailAt(path, line,
           "time stamp " + text::FormatDouble(t) + " s is out of range (expected 0 to " +
               text::FormatDouble(kMrclamMaxTime) + " s, Unix time)");
  }
}

/// The order that sorts `times` stably, and how many rows were out of order on the way.
std::vector<std::size_t> StableTimeOrder(const std::vector<double>& times,
                                         std::size_t& out_of_order) {
  std::vector<std::size_t> order(times.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  out_of_order = 0;
  for (std::size_t i = 1; i < times.size(); ++i) {
    if (times[i] < times[i - 1]) ++out_of_order;
  }
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return times[a] < times[b]; });
  return order;
}

void ReadBarcodes(const std::filesystem::path& path, MrclamRobotData& data) {
  std::map<int, std::size_t> subject_line;
  for (const Row<2>& row : ReadRows<2>(path, "subject, barcode")) {
    const int subject = PositiveInteger(row.values[0], path, row.line, "subject");
    const int barcode = PositiveInteger(row.values[1], path, row.line, "barcode");
    if (!subject_line.emplace(subject, row.line).second) {
      FailAt(path, row.line,
             "subject " + std::to_string(subject) + " already listed on line " +
                 std::to_string(subject_line[subject]));
    }
    if (!data.barcode_subject.emplace(barcode, subject).second) {
      FailAt(path, row.line,
             "barcode " + std::to_string(barcode) + " already given to subject " +
                 std::to_string(data.barcode_subject[barcode]));
    }
  }
}

void ReadLandmarks(const std::filesystem::path& path, MrclamRobotData& data) {
  for (const Row<5>& row : ReadRows<5>(path, "subject, x [m], y [m], x std [m], y std [m]")) {
    const int subject = PositiveInteger(row.values[0], path, row.line, "subject");
    if (subject <= kMrclamRobots) {
      FailAt(path, row.line,
             "subject " + std::to_string(subject) + " is a robot (subjects 1-5), not a landmark");
    }
    if (std::find(data.landmark_subjects.begin(), data.landmark_subjects.end(), subject) !=
        data.landmark_subjects.end()) {
      FailAt(path, row.line, "landmark subject " + std::to_string(subject) + " listed twice");
    }
    data.landmark_subjects.push_back(subject);
    data.landmarks.emplace_back(row.values[1], row.values[2]);
  }
}

void ReadOdometry(const std::filesystem::path& path, MrclamRobotData& data) {
  const auto rows = ReadRows<3>(path, "t [s], v [m/s], w [rad/s]");
  std::vector<double> times;
  times.reserve(rows.size());
  for (const auto& row : rows) {
    CheckTime(row.values[0], path, row.line);
    times.push_back(row.values[0]);
  }
  const std::vector<std::size_t> order = StableTimeOrder(times, data.odometry_out_of_order);
  for (std::size_t i : order) {
    const Control u(rows[i].values[1], rows[i].values[2]);
    if (!data.odometry_times.empty() && data.odometry_times.back() == times[i]) {
      data.odometry.back() = u;  // the last command logged at a time stamp is the one in force
      ++data.odometry_repeated_times;
      continue;
    }
    data.odometry_times.push_back(times[i]);
    data.odometry.push_back(u);
  }
}

void ReadTruth(const std::filesystem::path& path, MrclamRobotData& data) {
  const auto rows = ReadRows<4>(path, "t [s], x [m], y [m], heading [rad]");
  std::vector<double> times;
  times.reserve(rows.size());
  for (const auto& row : rows) {
    CheckTime(row.values[0], path, row.line);
    times.push_back(row.values[0]);
  }
  const std::vector<std::size_t> order = StableTimeOrder(times, data.truth_out_of_order);
  for (std::size_t i : order) {
    if (!data.truth_times.empty() && data.truth_times.back() == times[i]) {
      ++data.truth_repeated_times;  // the first Vicon sample of a time stamp is kept
      continue;
    }
    Pose x(rows[i].values[1], rows[i].values[2], rows[i].values[3]);
    if (!data.truth_poses.empty()) {
      // Unwrap: the heading moves by the wrapped difference from the previous sample.
      const double previous = data.truth_poses.back()(2);
      x(2) = previous + WrapAngle(x(2) - previous);
    }
    data.truth_times.push_back(times[i]);
    data.truth_poses.push_back(x);
  }
}

void ReadDetections(const std::filesystem::path& path, MrclamRobotData& data) {
  const auto rows = ReadRows<4>(path, "t [s], barcode, range [m], bearing [rad]");
  std::vector<double> times;
  times.reserve(rows.size());
  for (const auto& row : rows) {
    CheckTime(row.values[0], path, row.line);
    times.push_back(row.values[0]);
  }
  const std::vector<std::size_t> order = StableTimeOrder(times, data.detections_out_of_order);
  for (std::size_t i : order) {
    const auto& [t, barcode, range, bearing] = rows[i].values;
    MrclamDetection d;
    d.t = t;
    d.barcode = PositiveInteger(barcode, path, rows[i].line, "barcode");
    if (const auto it = data.barcode_subject.find(d.barcode);
        it != data.barcode_subject.end() && it->second > kMrclamRobots &&
        std::find(data.landmark_subjects.begin(), data.landmark_subjects.end(), it->second) ==
            data.landmark_subjects.end()) {
      FailAt(path, rows[i].line,
             "barcode " + std::to_string(d.barcode) + " is that of landmark subject " +
                 std::to_string(it->second) +
                 " (Barcodes.dat), which Landmark_Groundtruth.dat does not list: the detection "
                 "has no true position");
    }
    if (!(range > 0.0)) {
      FailAt(path, rows[i].line, "range " + text::FormatDouble(range) + " m is not positive");
    }
    d.range = range;
    d.bearing = WrapAngle(bearing);
    data.detections.push_back(d);
  }
}

std::filesystem::path RobotFile(int robot, std::string_view kind) {
  return "Robot" + std::to_string(robot) + "_" + std::string(kind) + ".dat";
}

/// The index of the last command with time <= t, or -1 when every command comes after t.
std::ptrdiff_t CommandInForce(const std::vector<double>& times, double t) {
  const auto it = std::upper_bound(times.begin(), times.end(), t);
  return std::distance(times.begin(), it) - 1;
}

/// Where a detection comes from: a landmark index, kClutter (robot or unknown barcode).
struct OriginTable {
  std::map<int, int> barcode_origin;  ///< barcodes of landmarks -> index
  std::map<int, bool> barcode_is_robot;

  explicit OriginTable(const MrclamRobotData& data) {
    for (const auto& [barcode, subject] : data.barcode_subject) {
      const auto it =
          std::find(data.landmark_subjects.begin(), data.landmark_subjects.end(), subject);
      if (it != data.landmark_subjects.end()) {
        barcode_origin[barcode] = static_cast<int>(it - data.landmark_subjects.begin());
      } else if (subject <= kMrclamRobots) {
        barcode_is_robot[barcode] = true;
      }
    }
  }
};

/// Appends the detections [begin, end) (one image) to `step`, counting their kinds.
void AddDetections(const MrclamRobotData& data, const OriginTable& origins, std::size_t begin,
                   std::size_t end, bool drop_non_landmarks, ScenarioStep& step,
                   MrclamCounts& counts) {
  for (std::size_t i = begin; i < end; ++i) {
    const MrclamDetection& d = data.detections[i];
    int origin = kClutter;
    if (const auto it = origins.barcode_origin.find(d.barcode);
        it != origins.barcode_origin.end()) {
      origin = it->second;
      ++counts.landmark_detections;
    } else if (origins.barcode_is_robot.count(d.barcode) > 0) {
      ++counts.other_robot_detections;
    } else {
      ++counts.unknown_barcode_detections;
    }
    if (origin == kClutter && drop_non_landmarks) continue;
    step.data.measurements.emplace_back(d.range, d.bearing);
    step.origin.push_back(origin);
  }
}

/// The propagation of the step from image time t0 to image time t1: time stamps and controls.
void AddPropagation(const MrclamRobotData& data, double t0, double t1, StepData& d) {
  const std::ptrdiff_t held = CommandInForce(data.odometry_times, t0);
  d.times.push_back(t0);
  d.controls.push_back(held >= 0 ? data.odometry[static_cast<std::size_t>(held)] : Control::Zero());
  for (auto i = static_cast<std::size_t>(held + 1);
       i < data.odometry_times.size() && data.odometry_times[i] < t1; ++i) {
    d.times.push_back(data.odometry_times[i]);
    d.controls.push_back(data.odometry[i]);
  }
  d.times.push_back(t1);
}

}  // namespace

std::filesystem::path MrclamFolder(int dataset) {
  return std::filesystem::path("utias-mrclam") / ("MRCLAM_Dataset" + std::to_string(dataset));
}

std::vector<std::filesystem::path> MrclamDataFiles(int dataset, int robot) {
  const std::filesystem::path folder = MrclamFolder(dataset);
  return {folder / "Barcodes.dat", folder / "Landmark_Groundtruth.dat",
          folder / RobotFile(robot, "Groundtruth"), folder / RobotFile(robot, "Odometry"),
          folder / RobotFile(robot, "Measurement")};
}

MrclamRobotData LoadMrclamRobot(const std::filesystem::path& data_dir, int dataset, int robot) {
  if (dataset < 1) {
    throw std::invalid_argument("MRCLAM dataset " + std::to_string(dataset) + ": expected >= 1");
  }
  if (robot < 1 || robot > kMrclamRobots) {
    throw std::invalid_argument("MRCLAM robot " + std::to_string(robot) + ": expected 1-" +
                                std::to_string(kMrclamRobots));
  }
  const std::filesystem::path dir = data_dir / MrclamFolder(dataset);
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) {
    throw std::runtime_error("MRCLAM folder " + QuotedPath(dir) + " is missing");
  }
  MrclamRobotData data;
  data.dataset = dataset;
  data.robot = robot;
  ReadBarcodes(dir / "Barcodes.dat", data);
  ReadLandmarks(dir / "Landmark_Groundtruth.dat", data);
  ReadTruth(dir / RobotFile(robot, "Groundtruth"), data);
  ReadOdometry(dir / RobotFile(robot, "Odometry"), data);
  ReadDetections(dir / RobotFile(robot, "Measurement"), data);
  return data;
}

MrclamOptions::MrclamOptions() {
  measurement_noise_cov << 0.175 * 0.175, 0.0, 0.0, 0.0124 * 0.0124;
  control_noise_cov << 0.0547 * 0.0547, 0.0, 0.0, 0.315 * 0.315;
}

void MrclamOptions::Validate() const {
  const auto fail = [](const std::string& field, const std::string& expected, double value) {
    throw std::invalid_argument("MrclamOptions." + field + " = " + text::FormatDouble(value) +
                                ": expected " + expected);
  };
  if (dataset < 1) fail("dataset", ">= 1", dataset);
  if (robot < 1 || robot > kMrclamRobots) fail("robot", "in 1-5", robot);
  // (0, 1] as for every scenario (phdslam list, --pd).
  if (!(detection_probability > 0.0 && detection_probability <= 1.0)) {
    fail("detection_probability", "in (0, 1]", detection_probability);
  }
  if (!(clutter_rate >= 0.0 && std::isfinite(clutter_rate))) {
    fail("clutter_rate", "a finite value >= 0", clutter_rate);
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
  RequireCovarianceOption(measurement_noise_cov, "MrclamOptions.measurement_noise_cov");
  RequireCovarianceOption(control_noise_cov, "MrclamOptions.control_noise_cov");
  if (max_steps < 0) fail("max_steps", ">= 0 (0 = all steps)", max_steps);
}

MrclamTruthAt InterpolateMrclamTruth(const std::vector<double>& times,
                                     const std::vector<Pose>& poses, double t) {
  MrclamTruthAt out;
  if (times.empty()) return out;
  if (t <= times.front()) {
    out.pose = poses.front();
    out.scored = t == times.front();
    return out;
  }
  if (t >= times.back()) {
    out.pose = poses.back();
    out.scored = t == times.back();
    return out;
  }
  const auto hi = static_cast<std::size_t>(
      std::distance(times.begin(), std::upper_bound(times.begin(), times.end(), t)));
  const std::size_t lo = hi - 1;
  const double span = times[hi] - times[lo];
  const double a = (t - times[lo]) / span;
  out.pose = (1.0 - a) * poses[lo] + a * poses[hi];
  out.scored = t == times[lo] || span <= kMrclamMaxTruthGap;
  return out;
}

Scenario MakeMrclamScenario(const MrclamRobotData& data, std::uint64_t seed,
                            const MrclamOptions& options, MrclamCounts* counts_out) {
  options.Validate();
  if (data.robot != options.robot || data.dataset != options.dataset) {
    throw std::invalid_argument("MRCLAM data of dataset " + std::to_string(data.dataset) +
                                " robot " + std::to_string(data.robot) + " given for dataset " +
                                std::to_string(options.dataset) + " robot " +
                                std::to_string(options.robot));
  }
  Scenario scenario;
  scenario.name = "mrclam";
  scenario.seed = seed;
  scenario.motion = MotionKind::kVelocity;
  scenario.control_noise_cov = options.control_noise_cov;
  scenario.sensor.fov_range = options.fov_range;
  scenario.sensor.fov_half_angle = options.fov_half_angle;
  scenario.sensor.range_buffer = options.range_buffer;
  scenario.sensor.angle_buffer = options.angle_buffer;
  scenario.sensor.profile = models::DetectionProfile::kLinearRange;
  scenario.sensor.pd_max = options.detection_probability;
  scenario.sensor.pd_nominal = options.detection_probability;
  scenario.sensor.noise_cov = options.measurement_noise_cov;
  scenario.sensor.clutter_rate = options.clutter_rate;
  scenario.truth.landmarks = data.landmarks;

  MrclamCounts counts;
  counts.non_landmarks_dropped = options.drop_non_landmarks;
  const OriginTable origins(data);
  const double first_time = std::max(data.odometry_times.empty() ? 0.0 : data.odometry_times[0],
                                     data.truth_times.empty() ? 0.0 : data.truth_times[0]);
  const double last_command = data.odometry_times.empty() ? 0.0 : data.odometry_times.back();
  const auto max_steps = static_cast<std::size_t>(options.max_steps);
  std::optional<double> previous;
  std::size_t i = 0;
  while (i < data.detections.size()) {
    std::size_t end = i + 1;
    const double t = data.detections[i].t;
    while (end < data.detections.size() && data.detections[end].t == t) ++end;
    const MrclamTruthAt truth = InterpolateMrclamTruth(data.truth_times, data.truth_poses, t);
    const bool can_start = t >= first_time && truth.scored;
    if ((!previous && !can_start) || t > last_command ||
        (max_steps > 0 && scenario.steps.size() >= max_steps)) {
      ++counts.images_skipped;
      i = end;
      continue;
    }
    ScenarioStep step;
    if (previous) {
      AddPropagation(data, *previous, t, step.data);
    } else {
      step.data.times.push_back(t);
      scenario.initial_pose = truth.pose;
    }
    AddDetections(data, origins, i, end, options.drop_non_landmarks, step, counts);
    scenario.steps.push_back(std::move(step));
    scenario.truth.poses.push_back(truth.pose);
    scenario.truth.pose_scored.push_back(truth.scored);
    if (!truth.scored) ++counts.unscored_steps;
    previous = t;
    i = end;
  }
  if (scenario.steps.empty()) {
    throw std::runtime_error("MRCLAM dataset " + std::to_string(data.dataset) + " robot " +
                             std::to_string(data.robot) +
                             ": no image lies within the commands and the Vicon truth");
  }
  counts.steps = scenario.steps.size();
  counts.odometry_out_of_order = data.odometry_out_of_order;
  counts.odometry_repeated_times = data.odometry_repeated_times;
  counts.truth_out_of_order = data.truth_out_of_order;
  counts.truth_repeated_times = data.truth_repeated_times;
  counts.detections_out_of_order = data.detections_out_of_order;
  if (counts_out != nullptr) *counts_out = counts;
  return scenario;
}

}  // namespace phdslam::datasets
