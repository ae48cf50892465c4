// The SLAM model linearised at the true trajectory and map: what the posterior Cramer-Rao bounds
// (docs/algorithms/pcrb.md) are computed from. Every matrix is a Jacobian evaluated at the truth,
// so the bounds depend on the truth, the noise and which detections carry information, never on
// an estimate.
#pragma once

#include <vector>

#include "src/core/types.h"

namespace phdslam::reference::pcrb {

/// One sub-interval of a step's motion: x' = f(x, u + w), linearised as dx' = F dx + G w with
/// the control noise w ~ N(0, Q_u) of rank 2 in the pose space.
struct MotionBlock {
  Mat3 fx = Mat3::Identity();
  Mat32 fu = Mat32::Zero();
};

/// One detection that carries information: the landmark index, the Jacobians of h at the truth
/// and the covariance whose inverse is its information, R / s for the information scale s
/// (1 for a known detection without clutter, pD q for the information-reduction factor).
struct Detection {
  int landmark = 0;
  Mat23 hx = Mat23::Zero();
  Mat2 hm = Mat2::Identity();
  Mat2 cov = Mat2::Identity();
};

/// Step k: the motion from the pose of step k - 1 (the initial pose for k = 0) to that of step
/// k, then the detections at the pose of step k.
struct LinearStep {
  std::vector<MotionBlock> motion;
  std::vector<Detection> detections;
};

struct LinearisedSlam {
  Mat2 control_noise_cov = Mat2::Identity();  ///< Q_u, positive definite
  Mat3 initial_pose_cov = Mat3::Zero();       ///< the estimators know the initial pose: zero
  int landmarks = 0;                          ///< detections index 0 .. landmarks - 1
  std::vector<LinearStep> steps;
};

}  // namespace phdslam::reference::pcrb
