#include "reference/ceres/marginalization.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>

#include "src/core/gaussian.h"

namespace phdslam::reference {
namespace {

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// Every block the factors touch, in first-seen order, with its size.
std::vector<std::pair<double*, int>> TouchedBlocks(const std::vector<const GraphFactor*>& factors) {
  std::vector<std::pair<double*, int>> out;
  std::set<const double*> seen;
  for (const GraphFactor* f : factors) {
    const std::vector<int>& sizes = f->cost->parameter_block_sizes();
    for (std::size_t i = 0; i < f->blocks.size(); ++i) {
      if (seen.insert(f->blocks[i]).second) out.emplace_back(f->blocks[i], sizes[i]);
    }
  }
  return out;
}

/// Symmetric pseudo-inverse over the eigenvalues above rel * the largest.
Eigen::MatrixXd PseudoInverse(const Eigen::MatrixXd& h, double rel) {
  if (h.rows() == 0) return h;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(h);
  const Eigen::VectorXd& l = eig.eigenvalues();
  const double floor = rel * std::max(l.maxCoeff(), 0.0);
  Eigen::VectorXd inv(l.size());
  for (Eigen::Index i = 0; i < l.size(); ++i) inv(i) = l(i) > floor ? 1.0 / l(i) : 0.0;
  return eig.eigenvectors() * inv.asDiagonal() * eig.eigenvectors().transpose();
}

constexpr double kRelativeEigenvalueFloor = 1e-12;

}  // namespace

DenseSystem Linearize(const std::vector<const GraphFactor*>& factors,
                      const std::vector<double*>& order, const FixedPoints& fixed_points) {
  DenseSystem s;
  s.order = order;
  std::map<const double*, int> index;
  const std::vector<std::pair<double*, int>> touched = TouchedBlocks(factors);
  std::map<const double*, int> size_of;
  for (const auto& [block, size] : touched) size_of[block] = size;
  int n = 0;
  for (std::size_t i = 0; i < order.size(); ++i) {
    index[order[i]] = static_cast<int>(i);
    s.offsets.push_back(n);
    const auto it = size_of.find(order[i]);
    const int size = it == size_of.end() ? 0 : it->second;
    s.sizes.push_back(size);
    n += size;
  }
  s.h = Eigen::MatrixXd::Zero(n, n);
  s.g = Eigen::VectorXd::Zero(n);
  for (const GraphFactor* f : factors) {
    const std::vector<int>& sizes = f->cost->parameter_block_sizes();
    const std::size_t nb = f->blocks.size();
    std::vector<Eigen::VectorXd> points(nb);
    std::vector<const double*> params(nb);
    for (std::size_t i = 0; i < nb; ++i) {
      const auto fp = fixed_points.find(f->blocks[i]);
      points[i] = fp != fixed_points.end()
                      ? fp->second
                      : Eigen::Map<const Eigen::VectorXd>(f->blocks[i], sizes[i]).eval();
      params[i] = points[i].data();
    }
    const int m = f->cost->num_residuals();
    Eigen::VectorXd r(m);
    std::vector<RowMajor> jac(nb);
    std::vector<double*> jac_ptr(nb);
    for (std::size_t i = 0; i < nb; ++i) {
      jac[i].resize(m, sizes[i]);
      jac_ptr[i] = jac[i].data();
    }
    if (!f->cost->Evaluate(params.data(), r.data(), jac_ptr.data())) {
      ++s.failed_factors;
      continue;
    }
    if (f->loss) {
      double rho[3];
      f->loss->Evaluate(r.squaredNorm(), rho);
      const double w = std::sqrt(std::max(rho[1], 0.0));
      r *= w;
      for (RowMajor& j : jac) j *= w;
    }
    for (std::size_t a = 0; a < nb; ++a) {
      const auto ia = index.find(f->blocks[a]);
      if (ia == index.end()) continue;
      const int oa = s.offsets[static_cast<std::size_t>(ia->second)];
      s.g.segment(oa, sizes[a]) += jac[a].transpose() * r;
      for (std::size_t b = 0; b < nb; ++b) {
        const auto ib = index.find(f->blocks[b]);
        if (ib == index.end()) continue;
        const int ob = s.offsets[static_cast<std::size_t>(ib->second)];
        s.h.block(oa, ob, sizes[a], sizes[b]) += jac[a].transpose() * jac[b];
      }
    }
  }
  return s;
}

namespace {

/// The linearised system of every non-constant block the factors touch (first-seen order) and the
/// LDLT factor of its information matrix.
struct FactoredSystem {
  std::vector<double*> order;
  DenseSystem system;
  Eigen::LDLT<Eigen::MatrixXd> ldlt;

