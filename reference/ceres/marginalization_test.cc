#include "reference/ceres/marginalization.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <memory>
#include <vector>

#include "reference/ceres/linear_prior.h"
#include "src/core/types.h"

namespace phdslam::reference {
namespace {

/// A linear Gaussian factor r = W (sum_i A_i x_i - z) on 2-D blocks.
class LinearFactor final : public ceres::CostFunction {
 public:
  LinearFactor(std::vector<Mat2> a, const Vec2& z, const Mat2& w) : a_(std::move(a)), z_(z), w_(w) {
    for (std::size_t i = 0; i < a_.size(); ++i) mutable_parameter_block_sizes()->push_back(2);
    set_num_residuals(2);
  }
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    Vec2 e = -z_;
    for (std::size_t i = 0; i < a_.size(); ++i) e += a_[i] * Eigen::Map<const Vec2>(parameters[i]);
    Eigen::Map<Vec2> r(residuals);
    r = w_ * e;
    if (jacobians == nullptr) return true;
    for (std::size_t i = 0; i < a_.size(); ++i) {
      if (jacobians[i] == nullptr) continue;
      Eigen::Map<Eigen::Matrix<double, 2, 2, Eigen::RowMajor>> j(jacobians[i]);
      j = w_ * a_[i];
    }
    return true;
  }

 private:
  std::vector<Mat2> a_;
  Vec2 z_;
  Mat2 w_;
};

GraphFactor Factor(std::vector<Mat2> a, const Vec2& z, const Mat2& w, std::vector<double*> blocks) {
  return {std::make_shared<LinearFactor>(std::move(a), z, w), nullptr, std::move(blocks)};
}

/// The solution and covariance of a linear least-squares problem, linearised at the current
/// values of `order`.
struct Solution {
  Eigen::VectorXd x;
  Eigen::MatrixXd cov;
};

Solution SolveLinear(const std::vector<const GraphFactor*>& factors,
                     const std::vector<double*>& order) {
  const DenseSystem s = Linearize(factors, order, {});
  Eigen::VectorXd x0(s.g.size());
  for (std::size_t i = 0; i < order.size(); ++i) {
    x0.segment(s.offsets[i], s.sizes[i]) = Eigen::Map<const Eigen::VectorXd>(order[i], s.sizes[i]);
  }
  const Eigen::LLT<Eigen::MatrixXd> llt(s.h);
  return {x0 - llt.solve(s.g), llt.solve(Eigen::MatrixXd::Identity(s.h.rows(), s.h.cols()))};
}

// A chain x_0 .. x_5 (2-D): a prior on x_0, relative measurements x_{k+1} - x_k, absolute
// measurements of x_1, x_3 and x_5, a coupling measurement of x_1 + 2 x_4 (a loop closure that
// spans the marginalised part), each with its own correlated noise.
class LinearChain : public ::testing::Test {
 protected:
  LinearChain() {
    for (int k = 0; k < 6; ++k) x_[k] = Vec2(0.3 * k - 1.0, 0.1 * k * k);  // arbitrary values
    const Mat2 i = Mat2::Identity();
    Mat2 w1;
    w1 << 2.0, 0.0, 0.5, 1.5;
    Mat2 w2;
    w2 << 0.7, 0.2, 0.0, 3.0;
    factors_.push_back(Factor({i}, Vec2(0.1, -0.2), 1.3 * i, {x_[0].data()}));
    for (int k = 0; k < 5; ++k) {
      factors_.push_back(Factor({-i, i}, Vec2(1.0 + 0.1 * k, 0.5 - 0.2 * k), k % 2 ? w1 : w2,
                                {x_[k].data(), x_[k + 1].data()}));
    }
    factors_.push_back(Factor({i}, Vec2(1.2, 0.4), w1, {x_[1].data()}));
    factors_.push_back(Factor({i}, Vec2(3.1, -0.6), w2, {x_[3].data()}));
    factors_.push_back(Factor({i}, Vec2(5.2, -1.6), w1, {x_[5].data()}));
    Mat2 a;
    a << 1.0, 0.3, -0.2, 1.0;
    factors_.push_back(Factor({a, 2.0 * i}, Vec2(9.0, -2.0), w2, {x_[1].data(), x_[4].data()}));
  }

  std::vector<const GraphFactor*> Touching(const std::vector<double*>& blocks, bool touching) {
    std::vector<const GraphFactor*> out;
    for (const GraphFactor& f : factors_) {
      bool t = false;
      for (double* b : f.blocks) {
        t = t || std::find(blocks.begin(), blocks.end(), b) != blocks.end();
      }
      if (t == touching) out.push_back(&f);
    }
    return out;
  }

