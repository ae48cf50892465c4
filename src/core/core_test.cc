#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <vector>

#include "src/core/angles.h"
#include "src/core/byte_tally.h"
#include "src/core/gaussian.h"
#include "src/core/log_sum_exp.h"
#include "src/core/random.h"

namespace phdslam {
namespace {

TEST(Angles, WrapMapsIntoMinusPiPi) {
  for (double a = -20.0; a < 20.0; a += 0.37) {
    const double w = WrapAngle(a);
    EXPECT_GE(w, -M_PI);
    EXPECT_LE(w, M_PI);
    EXPECT_NEAR(std::remainder(a - w, 2.0 * M_PI), 0.0, 1e-12);
  }
}

TEST(LogSumExp, MatchesDirectSumAndHandlesNegInf) {
  const std::vector<double> x = {-1.0, 0.5, -3.0};
  EXPECT_NEAR(LogSumExp(x), std::log(std::exp(-1.0) + std::exp(0.5) + std::exp(-3.0)), 1e-14);
  EXPECT_EQ(LogSumExp(std::vector<double>{}), kNegInf);
  EXPECT_EQ(LogSumExp(std::vector<double>{kNegInf, kNegInf}), kNegInf);
  EXPECT_NEAR(LogSumExp(std::vector<double>{-1000.0, -1000.0}), -1000.0 + std::log(2.0), 1e-12);
  EXPECT_NEAR(LogAddExp(kNegInf, 2.0), 2.0, 0.0);
}

TEST(Gaussian, LogPdfMatchesClosedFormAndRejectsIndefinite) {
  Eigen::Matrix2d s;
  s << 2.0, 0.3, 0.3, 1.0;
  const Eigen::Vector2d x(0.4, -0.2);
  const Eigen::Vector2d mu(0.1, 0.1);
  const Eigen::Vector2d r = x - mu;
  const double expect =
      -std::log(2 * M_PI) - 0.5 * std::log(s.determinant()) - 0.5 * r.dot(s.inverse() * r);
  EXPECT_NEAR(*LogNormalPdf<2>(x, mu, s), expect, 1e-13);
  EXPECT_NEAR(EvalGaussian2(r, s).log_pdf, expect, 1e-13);
  Eigen::Matrix2d bad;
  bad << 1.0, 2.0, 2.0, 1.0;
  EXPECT_FALSE(LogNormalPdf<2>(x, mu, bad).has_value());
  EXPECT_FALSE(CholeskyLower<2>(Eigen::Matrix2d::Zero()).has_value());
}

TEST(Gaussian, FirstCoordinatePreGateNeverSkipsAPairTheFullTestKeeps) {
  // Random positive-definite S (condition numbers up to about 1e5, as range-bearing innovation
  // covariances have) and residuals near the gate: every skipped residual fails the full test.
  RandomStream rng(11);
  const double gate = 9.21;
  int skipped = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const double a = std::exp(4.0 * rng.Normal());
    const double b = std::exp(4.0 * rng.Normal());
    const double c = 0.99 * std::sqrt(a * b) * std::tanh(rng.Normal());
    Eigen::Matrix2d s;
    s << a, c, c, b;
    const double w = FirstCoordinateGateHalfWidth(s, gate);
    const Eigen::Vector2d nu(3.0 * std::sqrt(a) * rng.Normal(), 3.0 * std::sqrt(b) * rng.Normal());
    if (std::abs(nu(0)) > w) {
      ++skipped;
      EXPECT_GE(nu.dot(s.inverse() * nu), gate) << "trial " << trial;
    }
  }
  EXPECT_GT(skipped, 1000);  // the pre-gate does skip
  // Not positive definite, or NaN: nothing is skipped.
  Eigen::Matrix2d indefinite;
  indefinite << 1.0, 2.0, 2.0, 1.0;
  EXPECT_EQ(FirstCoordinateGateHalfWidth(indefinite, gate),
            std::numeric_limits<double>::infinity());
  Eigen::Matrix2d with_nan = Eigen::Matrix2d::Identity();
  with_nan(1, 1) = std::nan("");
  EXPECT_FALSE(std::abs(1e300) > FirstCoordinateGateHalfWidth(with_nan, gate));
}

template <typename Matrix>
void ExpectSymmetrizeEqualsTheMatrixExpression(RandomStream& rng, Matrix p) {
  for (Eigen::Index r = 0; r < p.rows(); ++r) {
    for (Eigen::Index c = 0; c < p.cols(); ++c)
      p(r, c) = std::exp(6.0 * rng.Normal()) * rng.Normal();
  }
  const Matrix expected = (0.5 * (p + p.transpose())).eval();
  Symmetrize(p);
  for (Eigen::Index r = 0; r < p.rows(); ++r) {
    for (Eigen::Index c = 0; c < p.cols(); ++c) {
      EXPECT_EQ(p(r, c), expected(r, c)) << r << "," << c;  // bit for bit, not approximately
    }
  }
}

TEST(Gaussian, SymmetrizeGivesTheValuesOfTheMatrixExpressionBitForBit) {
  RandomStream rng(5);
  for (int trial = 0; trial < 200; ++trial) {
    ExpectSymmetrizeEqualsTheMatrixExpression(rng, Eigen::Matrix2d());
    ExpectSymmetrizeEqualsTheMatrixExpression(rng, Eigen::Matrix3d());
    ExpectSymmetrizeEqualsTheMatrixExpression(rng, Eigen::MatrixXd(7, 7));
  }
}

// Symmetric 2x2 matrices of every kind Cholesky2 meets: well and badly conditioned positive
// definite ones over many scales, indefinite, singular, zero, negative and NaN ones.
Eigen::Matrix2d RandomSymmetric2(RandomStream& rng, int trial) {
  const double scale = std::pow(10.0, rng.Uniform(-8.0, 8.0));
  Eigen::Matrix2d a;
  a(0, 0) = scale * rng.Uniform(-0.2, 3.0);
  a(1, 1) = scale * rng.Uniform(-0.2, 3.0);
  const double bound = std::sqrt(std::abs(a(0, 0) * a(1, 1)));
  a(1, 0) = bound * rng.Uniform(-1.05, 1.05);
  if (trial % 97 == 0) a(1, 0) = std::sqrt(a(0, 0) * a(1, 1));  // singular, or NaN when < 0
  if (trial % 89 == 0) a.setZero();
  if (trial % 83 == 0) a(1, 1) = std::numeric_limits<double>::quiet_NaN();
  a(0, 1) = a(1, 0);
  return a;
}

TEST(Gaussian, Cholesky2GivesEigenLltsVerdictAndInverseBitForBit) {
  RandomStream rng(11);
  int positive_definite = 0;
  int not_positive_definite = 0;
  for (int trial = 0; trial < 200000; ++trial) {
    const Eigen::Matrix2d a = RandomSymmetric2(rng, trial);
    const Eigen::LLT<Eigen::Matrix2d> llt(a);
    const Cholesky2 factor(a);
    ASSERT_EQ(factor.positive_definite(), LltIsPositiveDefinite(llt)) << "trial " << trial << "\n"
                                                                      << a;
    if (!factor.positive_definite()) {
      ++not_positive_definite;
      continue;
    }
    ++positive_definite;
    const Eigen::Matrix2d expected = llt.solve(Eigen::Matrix2d::Identity());
    const Eigen::Matrix2d inverse = factor.Inverse();
    for (int r = 0; r < 2; ++r) {
      for (int c = 0; c < 2; ++c) {
        ASSERT_EQ(inverse(r, c), expected(r, c))
            << "trial " << trial << " (" << r << ", " << c << ")\n"
            << a;  // bit for bit, not approximately
      }
    }
  }
  EXPECT_GT(positive_definite, 100000);
  EXPECT_GT(not_positive_definite, 10000);
}

// Symmetric 3x3 matrices of every kind Cholesky3 meets: well and badly conditioned positive
// definite ones over many scales, indefinite, singular, zero and NaN ones.
Eigen::Matrix3d RandomSymmetric3(RandomStream& rng, int trial) {
  const double scale = std::pow(10.0, rng.Uniform(-8.0, 8.0));
  Eigen::Matrix3d b;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) b(r, c) = rng.Uniform(-1.0, 1.0);
  }
  Eigen::Matrix3d a = scale * (b * b.transpose());
  for (int i = 0; i < 3; ++i) a(i, i) += scale * rng.Uniform(-0.05, 0.3);
  if (trial % 97 == 0) {  // singular: the third row the sum of the others
    a.row(2) = a.row(0) + a.row(1);
    a.col(2) = a.row(2).transpose();
  }
  if (trial % 89 == 0) a.setZero();
  if (trial % 83 == 0) a(2, 1) = a(1, 2) = std::numeric_limits<double>::quiet_NaN();
  if (trial % 79 == 0) a(0, 0) = -a(0, 0);
  return a;
}

