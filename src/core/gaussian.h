// Small dense Gaussian helpers for fixed-size Eigen types.
//
// Covariances are kept symmetric positive-definite as follows: every update that can lose
// symmetry to rounding (Joseph-free Kalman updates, moment matching, propagation) is followed by
// Symmetrize(); densities and sampling go through an LLT whose failure is reported to the caller,
// which then applies the reference fallback (keep the previous iterate, or do not sample).
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <type_traits>

#include "src/core/cholesky3.h"

namespace phdslam {

/// Replaces P by (P + P^T) / 2 in place: each pair of off-diagonal entries by 0.5 (a + b), each
/// diagonal entry by 0.5 (d + d), element by element without a temporary matrix (the values of
/// (0.5 * (P + P^T)).eval(), bit for bit).
template <typename Derived>
void Symmetrize(Eigen::MatrixBase<Derived>& p) {
  for (Eigen::Index c = 0; c < p.cols(); ++c) {
    for (Eigen::Index r = 0; r <= c && r < p.rows(); ++r) {
      const typename Derived::Scalar v = 0.5 * (p(r, c) + p(c, r));
      p(r, c) = v;
      p(c, r) = v;
    }
  }
}

/// Lower Cholesky factor, or nullopt when P is not numerically positive definite
/// (any pivot <= 0 or not finite).
/// Whether an Eigen::LLT factorisation shows P numerically positive definite: it succeeded and
/// every pivot (diagonal of L) is positive and finite. The test of CholeskyLower, for callers that
/// keep the factorisation to solve with it.
template <typename Llt>
bool LltIsPositiveDefinite(const Llt& llt) {
  if (llt.info() != Eigen::Success) return false;
  const auto pivots = llt.matrixLLT().diagonal();
  for (Eigen::Index i = 0; i < pivots.size(); ++i) {
    if (!(pivots(i) > 0.0) || !std::isfinite(pivots(i))) return false;
  }
  return true;
}

/// The Cholesky factor L (A = L L^T) of a symmetric 2x2 A, read from its lower triangle, with
/// the operations of Eigen's LLT<Matrix2d> in their order: the factor, the verdict of
/// LltIsPositiveDefinite and Inverse() (LLT::solve of the identity) are theirs bit for bit, without
/// the blocked triangular solver Eigen runs for a matrix right-hand side however small.
class Cholesky2 {
 public:
  explicit Cholesky2(const Eigen::Matrix2d& a) {
    const double x0 = a(0, 0);
    if (!(x0 > 0.0)) return;  // LLT stops at a pivot <= 0; a NaN pivot fails the check below
    l00_ = std::sqrt(x0);
    l10_ = a(1, 0) / l00_;
    const double x1 = a(1, 1) - l10_ * l10_;
    if (!(x1 > 0.0)) return;
    l11_ = std::sqrt(x1);
    positive_definite_ = std::isfinite(l00_) && std::isfinite(l11_);
  }

  /// Whether A is numerically positive definite (LltIsPositiveDefinite's test).
  [[nodiscard]] bool positive_definite() const { return positive_definite_; }

  /// log det A as 2 * L.diagonal().array().log().sum(). Only for a positive-definite A.
  [[nodiscard]] double LogDet() const { return 2.0 * (std::log(l00_) + std::log(l11_)); }

  /// L^-1 r as L.triangularView<Lower>().solve(r): forward substitution dividing by each pivot.
  [[nodiscard]] Eigen::Vector2d SolveLower(const Eigen::Vector2d& r) const {
    const double w0 = r(0) / l00_;
    return {w0, (r(1) - l10_ * w0) / l11_};
  }

  /// A^-1, solved column by column as L y = e_j, then L^T x = y, each pivot applied as a product
  /// with its reciprocal. Only for a positive-definite A.
  [[nodiscard]] Eigen::Matrix2d Inverse() const {
    const double r0 = 1.0 / l00_;
    const double r1 = 1.0 / l11_;
    Eigen::Matrix2d x;
    for (int j = 0; j < 2; ++j) {
      const double y0 = (j == 0 ? 1.0 : 0.0) * r0;
      const double y1 = ((j == 1 ? 1.0 : 0.0) - y0 * l10_) * r1;
      const double x1 = (y1 - 0.0) * r1;
      x(1, j) = x1;
      x(0, j) = (y0 - (0.0 + l10_ * x1)) * r0;
    }
    return x;
  }