  Vec2 x_[6];
  std::vector<GraphFactor> factors_;
};

TEST_F(LinearChain, MarginalisedPriorGivesTheBatchSolutionAndMarginal) {
  std::vector<const GraphFactor*> all;
  for (const GraphFactor& f : factors_) all.push_back(&f);
  const std::vector<double*> kept = {x_[2].data(), x_[3].data(), x_[4].data(), x_[5].data()};
  std::vector<double*> order = {x_[0].data(), x_[1].data()};
  order.insert(order.end(), kept.begin(), kept.end());
  const Solution batch = SolveLinear(all, order);

  // Linearisation points away from the current values: the factors are linear, so the prior
  // must not depend on them.
  FixedPoints fixed;
  fixed[x_[4].data()] = Eigen::Vector2d(7.0, -3.0);
  const std::vector<double*> gone = {x_[0].data(), x_[1].data()};
  const LinearPrior prior = Marginalize(Touching(gone, true), gone, {}, fixed);
  ASSERT_EQ(prior.blocks.size(), 2u);  // x_2 (relative measurement) and x_4 (loop closure)
  EXPECT_GE(prior.IndexOf(x_[2].data()), 0);
  EXPECT_GE(prior.IndexOf(x_[4].data()), 0);
  EXPECT_EQ(prior.IndexOf(x_[0].data()), -1);
  EXPECT_TRUE(
      prior.linearization_points[static_cast<std::size_t>(prior.IndexOf(x_[4].data()))].isApprox(
          Eigen::Vector2d(7.0, -3.0)));

  GraphFactor prior_factor{std::shared_ptr<ceres::CostFunction>(LinearPriorFactor::Create(prior)),
                           nullptr, prior.blocks};
  std::vector<const GraphFactor*> reduced = Touching(gone, false);
  reduced.push_back(&prior_factor);
  const Solution window = SolveLinear(reduced, kept);
  EXPECT_TRUE(window.x.isApprox(batch.x.tail(8), 1e-10)) << window.x.transpose() << "\n"
                                                         << batch.x.tail(8).transpose();
  EXPECT_TRUE(window.cov.isApprox(batch.cov.bottomRightCorner(8, 8), 1e-10))
      << window.cov << "\n\n"
      << batch.cov.bottomRightCorner(8, 8);
}

TEST_F(LinearChain, MarginalCovariancesAreTheBlocksOfTheInverse) {
  std::vector<const GraphFactor*> all;
  for (const GraphFactor& f : factors_) all.push_back(&f);
  std::vector<double*> order;
  for (Vec2& x : x_) order.push_back(x.data());
  const Solution batch = SolveLinear(all, order);
  const std::vector<Eigen::MatrixXd> covs =
      MarginalCovariances(all, {}, {x_[1].data(), x_[4].data()});
  ASSERT_EQ(covs.size(), 2u);
  EXPECT_TRUE(covs[0].isApprox(batch.cov.block(2, 2, 2, 2), 1e-10));
  EXPECT_TRUE(covs[1].isApprox(batch.cov.block(8, 8, 2, 2), 1e-10));
  // A constant block is not estimated: holding x_0 removes its uncertainty from x_1's.
  const std::vector<Eigen::MatrixXd> fixed0 =
      MarginalCovariances(all, {x_[0].data()}, {x_[1].data()});
  ASSERT_EQ(fixed0.size(), 1u);
  EXPECT_LT(fixed0[0].trace(), covs[0].trace());
}

TEST_F(LinearChain, AnchoredCovariancesAreTheBlocksOfTheInverseWithTheAnchor) {
  std::vector<const GraphFactor*> all;
  for (const GraphFactor& f : factors_) all.push_back(&f);
  std::vector<double*> order;
  for (Vec2& x : x_) order.push_back(x.data());
  const Solution batch = SolveLinear(all, order);
  const AnchoredCovariances c =
      AnchoredMarginalCovariances(all, {}, x_[4].data(), {x_[1].data(), x_[3].data()});
  ASSERT_EQ(c.marginal.size(), 2u);
  ASSERT_EQ(c.cross.size(), 2u);
  EXPECT_TRUE(c.anchor.isApprox(batch.cov.block(8, 8, 2, 2), 1e-10));
  EXPECT_TRUE(c.marginal[0].isApprox(batch.cov.block(2, 2, 2, 2), 1e-10));
  EXPECT_TRUE(c.marginal[1].isApprox(batch.cov.block(6, 6, 2, 2), 1e-10));
  EXPECT_TRUE(c.cross[0].isApprox(batch.cov.block(2, 8, 2, 2), 1e-10));
  EXPECT_TRUE(c.cross[1].isApprox(batch.cov.block(6, 8, 2, 2), 1e-10));
  // Neighbours on the chain are correlated.
  EXPECT_GT(c.cross[1].norm(), 1e-6);
  // An anchor outside the problem gives nothing.
  Vec2 outside = Vec2::Zero();
  EXPECT_TRUE(AnchoredMarginalCovariances(all, {}, outside.data(), {x_[1].data()}).cross.empty());
}

TEST(GaussianPrior, WhitensTheCovariance) {
  Vec2 m(1.0, 2.0);
  Mat2 cov;
  cov << 4.0, 1.0, 1.0, 2.0;
  const LinearPrior p = GaussianPrior(m.data(), m, cov);
  EXPECT_TRUE((p.a.transpose() * p.a).isApprox(Mat2(cov.inverse()), 1e-12));
  Mat2 bad;
  bad << 1.0, 2.0, 2.0, 1.0;
  EXPECT_THROW(GaussianPrior(m.data(), m, bad), std::invalid_argument);
}

}  // namespace
}  // namespace phdslam::reference
