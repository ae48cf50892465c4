#include "reference/ceres/joint_compatibility.h"

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "src/core/angles.h"
#include "src/models/range_bearing_model.h"

namespace phdslam::reference {
namespace {

using Mat23 = Eigen::Matrix<double, 2, 3>;

// One candidate pair, linearised at the pose and the landmark's mean.
struct LinearPair {
  int measurement = 0;
  int landmark = 0;
  double d2 = 0.0;
  Vec2 nu = Vec2::Zero();
  Mat23 hx = Mat23::Zero();
  Mat2 own = Mat2::Zero();         ///< Hm Pm Hm^T + R
  Mat23 hm_cross = Mat23::Zero();  ///< Hm C: the landmark's correlation with the pose
};

LinearPair Linearise(const Pose& pose, const MapLandmark& m, const Measurement& z, const Mat2& r,
                     const GatedPair& g) {
  const models::PredictionWithJacobians p = models::PredictWithJacobians(pose, m.mean);
  LinearPair out;
  out.measurement = g.measurement;
  out.landmark = g.landmark;
  out.d2 = g.d2;
  out.nu = Vec2(z(0) - p.z_hat(0), WrapAngle(z(1) - p.z_hat(1)));
  out.hx = p.j.hx;
  out.own = p.j.hm * m.cov * p.j.hm.transpose() + r;
  out.hm_cross = p.j.hm * m.pose_cross;
  return out;
}

class JcbbSearch {
 public:
  JcbbSearch(std::vector<std::vector<LinearPair>> candidates, const Mat3& pose_cov,
             std::size_t landmarks, const JointCompatibilityOptions& options)
      : candidates_(std::move(candidates)),
        pose_cov_(pose_cov),
        used_(landmarks, false),
        max_nodes_(options.max_nodes),
        tail_(std::exp(-0.5 * options.gate_chi2)) {
    for (std::size_t j = candidates_.size(); j-- > 0;) {
      reachable_.insert(reachable_.begin(), (reachable_.empty() ? 0 : reachable_.front()) +
                                                (candidates_[j].empty() ? 0 : 1));
    }
    reachable_.push_back(0);
  }

  // The best assignment: per entry of `candidates`, the chosen pair's index or -1.
  std::vector<int> Run() {
    choice_.assign(candidates_.size(), -1);
    best_choice_ = choice_;
    Visit(0);
    return best_choice_;
  }

 private:
  void Visit(std::size_t j) {
    const int pairs = static_cast<int>(stack_.size());
    if (j == candidates_.size()) {
      if (pairs > best_pairs_ || (pairs == best_pairs_ && joint_d2_ < best_d2_)) {
        best_pairs_ = pairs;
        best_d2_ = joint_d2_;
        best_choice_ = choice_;
      }
      return;
    }
    if (pairs + reachable_[j] < best_pairs_) return;
    for (std::size_t c = 0; c < candidates_[j].size(); ++c) {
      const LinearPair& p = candidates_[j][c];
      if (used_[static_cast<std::size_t>(p.landmark)]) continue;
      const double before = joint_d2_;
      if (!TryPush(&p)) continue;
      used_[static_cast<std::size_t>(p.landmark)] = true;
      choice_[j] = static_cast<int>(c);
      Visit(j + 1);
      choice_[j] = -1;
      used_[static_cast<std::size_t>(p.landmark)] = false;
      stack_.pop_back();
      joint_d2_ = before;
    }
    if (pairs + reachable_[j + 1] >= best_pairs_) Visit(j + 1);  // clutter or a new landmark
  }

  // Adds `p` to the stack when the pairs stay jointly compatible.
  bool TryPush(const LinearPair* p) {
    if (nodes_ >= max_nodes_) return false;
    ++nodes_;
    stack_.push_back(p);
    const double d2 = JointD2();
    if (std::isfinite(d2) && d2 < Threshold(stack_.size())) {
      joint_d2_ = d2;
      return true;
    }
    stack_.pop_back();
    return false;
  }

  double JointD2() const {
    const auto n = static_cast<Eigen::Index>(2 * stack_.size());
    Eigen::MatrixXd s(n, n);
    Eigen::VectorXd nu(n);
    for (std::size_t a = 0; a < stack_.size(); ++a) {
      const LinearPair& pa = *stack_[a];
      const auto ia = static_cast<Eigen::Index>(2 * a);
      nu.segment<2>(ia) = pa.nu;
      for (std::size_t b = 0; b <= a; ++b) {
        const LinearPair& pb = *stack_[b];
        Mat2 block = pa.hx * pose_cov_ * pb.hx.transpose() + pa.hx * pb.hm_cross.transpose() +
                     pa.hm_cross * pb.hx.transpose();
        if (a == b) {
          block += pa.own;
          block = 0.5 * (block + block.transpose()).eval();
        }
        const auto ib = static_cast<Eigen::Index>(2 * b);
        s.block<2, 2>(ia, ib) = block;
        s.block<2, 2>(ib, ia) = block.transpose();
      }
    }
    const Eigen::LLT<Eigen::MatrixXd> llt(s);
    if (llt.info() != Eigen::Success) return std::numeric_limits<double>::infinity();
    return nu.dot(llt.solve(nu));
  }

