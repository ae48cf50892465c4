// Test-only: the posterior Cramer-Rao bound of a linearised SLAM model computed the direct way,
// as the inverse of the dense Fisher information of the whole problem. The variables are the
// control noise of every motion block and the landmarks (the poses are linear functions of the
// noise), so the information blkdiag(Q^-1, ..., 0) + sum_detections A^T R^-1 A is positive
// definite without any regularisation once every included landmark has been detected.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <vector>

#include "reference/pcrb/linearised_slam.h"

namespace phdslam::reference::pcrb::testing {

struct BatchBound {
  std::vector<Mat3> pose_covs;       ///< steps 0 .. last, given the data of steps 0 .. last
  Eigen::MatrixXd covariance;        ///< over [noise, detected landmarks]
  std::vector<int> landmark_column;  ///< column of each landmark in `covariance`, -1 if unseen
};

/// The bound given the data of steps 0 .. last (inclusive), marginals at steps 0 .. last.
inline BatchBound DenseBatchBound(const LinearisedSlam& model, std::size_t last) {
  int blocks = 0;
  for (std::size_t k = 0; k <= last; ++k) blocks += static_cast<int>(model.steps[k].motion.size());
  BatchBound out;
  out.landmark_column.assign(static_cast<std::size_t>(model.landmarks), -1);
  int columns = 2 * blocks;
  for (std::size_t k = 0; k <= last; ++k) {
    for (const Detection& d : model.steps[k].detections) {
      int& c = out.landmark_column[static_cast<std::size_t>(d.landmark)];
      if (c < 0) {
        c = columns;
        columns += 2;
      }
    }
  }
  Eigen::MatrixXd info = Eigen::MatrixXd::Zero(columns, columns);
  const Mat2 q_inv = model.control_noise_cov.inverse();
  for (int b = 0; b < blocks; ++b) info.block<2, 2>(2 * b, 2 * b) = q_inv;
  // phi: d pose / d [noise, landmarks]; the initial pose's own uncertainty must be zero here.
  Eigen::MatrixXd phi = Eigen::MatrixXd::Zero(3, columns);
  std::vector<Eigen::MatrixXd> phis;
  int b = 0;
  for (std::size_t k = 0; k <= last; ++k) {
    for (const MotionBlock& m : model.steps[k].motion) {
      phi = (m.fx * phi).eval();
      phi.middleCols<2>(2 * b) += m.fu;
      ++b;
    }
    for (const Detection& d : model.steps[k].detections) {
      Eigen::MatrixXd a = d.hx * phi;
      a.middleCols<2>(out.landmark_column[static_cast<std::size_t>(d.landmark)]) += d.hm;
      info += a.transpose() * d.cov.inverse() * a;
    }
    phis.push_back(phi);
  }
  out.covariance = info.llt().solve(Eigen::MatrixXd::Identity(columns, columns));
  for (const Eigen::MatrixXd& p : phis)
    out.pose_covs.emplace_back(p * out.covariance * p.transpose());
  return out;
}

}  // namespace phdslam::reference::pcrb::testing
