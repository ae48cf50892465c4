// Fixed-size Eigen types shared by every part of phdslam.
#pragma once

#include <Eigen/Core>

namespace phdslam {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Mat2 = Eigen::Matrix2d;
using Mat3 = Eigen::Matrix3d;
using Mat23 = Eigen::Matrix<double, 2, 3>;
using Mat32 = Eigen::Matrix<double, 3, 2>;

/// Vehicle pose [x, y, theta] (m, m, rad). The heading is never wrapped.
using Pose = Vec3;
/// Point landmark [x, y] (m).
using Landmark = Vec2;
/// Range-bearing measurement [r, phi] (m, rad); the bearing is wrapped to [-pi, pi].
using Measurement = Vec2;
/// Control input: [v, omega] (synthetic) or [v_e, alpha] (Victoria Park).
using Control = Vec2;

}  // namespace phdslam