TEST(Gaussian, Cholesky3GivesEigenLltsValuesBitForBit) {
  RandomStream rng(13);
  int positive_definite = 0;
  int not_positive_definite = 0;
  for (int trial = 0; trial < 200000; ++trial) {
    const Eigen::Matrix3d a = RandomSymmetric3(rng, trial);
    const Eigen::LLT<Eigen::Matrix3d> llt(a);
    const Cholesky3 factor(a);
    ASSERT_EQ(factor.positive_definite(), LltIsPositiveDefinite(llt)) << "trial " << trial << "\n"
                                                                      << a;
    if (!factor.positive_definite()) {
      ++not_positive_definite;
      continue;
    }
    ++positive_definite;
    const Eigen::Vector3d r(rng.Normal(), rng.Normal(), rng.Normal());
    Eigen::Matrix3d b;
    for (int c = 0; c < 3; ++c)
      b.col(c) = Eigen::Vector3d(rng.Normal(), rng.Normal(), rng.Normal());
    const Eigen::Matrix3d l = llt.matrixL();
    // Bit for bit, not approximately.
    ASSERT_EQ(factor.LogDet(), 2.0 * llt.matrixLLT().diagonal().array().log().sum()) << trial;
    const Eigen::Vector3d lower = l.triangularView<Eigen::Lower>().solve(r);
    const Eigen::Vector3d full = llt.solve(r);
    ASSERT_EQ(factor.SolveLower(r), lower) << trial;
    ASSERT_EQ(factor.Solve(r), full) << trial;
    ASSERT_EQ(factor.TraceOfSolve(b), llt.solve(b).trace()) << trial;
    ASSERT_EQ(factor.L(), l) << trial;
    ASSERT_EQ(factor.LogDiagonalSum(), l.diagonal().array().log().sum()) << trial;
    const Eigen::Matrix3d l_inverse =
        l.triangularView<Eigen::Lower>().solve(Eigen::Matrix3d::Identity());
    ASSERT_EQ(factor.InverseOfL(), l_inverse) << trial;
  }
  EXPECT_GT(positive_definite, 100000);
  EXPECT_GT(not_positive_definite, 5000);
}

