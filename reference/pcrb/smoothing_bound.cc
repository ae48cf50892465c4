#include "reference/pcrb/smoothing_bound.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <stdexcept>

namespace phdslam::reference::pcrb {
namespace {

using RowBlock = Eigen::Matrix<double, 3, Eigen::Dynamic>;

// The forward filter of the pose given the map: covariance P and the map coefficient Gamma of the
// mean (E[x_k | m, Z_1:k] = a_k + Gamma_k m).
struct ForwardPose {
  Mat3 p;
  RowBlock gamma;
};

Eigen::Index Col(int landmark) { return 2 * static_cast<Eigen::Index>(landmark); }

std::vector<ForwardPose> ForwardPass(const LinearisedSlam& model) {
  std::vector<ForwardPose> out;
  out.reserve(model.steps.size());
  Mat3 p = model.initial_pose_cov;
  RowBlock gamma = RowBlock::Zero(3, 2 * static_cast<Eigen::Index>(model.landmarks));
  for (const LinearStep& step : model.steps) {
    for (const MotionBlock& b : step.motion) {
      p = b.fx * p * b.fx.transpose() + b.fu * model.control_noise_cov * b.fu.transpose();
      gamma = (b.fx * gamma).eval();
    }
    for (const Detection& d : step.detections) {
      const Mat2 s = d.hx * p * d.hx.transpose() + d.cov;
      const Eigen::Matrix<double, 3, 2> k = Eigen::LLT<Mat2>(s).solve(d.hx * p).transpose();
      p -= k * s * k.transpose();
      p = 0.5 * (p + p.transpose()).eval();
      const Eigen::Matrix<double, 2, Eigen::Dynamic> hgamma = d.hx * gamma;
      gamma -= k * hgamma;
      gamma.middleCols<2>(Col(d.landmark)) -= k * d.hm;
    }
    out.push_back({p, gamma});
  }
  return out;
}

// The backward information filter of the pose given the map: information Lambda and the map
// coefficient Psi of the information vector, from the detections after the current step.
struct BackwardPose {
  Mat3 lambda = Mat3::Zero();
  RowBlock psi;
};

void AddDetections(const LinearStep& step, BackwardPose& b) {
  for (const Detection& d : step.detections) {
    const Eigen::LLT<Mat2> r(d.cov);
    b.lambda += d.hx.transpose() * r.solve(d.hx);
    b.psi.middleCols<2>(Col(d.landmark)) -= d.hx.transpose() * r.solve(d.hm);
  }
  b.lambda = 0.5 * (b.lambda + b.lambda.transpose()).eval();
}

// Through x' = F x + G w backwards: the Schur complement over w, whose block
// W = G^T Lambda G + Q^-1 is positive definite because Q is.
void PredictBack(const MotionBlock& m, const Mat2& q_inv, BackwardPose& b) {
  const Mat2 w = m.fu.transpose() * b.lambda * m.fu + q_inv;
  const Mat3 t = Mat3::Identity() - b.lambda * m.fu * Eigen::LLT<Mat2>(w).solve(m.fu.transpose());
  b.lambda = m.fx.transpose() * t * b.lambda * m.fx;
  b.lambda = 0.5 * (b.lambda + b.lambda.transpose()).eval();
  b.psi = (m.fx.transpose() * t * b.psi).eval();
}

Mat3 Combine(const ForwardPose& f, const BackwardPose& b, const Eigen::MatrixXd& map_cov) {
  // (P^-1 + Lambda)^-1 = P (I + Lambda P)^-1, valid for a singular P; the mean's map
  // coefficient is (I + P Lambda)^-1 Gamma + C Psi.
  const Mat3 c_raw = f.p * (Mat3::Identity() + b.lambda * f.p).inverse();
  const Mat3 c = 0.5 * (c_raw + c_raw.transpose());
  const RowBlock bk = (Mat3::Identity() + f.p * b.lambda).inverse() * f.gamma + c * b.psi;
  const Mat3 total = c + bk * map_cov * bk.transpose();
  return 0.5 * (total + total.transpose());
}

}  // namespace

std::vector<Mat3> ComputeSmoothingBound(const LinearisedSlam& model,
                                        const FilteringBound& filtering) {
  const Eigen::LLT<Mat2> q(model.control_noise_cov);
  if (!model.control_noise_cov.allFinite() || q.info() != Eigen::Success) {
    throw std::invalid_argument(
        "pcrb-smoother: the control noise covariance is not positive "
        "definite");
  }
  const Mat2 q_inv = q.solve(Mat2::Identity());
  const std::vector<ForwardPose> forward = ForwardPass(model);
  std::vector<Mat3> out(model.steps.size());
  BackwardPose back;
  back.psi = RowBlock::Zero(3, 2 * static_cast<Eigen::Index>(model.landmarks));
  for (std::size_t k = model.steps.size(); k-- > 0;) {
    out[k] = Combine(forward[k], back, filtering.map_cov);
    const LinearStep& step = model.steps[k];
    AddDetections(step, back);
    for (auto it = step.motion.rbegin(); it != step.motion.rend(); ++it) {
      PredictBack(*it, q_inv, back);
    }
  }
  return out;
}

}  // namespace phdslam::reference::pcrb
