// The Cholesky factorisation of a symmetric 3x3 matrix with Eigen 3.4's LLT<Matrix3d> arithmetic
// in its order, without its generic machinery (dynamic blocks, the L1 norm it keeps for rcond(),
// the blocked triangular solver it runs for a matrix right-hand side however small).
#pragma once

#include <Eigen/Core>
#include <cmath>

namespace phdslam {

/// A = L L^T for a symmetric 3x3 A read from its lower triangle. Every value it gives equals, bit
/// for bit, what Eigen::LLT<Matrix3d> and the expressions named at each member give (core_test
/// checks this on random matrices of every kind): a speed-up that changes no result.
class Cholesky3 {
 public:
  explicit Cholesky3(const Eigen::Matrix3d& a) {
    // LLT's unblocked loop: the pivot less the squared norm of the row left of it, stopping at a
    // pivot <= 0 (a NaN pivot goes on and fails the finiteness test); the column below divided by
    // the pivot's square root.
    const double x0 = a(0, 0);
    if (x0 <= 0.0) return;
    l_[0][0] = std::sqrt(x0);
    l_[1][0] = a(1, 0) / l_[0][0];
    l_[2][0] = a(2, 0) / l_[0][0];
    const double x1 = a(1, 1) - l_[1][0] * l_[1][0];
    if (x1 <= 0.0) return;
    l_[1][1] = std::sqrt(x1);
    l_[2][1] = (a(2, 1) - l_[2][0] * l_[1][0]) / l_[1][1];
    const double x2 = a(2, 2) - (l_[2][0] * l_[2][0] + l_[2][1] * l_[2][1]);
    if (x2 <= 0.0) return;
    l_[2][2] = std::sqrt(x2);
    positive_definite_ = true;
    for (int i = 0; i < 3; ++i) {
      if (!(l_[i][i] > 0.0) || !std::isfinite(l_[i][i])) positive_definite_ = false;
    }
  }

  /// LltIsPositiveDefinite's verdict on LLT(A): it succeeded, every pivot positive and finite.
  [[nodiscard]] bool positive_definite() const { return positive_definite_; }

  /// L.diagonal().array().log().sum(). Only for a positive-definite A.
  [[nodiscard]] double LogDiagonalSum() const {
    return (std::log(l_[0][0]) + std::log(l_[1][1])) + std::log(l_[2][2]);
  }

  /// log det A as 2 * L.diagonal().array().log().sum(). Only for a positive-definite A.
  [[nodiscard]] double LogDet() const { return 2.0 * LogDiagonalSum(); }

  /// L, zero above the diagonal (Matrix3d(LLT::matrixL())).
  [[nodiscard]] Eigen::Matrix3d L() const {
    Eigen::Matrix3d l = Eigen::Matrix3d::Zero();
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j <= i; ++j) l(i, j) = l_[i][j];
    }
    return l;
  }

  /// L^-1 as L.triangularView<Lower>().solve(Matrix3d::Identity()) with L = Matrix3d(matrixL()):
  /// the blocked solver's substitutions, each pivot applied as a product with its reciprocal.
  /// Only for a positive-definite A.
  [[nodiscard]] Eigen::Matrix3d InverseOfL() const {
    const double r0 = 1.0 / l_[0][0];
    const double r1 = 1.0 / l_[1][1];
    const double r2 = 1.0 / l_[2][2];
    Eigen::Matrix3d x;
    for (int j = 0; j < 3; ++j) {
      const double y0 = (j == 0 ? 1.0 : 0.0) * r0;
      const double y1 = ((j == 1 ? 1.0 : 0.0) - y0 * l_[1][0]) * r1;
      const double y2 = (((j == 2 ? 1.0 : 0.0) - y0 * l_[2][0]) - y1 * l_[2][1]) * r2;
      x(0, j) = y0;
      x(1, j) = y1;
      x(2, j) = y2;
    }
    return x;
  }

  /// L^-1 r as L.triangularView<Lower>().solve(r): forward substitution dividing by each pivot.
  [[nodiscard]] Eigen::Vector3d SolveLower(const Eigen::Vector3d& r) const {
    Eigen::Vector3d w;
    w(0) = r(0) / l_[0][0];
    w(1) = (r(1) - l_[1][0] * w(0)) / l_[1][1];
    w(2) = (r(2) - (l_[2][0] * w(0) + l_[2][1] * w(1))) / l_[2][2];
    return w;
  }

  /// A^-1 r as LLT::solve(r): SolveLower, then the back substitution with L^T.
  [[nodiscard]] Eigen::Vector3d Solve(const Eigen::Vector3d& r) const {
    Eigen::Vector3d x = SolveLower(r);
    x(2) = x(2) / l_[2][2];
    x(1) = (x(1) - l_[2][1] * x(2)) / l_[1][1];
    x(0) = (x(0) - (l_[1][0] * x(1) + l_[2][0] * x(2))) / l_[0][0];
    return x;
  }

  /// trace(A^-1 B) as LLT::solve(B).trace(): the blocked solver's column-by-column substitutions,
  /// each pivot applied as a product with its reciprocal, of which the diagonal is summed.
  [[nodiscard]] double TraceOfSolve(const Eigen::Matrix3d& b) const {
    const double r0 = 1.0 / l_[0][0];
    const double r1 = 1.0 / l_[1][1];
    const double r2 = 1.0 / l_[2][2];
    double diagonal[3];
    for (int j = 0; j < 3; ++j) {
      // L y = b_j.
      const double y0 = b(0, j) * r0;
      double y1 = b(1, j) - y0 * l_[1][0];
      double y2 = b(2, j) - y0 * l_[2][0];
      y1 *= r1;
      y2 = (y2 - y1 * l_[2][1]) * r2;
      // L^T x = y.
      const double x2 = (y2 - 0.0) * r2;
      const double x1 = (y1 - (0.0 + l_[2][1] * x2)) * r1;
      const double x0 = (y0 - ((0.0 + l_[1][0] * x1) + l_[2][0] * x2)) * r0;
      diagonal[j] = j == 0 ? x0 : (j == 1 ? x1 : x2);
    }
    return diagonal[0] + (diagonal[1] + diagonal[2]);
  }

 private:
  double l_[3][3] = {};  // the lower triangle of L; l_[i][j] = L(i, j)
  bool positive_definite_ = false;
};

}  // namespace phdslam