/// LogNormalPdf's general path (Eigen's LLT and triangular solver), which N = 2 and 3 bypass.
template <int N>
std::optional<double> LogNormalPdfByEigen(const Eigen::Matrix<double, N, 1>& x,
                                          const Eigen::Matrix<double, N, 1>& mu,
                                          const Eigen::Matrix<double, N, N>& s) {
  const auto l = CholeskyLower<N>(s);
  if (!l) return std::nullopt;
  const Eigen::Matrix<double, N, 1> w = l->template triangularView<Eigen::Lower>().solve(x - mu);
  const double log_det = 2.0 * l->diagonal().array().log().sum();
  return -0.5 * (N * std::log(2.0 * std::numbers::pi) + log_det + w.squaredNorm());
}

TEST(Gaussian, LogNormalPdfOfTwoAndThreeDimensionsIsTheGeneralPathsBitForBit) {
  RandomStream rng(17);
  int compared = 0;
  for (int trial = 0; trial < 100000; ++trial) {
    const Eigen::Matrix2d s2 = RandomSymmetric2(rng, trial);
    const Eigen::Matrix3d s3 = RandomSymmetric3(rng, trial);
    const double spread = std::pow(10.0, rng.Uniform(-6.0, 6.0));
    const Eigen::Vector2d x2(spread * rng.Normal(), spread * rng.Normal());
    const Eigen::Vector2d mu2(rng.Normal(), rng.Normal());
    const Eigen::Vector3d x3(spread * rng.Normal(), spread * rng.Normal(), rng.Normal());
    const Eigen::Vector3d mu3(rng.Normal(), rng.Normal(), rng.Normal());
    const std::optional<double> got2 = LogNormalPdf<2>(x2, mu2, s2);
    const std::optional<double> want2 = LogNormalPdfByEigen<2>(x2, mu2, s2);
    const std::optional<double> got3 = LogNormalPdf<3>(x3, mu3, s3);
    const std::optional<double> want3 = LogNormalPdfByEigen<3>(x3, mu3, s3);
    ASSERT_EQ(got2.has_value(), want2.has_value()) << trial;
    ASSERT_EQ(got3.has_value(), want3.has_value()) << trial;
    if (got2) {
      ASSERT_EQ(*got2, *want2) << trial;
    }
    if (got3) {
      ASSERT_EQ(*got3, *want3) << trial;
    }
    compared += (got2 ? 1 : 0) + (got3 ? 1 : 0);
  }
  EXPECT_GT(compared, 150000);
}

