// Trajectories in the TUM RGB-D format ("t x y z qx qy qz qw" per line), readable by evo and
// other trajectory tools. A planar pose (x, y, theta) is written with z = 0 and the rotation
// about the z axis by theta, q = (0, 0, sin(theta / 2), cos(theta / 2)).
#pragma once

#include <filesystem>
#include <vector>

#include "src/core/types.h"

namespace phdslam::datasets {

struct StampedPose {
  double t = 0.0;  ///< s
  Pose pose = Pose::Zero();
};

/// Writes the header comment "# t x y z qx qy qz qw" and one line per pose, each number in the
/// shortest text that reads back exactly. Throws std::invalid_argument naming the pose index when
/// a value is NaN/inf, std::runtime_error naming the file when it cannot be written.
void WriteTumTrajectory(const std::filesystem::path& path, const std::vector<StampedPose>& poses);

/// Reads a TUM trajectory. Blank lines and lines starting with '#' are skipped; z is ignored.
/// The yaw is taken from the (normalised) quaternion, atan2(2 (qw qz + qx qy),
/// 1 - 2 (qy^2 + qz^2)), and headings are unwrapped along the file (each yaw is chosen within pi
/// of the previous one; the first lies in [-pi, pi]), since phdslam never wraps headings.
/// Throws std::runtime_error naming the file and line for a wrong column count, a token that is
/// not a number, a NaN/inf value, a zero quaternion, a quaternion that is not a rotation about z
/// (tilted by more than 1e-3 rad) or a repeated time stamp, and naming the file when it cannot be
/// opened or holds no poses.
std::vector<StampedPose> ReadTumTrajectory(const std::filesystem::path& path);

}  // namespace phdslam::datasets
