#include "reference/ceres/joint_compatibility.h"

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "reference/ceres/landmark_association.h"
#include "src/core/angles.h"
#include "src/models/range_bearing_model.h"

namespace phdslam::reference {
namespace {

using Mat23 = Eigen::Matrix<double, 2, 3>;

// pD is held above this in the likelihood objective, so that a landmark estimated just outside
// the field of view stays a finite alternative.
constexpr double kMinDetectionProbability = 1e-3;

// 1/2 nu^T S^-1 nu and 1/2 log det(2 pi S) of a joint innovation.
struct JointEval {
  double d2 = std::numeric_limits<double>::infinity();
  double half_log_det = 0.0;
};

// One candidate pair, linearised at the pose and the landmark's mean.
struct LinearPair {
  int measurement = 0;
  int landmark = 0;
  double d2 = 0.0;
  Vec2 nu = Vec2::Zero();
  Mat23 hx = Mat23::Zero();
  Mat2 own = Mat2::Zero();         ///< Hm Pm Hm^T + R
  Mat23 hm_cross = Mat23::Zero();  ///< Hm C: the landmark's correlation with the pose
  double log_pd = 0.0;             ///< log pD of the landmark at the pose
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
  out.log_pd = std::log(std::clamp(m.detection_probability, kMinDetectionProbability, 1.0));
  return out;
}

class JcbbSearch {
 public:
  JcbbSearch(std::vector<std::vector<LinearPair>> candidates, const Mat3& pose_cov,
             std::size_t landmarks, const Mat2& r, const JointCompatibilityOptions& options)
      : candidates_(std::move(candidates)),
        pose_cov_(pose_cov),
        used_(landmarks, false),
        max_nodes_(options.max_nodes),
        tail_(std::exp(-0.5 * options.gate_chi2)),
        likelihood_(options.null_intensity > 0.0),
        null_cost_(likelihood_ ? -std::log(options.null_intensity) : 0.0) {
    // The cheapest a measurement can cost: a pair costs at least 1/2 log det(2 pi R) (its
    // conditional innovation covariance is at least R, the squared distance at least 0, pD at
    // most 1).
    const double pair_floor = 0.5 * std::log((2.0 * std::numbers::pi * r).determinant());
    reachable_.assign(candidates_.size() + 1, 0);
    cost_floor_.assign(candidates_.size() + 1, 0.0);
    for (std::size_t j = candidates_.size(); j-- > 0;) {
      const bool has = !candidates_[j].empty();
      reachable_[j] = reachable_[j + 1] + (has ? 1 : 0);
      cost_floor_[j] = cost_floor_[j + 1] + (has ? std::min(null_cost_, pair_floor) : null_cost_);
    }
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
      if (Better(pairs)) {
        best_pairs_ = pairs;
        best_d2_ = joint_d2_;
        best_cost_ = Cost();
        best_choice_ = choice_;
      }
      return;
    }
    if (CutAt(j, pairs)) return;
    for (std::size_t c = 0; c < candidates_[j].size(); ++c) {
      const LinearPair& p = candidates_[j][c];
      if (used_[static_cast<std::size_t>(p.landmark)]) continue;
      const double before = joint_d2_;
      const double before_pair_cost = pair_cost_;
      const double before_log_pd = log_pd_sum_;
      if (!TryPush(&p)) continue;
      used_[static_cast<std::size_t>(p.landmark)] = true;
      choice_[j] = static_cast<int>(c);
      Visit(j + 1);
      choice_[j] = -1;
      used_[static_cast<std::size_t>(p.landmark)] = false;
      stack_.pop_back();
      joint_d2_ = before;
      pair_cost_ = before_pair_cost;
      log_pd_sum_ = before_log_pd;
    }
    ++nulls_;  // clutter or a new landmark
    if (!CutAt(j + 1, pairs)) Visit(j + 1);
    --nulls_;
  }

  // The likelihood objective: -log of the pairs' joint likelihood, pD included, and of the null
  // intensity of each measurement left out.
  [[nodiscard]] double Cost() const { return pair_cost_ + nulls_ * null_cost_; }

  [[nodiscard]] bool Better(int pairs) const {
    if (likelihood_) return Cost() < best_cost_;
    return pairs > best_pairs_ || (pairs == best_pairs_ && joint_d2_ < best_d2_);
  }

  // Whether no completion of the branch from measurement j on can beat the best.
  [[nodiscard]] bool CutAt(std::size_t j, int pairs) const {
    if (likelihood_) return Cost() + cost_floor_[j] >= best_cost_;
    return pairs + reachable_[j] < best_pairs_;
  }

  // Adds `p` to the stack when the pairs stay jointly compatible.
  bool TryPush(const LinearPair* p) {
    if (nodes_ >= max_nodes_) return false;
    ++nodes_;
    stack_.push_back(p);
    const JointEval e = Evaluate();
    if (std::isfinite(e.d2) && e.d2 < Threshold(stack_.size())) {
      joint_d2_ = e.d2;
      log_pd_sum_ += p->log_pd;
      pair_cost_ = 0.5 * e.d2 + e.half_log_det - log_pd_sum_;
      return true;
    }
    stack_.pop_back();
    return false;
  }

  JointEval Evaluate() const {
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
    JointEval e;
    if (llt.info() != Eigen::Success) return e;
    e.d2 = nu.dot(llt.solve(nu));
    const Eigen::VectorXd diagonal = llt.matrixL().toDenseMatrix().diagonal();
    e.half_log_det = diagonal.array().log().sum() +
                     0.5 * static_cast<double>(n) * std::log(2.0 * std::numbers::pi);
    return e;
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
  bool likelihood_;
  double null_cost_;                ///< -log of the null intensity (likelihood objective)
  std::vector<int> reachable_;      ///< measurements from j on that have a candidate
  std::vector<double> cost_floor_;  ///< the least cost of measurements j on
  std::vector<double> thresholds_;
  std::vector<const LinearPair*> stack_;
  std::vector<int> choice_;
  std::vector<int> best_choice_;
  double joint_d2_ = 0.0;
  double pair_cost_ = 0.0;
  double log_pd_sum_ = 0.0;
  int nulls_ = 0;
  double best_cost_ = std::numeric_limits<double>::infinity();
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
  if (!(options.null_intensity >= 0.0)) {
    throw std::invalid_argument("JointCompatibilityOptions.null_intensity: expected >= 0");
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
  const std::vector<int> choice = JcbbSearch(candidates, pose_cov, map.size(), r, options).Run();
  for (std::size_t j = 0; j < scan.size(); ++j) {
    if (choice[j] < 0) continue;
    const LinearPair& p = candidates[j][static_cast<std::size_t>(choice[j])];
    out.landmark[j] = p.landmark;
    out.mahalanobis2[j] = p.d2;
  }
  return out;
}

}  // namespace phdslam::reference
