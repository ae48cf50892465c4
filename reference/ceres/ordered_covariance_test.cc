#include "reference/ceres/ordered_covariance.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cstddef>
#include <random>
#include <vector>

namespace phdslam::reference {
namespace {

/// r = W (x_j - x_i - d): a whitened relative measurement between two 2-vectors.
struct RelativeCost {
  Eigen::Vector2d d;
  double w;
  template <typename T>
  bool operator()(const T* xi, const T* xj, T* r) const {
    for (int k = 0; k < 2; ++k) r[k] = T(w) * (xj[k] - xi[k] - T(d[k]));
    return true;
  }
  static ceres::CostFunction* Create(const Eigen::Vector2d& d, double w) {
    return new ceres::AutoDiffCostFunction<RelativeCost, 2, 2, 2>(new RelativeCost{d, w});
  }
};

/// r = W (x - a): a whitened prior on one 2-vector.
struct PriorCost {
  Eigen::Vector2d a;
  double w;
  template <typename T>
  bool operator()(const T* x, T* r) const {
    for (int k = 0; k < 2; ++k) r[k] = T(w) * (x[k] - T(a[k]));
    return true;
  }
  static ceres::CostFunction* Create(const Eigen::Vector2d& a, double w) {
    return new ceres::AutoDiffCostFunction<PriorCost, 2, 2>(new PriorCost{a, w});
  }
};

struct Edge {
  int i;
  int j;
  Eigen::Vector2d d;
  double w;
};

constexpr int kBlocks = 40;

std::vector<Edge> RandomEdges() {
  std::mt19937 rng(7);
  std::normal_distribution<double> n(0.0, 1.0);
  std::uniform_real_distribution<double> w(0.5, 3.0);
  std::uniform_int_distribution<int> pick(0, kBlocks - 1);
  std::vector<Edge> edges;
  for (int i = 0; i + 1 < kBlocks; ++i) edges.push_back({i, i + 1, {n(rng), n(rng)}, w(rng)});
  for (int e = 0; e < 30; ++e) {
    const int i = pick(rng);
    const int j = pick(rng);
    if (i != j) edges.push_back({i, j, {n(rng), n(rng)}, w(rng)});
  }
  return edges;
}

/// The same problem with block b at buffer_[slot(b)]: the blocks' addresses follow `slot`, the
/// order they are added to the problem does not.
struct Graph {
  std::vector<double> buffer = std::vector<double>(2 * kBlocks, 0.5);
  ceres::Problem problem;
  std::vector<double*> block;

  Graph(const std::vector<Edge>& edges, bool reversed_in_memory) {
    for (int b = 0; b < kBlocks; ++b) {
      const int slot = reversed_in_memory ? kBlocks - 1 - b : b;
      block.push_back(buffer.data() + 2 * static_cast<std::ptrdiff_t>(slot));
      problem.AddParameterBlock(block.back(), 2);
    }
    problem.AddResidualBlock(PriorCost::Create({0.0, 0.0}, 10.0), nullptr, block[0]);
    for (const Edge& e : edges) {
      problem.AddResidualBlock(RelativeCost::Create(e.d, e.w), nullptr, block[e.i], block[e.j]);
    }
  }
};

std::vector<Eigen::Matrix2d> Marginals(Graph& g) {
  ceres::Covariance::Options options;
  options.algorithm_type = ceres::SPARSE_QR;
  OrderedCovariance covariance(options);
  OrderedCovariance::BlockPairs pairs;
  for (const double* b : g.block) pairs.emplace_back(b, b);
  EXPECT_TRUE(covariance.Compute(pairs, &g.problem));
  std::vector<Eigen::Matrix2d> out;
  for (const double* b : g.block) {
    Eigen::Matrix<double, 2, 2, Eigen::RowMajor> c;
    EXPECT_TRUE(covariance.GetCovarianceBlock(b, b, c.data()));
    out.emplace_back(c);
  }
  return out;
}

/// (J^T J)^-1 of the linear problem, assembled densely.
Eigen::MatrixXd DenseCovariance(const std::vector<Edge>& edges) {
  Eigen::MatrixXd info = Eigen::MatrixXd::Zero(2 * kBlocks, 2 * kBlocks);
  info.block<2, 2>(0, 0) += 100.0 * Eigen::Matrix2d::Identity();
  for (const Edge& e : edges) {
    const double w2 = e.w * e.w;
    info.block<2, 2>(2 * e.i, 2 * e.i) += w2 * Eigen::Matrix2d::Identity();
    info.block<2, 2>(2 * e.j, 2 * e.j) += w2 * Eigen::Matrix2d::Identity();
    info.block<2, 2>(2 * e.i, 2 * e.j) -= w2 * Eigen::Matrix2d::Identity();
    info.block<2, 2>(2 * e.j, 2 * e.i) -= w2 * Eigen::Matrix2d::Identity();
  }
  return info.inverse();
}

TEST(OrderedCovariance, EqualProblemsGiveIdenticalCovariancesWhereverTheirBlocksLie) {
  const std::vector<Edge> edges = RandomEdges();
  Graph forward(edges, false);
  Graph reversed(edges, true);
  const std::vector<Eigen::Matrix2d> a = Marginals(forward);
  const std::vector<Eigen::Matrix2d> b = Marginals(reversed);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    for (int r = 0; r < 2; ++r) {
      for (int c = 0; c < 2; ++c) EXPECT_EQ(a[k](r, c), b[k](r, c)) << "block " << k;
    }
  }
}

TEST(OrderedCovariance, EqualsTheInverseInformationOfALinearProblem) {
  const std::vector<Edge> edges = RandomEdges();
  Graph g(edges, true);
  const std::vector<Eigen::Matrix2d> marginals = Marginals(g);
  const Eigen::MatrixXd dense = DenseCovariance(edges);
  for (int k = 0; k < kBlocks; ++k) {
    const Eigen::Matrix2d expected = dense.block<2, 2>(2 * k, 2 * k);
    EXPECT_LT((marginals[static_cast<std::size_t>(k)] - expected).norm(), 1e-9 * expected.norm())
        << "block " << k;
  }
}

TEST(OrderedCovariance, ABlockNotInTheProblemIsRefused) {
  const std::vector<Edge> edges = RandomEdges();
  Graph g(edges, false);
  ceres::Covariance::Options options;
  OrderedCovariance covariance(options);
  const double outside[2] = {0.0, 0.0};
  EXPECT_FALSE(covariance.Compute({{outside, outside}}, &g.problem));
  EXPECT_FALSE(covariance.GetCovarianceBlock(outside, outside, nullptr));
}

}  // namespace
}  // namespace phdslam::reference
