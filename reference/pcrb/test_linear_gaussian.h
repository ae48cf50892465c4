// Test-only: a linear-Gaussian SLAM problem (a holonomic robot with position controls and a
// linear relative-position sensor, z = m - p + v) and an information filter for it written
// independently of the bound's covariance-form recursion: Tichavsky et al.'s information
// recursion with the prediction's Schur complement over the control noise.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/LU>
#include <vector>

#include "reference/pcrb/linearised_slam.h"
#include "src/core/random.h"

namespace phdslam::reference::pcrb::testing {

/// `steps` steps of dt = 1 s, `landmarks` landmarks; at step k landmark i is detected when
/// detected(k, i) (every step and landmark when `pd` is 1; else a Bernoulli(pd) draw of `rng`).
inline LinearisedSlam LinearGaussianModel(int steps, int landmarks, double pd, RandomStream& rng) {
  LinearisedSlam m;
  m.control_noise_cov << 0.04, 0.01, 0.01, 0.09;
  m.initial_pose_cov = Vec3(0.01, 0.02, 0.03).asDiagonal();
  m.landmarks = landmarks;
  for (int k = 0; k < steps; ++k) {
    LinearStep step;
    if (k > 0) {
      MotionBlock b;
      b.fu << 1.0, 0.0, 0.0, 1.0, 0.0, 0.0;
      step.motion.push_back(b);
    }
    for (int i = 0; i < landmarks; ++i) {
      if (pd < 1.0 && !(rng.Uniform() < pd)) continue;
      Detection d;
      d.landmark = i;
      d.hx << -1.0, 0.0, 0.0, 0.0, -1.0, 0.0;
      d.hm = Mat2::Identity();
      d.cov << 0.25, 0.05, 0.05, 0.16;
      step.detections.push_back(d);
    }
    m.steps.push_back(step);
  }
  return m;
}

/// The information filter's pose covariance after every step: the information of [pose, map]
/// is propagated (x = F^-1 (x' - G w), then the Schur complement over w) and updated additively;
/// the pose block of its inverse over the landmarks detected so far is the covariance.
inline std::vector<Mat3> InformationFilterPoseCovs(const LinearisedSlam& m) {
  const int n = 3 + 2 * m.landmarks;
  Eigen::MatrixXd j = Eigen::MatrixXd::Zero(n, n);
  j.topLeftCorner<3, 3>() = m.initial_pose_cov.inverse();
  std::vector<bool> seen(static_cast<std::size_t>(m.landmarks), false);
  std::vector<Mat3> out;
  for (const LinearStep& step : m.steps) {
    for (const MotionBlock& b : step.motion) {
      // Over [x', w, map]: z = M y with x = F^-1 x' - F^-1 G w.
      Eigen::MatrixXd mm = Eigen::MatrixXd::Zero(n + 2, n + 2);
      const Mat3 f_inv = b.fx.inverse();
      mm.topLeftCorner<3, 3>() = f_inv;
      mm.block<3, 2>(0, 3) = -f_inv * b.fu;
      mm.block<2, 2>(3, 3) = Mat2::Identity();
      mm.bottomRightCorner(n - 3, n - 3).setIdentity();
      Eigen::MatrixXd jz = Eigen::MatrixXd::Zero(n + 2, n + 2);
      jz.topLeftCorner<3, 3>() = j.topLeftCorner<3, 3>();
      jz.block(0, 5, 3, n - 3) = j.topRightCorner(3, n - 3);
      jz.block(5, 0, n - 3, 3) = j.bottomLeftCorner(n - 3, 3);
      jz.bottomRightCorner(n - 3, n - 3) = j.bottomRightCorner(n - 3, n - 3);
      jz.block<2, 2>(3, 3) = m.control_noise_cov.inverse();
      // jz is ordered [x, w, map]; mm maps [x', w, map] to it.
      const Eigen::MatrixXd jy = mm.transpose() * jz * mm;
      std::vector<int> keep;
      for (int i = 0; i < n + 2; ++i) {
        if (i != 3 && i != 4) keep.push_back(i);
      }
      const Eigen::MatrixXd a = jy(keep, keep);
      const Eigen::MatrixXd c = jy(keep, std::vector<int>{3, 4});
      const Mat2 w = jy.block<2, 2>(3, 3);
      j = a - c * w.inverse() * c.transpose();
    }
    for (const Detection& d : step.detections) {
      Eigen::MatrixXd h = Eigen::MatrixXd::Zero(2, n);
      h.leftCols<3>() = d.hx;
      h.middleCols<2>(3 + 2 * d.landmark) = d.hm;
      j += h.transpose() * d.cov.inverse() * h;
      seen[static_cast<std::size_t>(d.landmark)] = true;
    }
    std::vector<int> idx = {0, 1, 2};
    for (int i = 0; i < m.landmarks; ++i) {
      if (seen[static_cast<std::size_t>(i)]) {
        idx.push_back(3 + 2 * i);
        idx.push_back(4 + 2 * i);
      }
    }
    const Eigen::MatrixXd js = j(idx, idx);
    out.emplace_back(js.inverse().topLeftCorner<3, 3>());
  }
  return out;
}

}  // namespace phdslam::reference::pcrb::testing