TEST(RandomStream, IsReproducibleAndSeedsAreIndependent) {
  RandomStream a(DeriveSeed(1, 2, 3));
  RandomStream b(DeriveSeed(1, 2, 3));
  RandomStream c(DeriveSeed(1, 3, 2));
  bool differs = false;
  for (int i = 0; i < 100; ++i) {
    const double va = a.Normal();
    EXPECT_EQ(va, b.Normal());
    differs = differs || (va != c.Normal());
  }
  EXPECT_TRUE(differs);
}

TEST(RandomStream, MomentsAreRight) {
  RandomStream r(7);
  const int n = 200000;
  double s = 0.0;
  double s2 = 0.0;
  double u = 0.0;
  double p = 0.0;
  for (int i = 0; i < n; ++i) {
    const double z = r.Normal();
    s += z;
    s2 += z * z;
    u += r.Uniform();
    p += r.Poisson(4.75);
  }
  EXPECT_NEAR(s / n, 0.0, 0.01);
  EXPECT_NEAR(s2 / n, 1.0, 0.01);
  EXPECT_NEAR(u / n, 0.5, 0.005);
  EXPECT_NEAR(p / n, 4.75, 0.02);
}

TEST(ByteTally, CountsEachBlockOnce) {
  const std::vector<double> a(10);
  const std::vector<double> b(4);
  ByteTally tally;
  tally.AddVector(a);
  tally.AddVector(b);
  tally.AddVector(a);  // shared: not counted again
  tally.Add(nullptr, 100);
  EXPECT_EQ(tally.bytes(), a.capacity() * sizeof(double) + b.capacity() * sizeof(double));
  tally.AddVector(std::vector<int>{});  // no buffer
  EXPECT_EQ(tally.bytes(), (a.capacity() + b.capacity()) * sizeof(double));
}

}  // namespace
}  // namespace phdslam
