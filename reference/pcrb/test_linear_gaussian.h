// Test-only: a linear-Gaussian SLAM problem (a holonomic robot with position controls and a
// linear relative-position sensor, z = m - p + v) and an information filter for it written
// independently of the bound's covariance-form recursion: Tichavsky et al.'s information
// recursion with the prediction's Schur complement over the control noise.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/LU>
#include <type_traits>
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

/// The position error |p_hat - p|^2 at the last step of one simulated run of the model: the true
/// initial pose drawn from N(0, P0), the landmarks at `landmarks_at`, the control noise and the
/// measurement noise drawn from `rng`; the estimate is the Kalman filter of the model (flat map
/// prior: a landmark's mean and covariance from its first detection), the estimator the bound
/// says is efficient.
inline double KalmanSquaredPositionError(const LinearisedSlam& m,
                                         const std::vector<Landmark>& landmarks_at,
                                         RandomStream& rng) {
  const int n = 3 + 2 * m.landmarks;
  auto draw = [&rng](const auto& cov) {
    using V = Eigen::Matrix<double, std::decay_t<decltype(cov)>::RowsAtCompileTime, 1>;
    V z;
    for (Eigen::Index i = 0; i < z.size(); ++i) z(i) = rng.Normal();
    const auto llt = cov.llt();
    return V(llt.matrixL() * z);
  };
  Vec3 x = Vec3::Zero();
  if (m.initial_pose_cov.trace() > 0.0) x = draw(m.initial_pose_cov);
  Eigen::VectorXd mean = Eigen::VectorXd::Zero(n);
  Eigen::MatrixXd p = Eigen::MatrixXd::Zero(n, n);
  p.topLeftCorner<3, 3>() = m.initial_pose_cov;
  std::vector<bool> seen(static_cast<std::size_t>(m.landmarks), false);
  for (const LinearStep& step : m.steps) {
    for (const MotionBlock& b : step.motion) {
      x = b.fx * x + b.fu * draw(m.control_noise_cov);
      mean.head<3>() = b.fx * mean.head<3>();
      p.topRows<3>() = (b.fx * p.topRows<3>()).eval();
      p.leftCols<3>() = (p.leftCols<3>() * b.fx.transpose()).eval();
      p.topLeftCorner<3, 3>() += b.fu * m.control_noise_cov * b.fu.transpose();
    }
    for (const Detection& d : step.detections) {
      const Eigen::Index s = 3 + 2 * static_cast<Eigen::Index>(d.landmark);
      const Vec2 z =
          d.hx * x + d.hm * landmarks_at[static_cast<std::size_t>(d.landmark)] + draw(d.cov);
      Eigen::MatrixXd h = Eigen::MatrixXd::Zero(2, n);
      h.leftCols<3>() = d.hx;
      h.middleCols<2>(s) = d.hm;
      if (!seen[static_cast<std::size_t>(d.landmark)]) {
        const Mat2 hm_inv = d.hm.inverse();
        mean.segment<2>(s) = hm_inv * (z - d.hx * mean.head<3>());
        const Eigen::MatrixXd rows = -hm_inv * d.hx * p.topRows<3>();
        p.middleRows(s, 2) = rows;
        p.middleCols(s, 2) = rows.transpose();
        p.block<2, 2>(s, s) =
            hm_inv * d.hx * p.topLeftCorner<3, 3>() * d.hx.transpose() * hm_inv.transpose() +
            hm_inv * d.cov * hm_inv.transpose();
        seen[static_cast<std::size_t>(d.landmark)] = true;
        continue;
      }
      const Eigen::MatrixXd sm = h * p * h.transpose() + d.cov;
      const Eigen::MatrixXd k = p * h.transpose() * sm.inverse();
      mean += k * (z - h * mean);
      p -= k * sm * k.transpose();
      p = 0.5 * (p + p.transpose()).eval();
    }
  }
  return (mean.head<2>() - x.head<2>()).squaredNorm();
}

}  // namespace phdslam::reference::pcrb::testing