  /// Index of block b in `order`, -1 when the factors do not make it free.
  std::ptrdiff_t IndexOf(const double* b) const {
    const auto it = std::find(order.begin(), order.end(), b);
    return it == order.end() ? -1 : it - order.begin();
  }
  /// H^-1 restricted to the columns of block i.
  Eigen::MatrixXd ColumnBlock(std::size_t i) const {
    return ldlt.solve(Eigen::MatrixXd::Identity(system.h.rows(), system.h.cols())
                          .middleCols(system.offsets[i], system.sizes[i]));
  }
};

/// Null when the information matrix is not positive definite.
std::optional<FactoredSystem> FactorFreeBlocks(const std::vector<const GraphFactor*>& factors,
                                               const std::set<const double*>& constant) {
  FactoredSystem f;
  for (const auto& [block, size] : TouchedBlocks(factors)) {
    if (constant.count(block) == 0) f.order.push_back(block);
  }
  f.system = Linearize(factors, f.order, {});
  f.ldlt.compute(f.system.h);
  if (f.ldlt.info() != Eigen::Success || !f.ldlt.isPositive()) return std::nullopt;
  return f;
}

}  // namespace

LinearPrior Marginalize(const std::vector<const GraphFactor*>& factors,
                        const std::vector<double*>& marginalized,
                        const std::set<const double*>& constant, const FixedPoints& fixed_points) {
  const std::set<const double*> gone(marginalized.begin(), marginalized.end());
  std::vector<double*> order;
  for (double* b : marginalized) {
    if (constant.count(b) == 0) order.push_back(b);
  }
  const std::size_t first_kept = order.size();
  for (const auto& [block, size] : TouchedBlocks(factors)) {
    if (gone.count(block) == 0 && constant.count(block) == 0) order.push_back(block);
  }
  const DenseSystem s = Linearize(factors, order, fixed_points);
  const int nm = first_kept == order.size() ? static_cast<int>(s.g.size()) : s.offsets[first_kept];
  const int nk = static_cast<int>(s.g.size()) - nm;
  LinearPrior prior;
  if (nk == 0) return prior;
  const Eigen::MatrixXd hmm_inv =
      PseudoInverse(s.h.topLeftCorner(nm, nm), kRelativeEigenvalueFloor);
  const Eigen::MatrixXd hkm = s.h.bottomLeftCorner(nk, nm);
  Eigen::MatrixXd hs = s.h.bottomRightCorner(nk, nk) - hkm * hmm_inv * hkm.transpose();
  Symmetrize(hs);
  const Eigen::VectorXd gs = s.g.tail(nk) - hkm * hmm_inv * s.g.head(nm);

  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(hs);
  const Eigen::VectorXd& l = eig.eigenvalues();
  const double floor = kRelativeEigenvalueFloor * std::max(l.maxCoeff(), 0.0);
  std::vector<Eigen::Index> rows;
  for (Eigen::Index i = 0; i < l.size(); ++i) {
    if (l(i) > floor) rows.push_back(i);
  }
  prior.a.resize(static_cast<Eigen::Index>(rows.size()), nk);
  prior.b.resize(static_cast<Eigen::Index>(rows.size()));
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto ri = static_cast<Eigen::Index>(i);
    const double sl = std::sqrt(l(rows[i]));
    const Eigen::VectorXd u = eig.eigenvectors().col(rows[i]);
    prior.a.row(ri) = sl * u.transpose();
    prior.b(ri) = u.dot(gs) / sl;
  }
  for (std::size_t i = first_kept; i < order.size(); ++i) {
    prior.blocks.push_back(order[i]);
    const auto fp = fixed_points.find(order[i]);
    prior.linearization_points.push_back(
        fp != fixed_points.end() ? fp->second
                                 : Eigen::Map<const Eigen::VectorXd>(order[i], s.sizes[i]).eval());
  }
  return prior;
}

std::vector<Eigen::MatrixXd> MarginalCovariances(const std::vector<const GraphFactor*>& factors,
                                                 const std::set<const double*>& constant,
                                                 const std::vector<const double*>& wanted) {
  const std::optional<FactoredSystem> f = FactorFreeBlocks(factors, constant);
  if (!f) return {};
  std::vector<Eigen::MatrixXd> out;
  for (const double* w : wanted) {
    const std::ptrdiff_t k = f->IndexOf(w);
    if (k < 0) return {};
    const auto i = static_cast<std::size_t>(k);
    Eigen::MatrixXd c = f->ColumnBlock(i).middleRows(f->system.offsets[i], f->system.sizes[i]);
    Symmetrize(c);
    if (!c.allFinite()) return {};
    out.push_back(c);
  }
  return out;
}

AnchoredCovariances AnchoredMarginalCovariances(const std::vector<const GraphFactor*>& factors,
                                                const std::set<const double*>& constant,
                                                const double* anchor,
                                                const std::vector<const double*>& wanted) {
  const std::optional<FactoredSystem> f = FactorFreeBlocks(factors, constant);
  if (!f) return {};
  const std::ptrdiff_t a = f->IndexOf(anchor);
  if (a < 0) return {};
  const auto ai = static_cast<std::size_t>(a);
  const Eigen::MatrixXd anchor_columns = f->ColumnBlock(ai);
  AnchoredCovariances out;
  out.anchor = anchor_columns.middleRows(f->system.offsets[ai], f->system.sizes[ai]);
  Symmetrize(out.anchor);
  if (!out.anchor.allFinite()) return {};
  for (const double* w : wanted) {
    const std::ptrdiff_t k = f->IndexOf(w);
    if (k < 0) return {};
    const auto ki = static_cast<std::size_t>(k);
    Eigen::MatrixXd c = f->ColumnBlock(ki).middleRows(f->system.offsets[ki], f->system.sizes[ki]);
    Symmetrize(c);
    Eigen::MatrixXd x = anchor_columns.middleRows(f->system.offsets[ki], f->system.sizes[ki]);
    if (!c.allFinite() || !x.allFinite()) return {};
    out.marginal.push_back(std::move(c));
    out.cross.push_back(std::move(x));
  }
  return out;
}

}  // namespace phdslam::reference