  double Threshold(std::size_t pairs) {
    while (thresholds_.size() < pairs) {
      thresholds_.push_back(
          ChiSquareQuantileEvenDof(2 * static_cast<int>(thresholds_.size() + 1), tail_));
    }
    return thresholds_[pairs - 1];
  }

  std::vector<std::vector<LinearPair>> candidates_;
  Mat3 pose_cov_;
  std::vector<bool> used_;
  int max_nodes_;
  double tail_;
  std::vector<int> reachable_;  ///< measurements from j on that have a candidate
  std::vector<double> thresholds_;
  std::vector<const LinearPair*> stack_;
  std::vector<int> choice_;
  std::vector<int> best_choice_;
  double joint_d2_ = 0.0;
  int best_pairs_ = 0;
  double best_d2_ = std::numeric_limits<double>::infinity();
  int nodes_ = 0;
};

// Upper tail of the chi-square distribution with 2k degrees of freedom:
// exp(-x/2) sum_{i<k} (x/2)^i / i!.
double ChiSquareTailEvenDof(int k, double x) {
  const double h = 0.5 * x;
  double term = 1.0;
  double sum = 1.0;
  for (int i = 1; i < k; ++i) {
    term *= h / i;
    sum += term;
  }
  return std::exp(-h) * sum;
}

}  // namespace

double ChiSquareQuantileEvenDof(int dof, double tail) {
  if (dof < 2 || dof % 2 != 0) {
    throw std::invalid_argument("ChiSquareQuantileEvenDof: dof must be even and >= 2, got " +
                                std::to_string(dof));
  }
  if (!(tail > 0.0 && tail < 1.0)) {
    throw std::invalid_argument("ChiSquareQuantileEvenDof: tail must be in (0, 1)");
  }
  const int k = dof / 2;
  double lo = 0.0;
  double hi = 2.0 * dof + 10.0;
  while (ChiSquareTailEvenDof(k, hi) > tail) hi *= 2.0;
  for (int i = 0; i < 200 && hi - lo > 1e-12 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (ChiSquareTailEvenDof(k, mid) > tail ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

ScanAssociation JointCompatibleAssociation(const Pose& pose, const Mat3& pose_cov,
                                           const std::vector<MapLandmark>& map,
                                           const std::vector<Measurement>& scan, const Mat2& r,
                                           const std::vector<GatedPair>& pairs,
                                           const JointCompatibilityOptions& options) {
  if (!(options.gate_chi2 > 0.0)) {
    throw std::invalid_argument("JointCompatibilityOptions.gate_chi2: expected > 0");
  }
  if (options.max_nodes < 1) {
    throw std::invalid_argument("JointCompatibilityOptions.max_nodes: expected >= 1");
  }
  std::vector<std::vector<LinearPair>> candidates(scan.size());
  for (const GatedPair& g : pairs) {
    const auto j = static_cast<std::size_t>(g.measurement);
    candidates[j].push_back(
        Linearise(pose, map[static_cast<std::size_t>(g.landmark)], scan[j], r, g));
  }
  for (auto& c : candidates) {
    std::sort(c.begin(), c.end(), [](const LinearPair& a, const LinearPair& b) {
      return a.d2 != b.d2 ? a.d2 < b.d2 : a.landmark < b.landmark;
    });
  }
  ScanAssociation out;
  out.landmark.assign(scan.size(), kUnassociated);
  out.mahalanobis2.assign(scan.size(), 0.0);
  out.gated.assign(scan.size(), 0);
  for (std::size_t j = 0; j < scan.size(); ++j)
    out.gated[j] = static_cast<int>(candidates[j].size());
  const std::vector<int> choice = JcbbSearch(candidates, pose_cov, map.size(), options).Run();
  for (std::size_t j = 0; j < scan.size(); ++j) {
    if (choice[j] < 0) continue;
    const LinearPair& p = candidates[j][static_cast<std::size_t>(choice[j])];
    out.landmark[j] = p.landmark;
    out.mahalanobis2[j] = p.d2;
  }
  return out;
}

}  // namespace phdslam::reference