 private:
  double l00_ = 0.0;
  double l10_ = 0.0;
  double l11_ = 0.0;
  bool positive_definite_ = false;
};

template <int N>
std::optional<Eigen::Matrix<double, N, N>> CholeskyLower(const Eigen::Matrix<double, N, N>& p) {
  const Eigen::LLT<Eigen::Matrix<double, N, N>> llt(p);
  if (!LltIsPositiveDefinite(llt)) return std::nullopt;
  return Eigen::Matrix<double, N, N>(llt.matrixL());
}

/// A square root S (S S^T = P) of a symmetric positive semi-definite P through its
/// eigen-decomposition, eigenvalues below zero (round-off) taken as zero. Unlike CholeskyLower it
/// exists for singular P (e.g. a noise without a heading component), so draws x = mu + S xi need
/// no fallback; it does not check P.
template <int N>
Eigen::Matrix<double, N, N> PsdSquareRoot(const Eigen::Matrix<double, N, N>& p) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, N, N>> eig(p);
  return eig.eigenvectors() * eig.eigenvalues().cwiseMax(0.0).cwiseSqrt().asDiagonal();
}

/// log N(x; mu, S) via a Cholesky factor of S; nullopt when S is not positive definite.
/// For N = 2 and 3 through Cholesky2 and Cholesky3, which give Eigen's LLT values bit for bit: the
/// same result as the general path, at a fraction of its cost.
template <int N>
std::optional<double> LogNormalPdf(const Eigen::Matrix<double, N, 1>& x,
                                   const Eigen::Matrix<double, N, 1>& mu,
                                   const Eigen::Matrix<double, N, N>& s) {
  if constexpr (N == 2 || N == 3) {
    using Factor = std::conditional_t<N == 2, Cholesky2, Cholesky3>;
    const Factor factor(s);
    if (!factor.positive_definite()) return std::nullopt;
    const Eigen::Matrix<double, N, 1> w = factor.SolveLower(x - mu);
    return -0.5 * (N * std::log(2.0 * std::numbers::pi) + factor.LogDet() + w.squaredNorm());
  } else {
    const auto l = CholeskyLower<N>(s);
    if (!l) return std::nullopt;
    const Eigen::Matrix<double, N, 1> w = l->template triangularView<Eigen::Lower>().solve(x - mu);
    const double log_det = 2.0 * l->diagonal().array().log().sum();
    return -0.5 * (N * std::log(2.0 * std::numbers::pi) + log_det + w.squaredNorm());
  }
}

/// A pre-gate for the test nu' S^-1 nu < gate with a 2x2 positive-definite S: when
/// |nu(0)| > FirstCoordinateGateHalfWidth(S, gate), the test fails, since nu' S^-1 nu >=
/// nu(0)^2 / S(0, 0). The half-width is enlarged by a relative 1e-3 so that no rounding of the full
/// test can disagree with the skip: the pre-gate saves the quadratic form of pairs that are far
/// apart and changes no gating decision. When S is not positive definite (the bound needs it) or
/// holds NaN, the half-width is infinite or NaN, which skips nothing.
inline double FirstCoordinateGateHalfWidth(const Eigen::Matrix2d& s, double gate) {
  const bool positive_definite = s(0, 0) > 0.0 && s(0, 0) * s(1, 1) - s(0, 1) * s(1, 0) > 0.0;
  if (!positive_definite) return std::numeric_limits<double>::infinity();
  return 1.001 * std::sqrt(gate * s(0, 0));
}

/// log N(r; 0, S) for a 2-D residual with an explicit 2x2 inverse, plus the squared Mahalanobis
/// distance. Used on the hot path of the PHD update and the cost matrix.
struct Gaussian2Eval {
  double log_pdf;
  double mahalanobis2;
};
inline Gaussian2Eval EvalGaussian2(const Eigen::Vector2d& r, const Eigen::Matrix2d& s) {
  const double det = s(0, 0) * s(1, 1) - s(0, 1) * s(1, 0);
  const double d2 =
      (s(1, 1) * r(0) * r(0) - (s(0, 1) + s(1, 0)) * r(0) * r(1) + s(0, 0) * r(1) * r(1)) / det;
  return {-std::log(2.0 * std::numbers::pi) - 0.5 * std::log(det) - 0.5 * d2, d2};
}

}  // namespace phdslam
