#include "reference/pcrb/filtering_bound.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <stdexcept>
#include <string>

namespace phdslam::reference::pcrb {
namespace {

Eigen::Index Slot(int landmark) { return 3 + 2 * static_cast<Eigen::Index>(landmark); }

// P <- A P A^T + blkdiag(G Q G^T, 0), A = blkdiag(F, I): only the pose rows and columns change.
void Predict(const MotionBlock& block, const Mat2& q, Eigen::MatrixXd& p) {
  p.topRows<3>() = (block.fx * p.topRows<3>()).eval();
  p.leftCols<3>() = (p.leftCols<3>() * block.fx.transpose()).eval();
  p.topLeftCorner<3, 3>() += block.fu * q * block.fu.transpose();
}

// The exact posterior of a landmark with zero prior information after one detection: given the
// pose, m = Hm^-1 (z - h0 - Hx x - v), so its rows are -Hm^-1 Hx times the pose rows and its own
// block adds Hm^-1 R Hm^-T (Hm is invertible: det Hm = 1 / range).
void Initialise(const Detection& d, Eigen::MatrixXd& p) {
  const Mat2 hm_inv = d.hm.inverse();
  const Mat23 a = -hm_inv * d.hx;
  const Eigen::Index s = Slot(d.landmark);
  const Eigen::MatrixXd rows = a * p.topRows<3>();
  p.middleRows(s, 2) = rows;
  p.middleCols(s, 2) = rows.transpose();
  p.block<2, 2>(s, s) =
      a * p.topLeftCorner<3, 3>() * a.transpose() + hm_inv * d.cov * hm_inv.transpose();
}

// One Kalman update with the stacked detections: P <- P - (HP)^T S^-1 (HP), S = H P H^T + R.
void Update(const std::vector<const Detection*>& ds, std::size_t step, Eigen::MatrixXd& p) {
  const auto m = static_cast<Eigen::Index>(ds.size());
  if (m == 0) return;
  Eigen::MatrixXd hp(2 * m, p.cols());
  for (Eigen::Index i = 0; i < m; ++i) {
    const Detection& d = *ds[static_cast<std::size_t>(i)];
    hp.middleRows(2 * i, 2) = d.hx * p.topRows<3>() + d.hm * p.middleRows(Slot(d.landmark), 2);
  }
  Eigen::MatrixXd s(2 * m, 2 * m);
  for (Eigen::Index j = 0; j < m; ++j) {
    const Detection& d = *ds[static_cast<std::size_t>(j)];
    s.middleCols(2 * j, 2) =
        hp.leftCols<3>() * d.hx.transpose() + hp.middleCols(Slot(d.landmark), 2) * d.hm.transpose();
    s.block<2, 2>(2 * j, 2 * j) += d.cov;
  }
  s = 0.5 * (s + s.transpose()).eval();
  const Eigen::LLT<Eigen::MatrixXd> llt(s);
  if (llt.info() != Eigen::Success) {
    throw std::invalid_argument("pcrb: innovation covariance of step " + std::to_string(step) +
                                " is not positive definite");
  }
  p.noalias() -= hp.transpose() * llt.solve(hp);
  p = 0.5 * (p + p.transpose()).eval();
}

void CheckDetection(const Detection& d, int landmarks, std::size_t step) {
  if (d.landmark < 0 || d.landmark >= landmarks) {
    throw std::invalid_argument("pcrb: step " + std::to_string(step) + " detects landmark " +
                                std::to_string(d.landmark) + " of " + std::to_string(landmarks));
  }
  if (!d.cov.allFinite() || Eigen::LLT<Mat2>(d.cov).info() != Eigen::Success) {
    throw std::invalid_argument("pcrb: a detection covariance of step " + std::to_string(step) +
                                " is not finite and positive definite");
  }
}

}  // namespace

FilteringBound ComputeFilteringBound(const LinearisedSlam& model) {
  const int l = model.landmarks;
  Eigen::MatrixXd p = Eigen::MatrixXd::Zero(3 + 2 * l, 3 + 2 * l);
  p.topLeftCorner<3, 3>() = model.initial_pose_cov;
  FilteringBound out;
  out.landmark_seen.assign(static_cast<std::size_t>(l), false);
  out.pose_covs.reserve(model.steps.size());
  for (std::size_t k = 0; k < model.steps.size(); ++k) {
    const LinearStep& step = model.steps[k];
    for (const MotionBlock& b : step.motion) Predict(b, model.control_noise_cov, p);
    std::vector<const Detection*> updates;
    for (const Detection& d : step.detections) {
      CheckDetection(d, l, k);
      const auto i = static_cast<std::size_t>(d.landmark);
      if (out.landmark_seen[i]) {
        updates.push_back(&d);
        continue;
      }
      Initialise(d, p);
      out.landmark_seen[i] = true;
    }
    Update(updates, k, p);
    out.pose_covs.emplace_back(p.topLeftCorner<3, 3>());
  }
  out.landmark_covs.reserve(static_cast<std::size_t>(l));
  for (int i = 0; i < l; ++i) out.landmark_covs.emplace_back(p.block<2, 2>(Slot(i), Slot(i)));
  out.map_cov = p.bottomRightCorner(2 * l, 2 * l);
  return out;
}

}  // namespace phdslam::reference::pcrb
