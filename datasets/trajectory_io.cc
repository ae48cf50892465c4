#include "datasets/trajectory_io.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <map>
#include <stdexcept>
#include <string>

#include "datasets/text_fields.h"
#include "src/core/angles.h"

namespace phdslam::datasets {
namespace {

constexpr std::array<const char*, 8> kColumns = {"t", "x", "y", "z", "qx", "qy", "qz", "qw"};

/// Largest tilt (rad) of a pose's rotation away from a rotation about z that still counts as
/// planar: 2 asin(sqrt(qx^2 + qy^2) / |q|).
constexpr double kMaxTiltRad = 1e-3;

}  // namespace

void WriteTumTrajectory(const std::filesystem::path& path, const std::vector<StampedPose>& poses) {
  for (std::size_t i = 0; i < poses.size(); ++i) {
    if (!std::isfinite(poses[i].t) || !poses[i].pose.allFinite()) {
      throw std::invalid_argument("WriteTumTrajectory('" + path.string() + "'): pose " +
                                  std::to_string(i) + " has a NaN/inf time or value");
    }
  }
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot open '" + path.string() + "' for writing");
  out << "# t x y z qx qy qz qw\n";
  for (const StampedPose& p : poses) {
    const double half = 0.5 * p.pose(2);
    out << text::FormatDouble(p.t) << ' ' << text::FormatDouble(p.pose(0)) << ' '
        << text::FormatDouble(p.pose(1)) << " 0 0 0 " << text::FormatDouble(std::sin(half)) << ' '
        << text::FormatDouble(std::cos(half)) << '\n';
  }
  out.flush();
  if (!out) throw std::runtime_error("error while writing '" + path.string() + "'");
}

std::vector<StampedPose> ReadTumTrajectory(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open TUM trajectory '" + path.string() + "'");
  std::vector<StampedPose> poses;
  std::map<double, std::size_t> first_line_of_time;
  std::string line;
  std::size_t line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    const std::string_view content = text::Trim(line);
    if (content.empty() || content.front() == '#') continue;
    const auto fail = [&](const std::string& what) {
      throw std::runtime_error(text::Where(path, line_number) + ": " + what);
    };
    const auto tokens = text::SplitWhitespace(content);
    if (tokens.size() != kColumns.size()) {
      fail("expected 8 values (t x y z qx qy qz qw), found " + std::to_string(tokens.size()));
    }
    std::array<double, 8> v{};
    for (std::size_t c = 0; c < tokens.size(); ++c) {
      const auto value = text::ParseDouble(tokens[c]);
      const std::string column = "column " + std::to_string(c + 1) + " (" + kColumns[c] + ")";
      if (!value) fail(column + ": '" + text::Printable(tokens[c]) + "' is not a number");
      if (!std::isfinite(*value)) fail(column + " is not finite");
      v[c] = *value;
    }
    const double qx = v[4];
    const double qy = v[5];
    const double qz = v[6];
    const double qw = v[7];
    const double norm2 = qx * qx + qy * qy + qz * qz + qw * qw;
    if (!(norm2 > 1e-18)) fail("the quaternion (qx qy qz qw) is zero");
    const double tilt = 2.0 * std::asin(std::min(1.0, std::sqrt((qx * qx + qy * qy) / norm2)));
    if (tilt > kMaxTiltRad) {
      fail("the quaternion is not a rotation about z (tilted by " + std::to_string(tilt) +
           " rad; a planar pose has qx = qy = 0)");
    }
    if (const auto [it, added] = first_line_of_time.emplace(v[0], line_number); !added) {
      fail("time stamp " + text::FormatDouble(v[0]) + " repeats that of line " +
           std::to_string(it->second) + " (time stamps must be unique)");
    }
    double yaw = std::atan2(2.0 * (qw * qz + qx * qy), norm2 - 2.0 * (qy * qy + qz * qz));
    if (!poses.empty()) {
      const double previous = poses.back().pose(2);
      yaw = previous + WrapAngle(yaw - previous);
    }
    poses.push_back({v[0], Pose(v[1], v[2], yaw)});
  }
  if (in.bad()) throw std::runtime_error("error while reading '" + path.string() + "'");
  if (poses.empty())
    throw std::runtime_error("TUM trajectory '" + path.string() + "' holds no poses");
  return poses;
}

}  // namespace phdslam::datasets
