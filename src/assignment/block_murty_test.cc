#include "src/assignment/block_murty.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "src/assignment/murty.h"
#include "src/core/random.h"

namespace phdslam::assignment {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// A PHD-SLAM-shaped matrix: r rows, m measurement columns with sparse gating, then r miss slots.
Eigen::MatrixXd GatedMatrix(RandomStream& rng, int r, int m, double gate_prob, bool integer) {
  Eigen::MatrixXd c = Eigen::MatrixXd::Constant(r, m + r, kInf);
  for (int i = 0; i < r; ++i) {
    for (int j = 0; j < m; ++j) {
      if (rng.Uniform() < gate_prob) {
        c(i, j) = integer ? std::floor(rng.Uniform(0.0, 6.0)) : rng.Uniform(-3.0, 5.0);
      }
    }
    c(i, m + i) = integer ? std::floor(rng.Uniform(0.0, 6.0)) : rng.Uniform(-1.0, 4.0);
  }
  return c;
}

TEST(BlockMurtyKBest, MatchesMonolithicMurtyOnSparseMatrices) {
  RandomStream rng(2024);
  int compared = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const int r = 1 + static_cast<int>(rng.Uniform() * 7);
    const int m = static_cast<int>(rng.Uniform() * 8);
    const bool integer = trial % 3 == 0;
    const Eigen::MatrixXd c = GatedMatrix(rng, r, m, 0.25, integer);
    const int k = 1 + static_cast<int>(rng.Uniform() * 60);
    const double gap = trial % 2 == 0 ? 6.9078 : kInf;
    const auto mono = MurtyKBest(c, k, gap);
    const auto block = BlockMurtyKBest(c, k, gap);
    ASSERT_EQ(block.size(), mono.size()) << "trial " << trial;
    for (std::size_t h = 0; h < mono.size(); ++h) {
      ASSERT_NEAR(block[h].cost, mono[h].cost, 1e-9) << "trial " << trial << " h " << h;
      double sum = 0.0;
      std::vector<bool> used(c.cols(), false);
      for (int i = 0; i < r; ++i) {
        const int col = block[h].row_to_col[i];
        ASSERT_TRUE(std::isfinite(c(i, col)));
        ASSERT_FALSE(used[col]);
        used[col] = true;
        sum += c(i, col);
      }
      ASSERT_NEAR(sum, block[h].cost, 1e-9);
    }
    // No duplicates.
    for (std::size_t a = 0; a < block.size(); ++a) {
      for (std::size_t b = a + 1; b < block.size(); ++b) {
        ASSERT_NE(block[a].row_to_col, block[b].row_to_col) << "trial " << trial;
      }
    }
    ++compared;
  }
  EXPECT_EQ(compared, 3000);
}

TEST(BlockMurtyKBest, IndependentSingletonsCombineExactly) {
  // Two independent rows, each: detect (cost 0) or miss (cost 1 / 3).
  Eigen::MatrixXd c = Eigen::MatrixXd::Constant(2, 4, kInf);
  c(0, 0) = 0.0;
  c(0, 2) = 1.0;
  c(1, 1) = 0.0;
  c(1, 3) = 3.0;
  const auto all = BlockMurtyKBest(c, 10, kInf);
  ASSERT_EQ(all.size(), 4u);
  EXPECT_EQ(all[0].cost, 0.0);
  EXPECT_EQ(all[1].cost, 1.0);
  EXPECT_EQ(all[2].cost, 3.0);
  EXPECT_EQ(all[3].cost, 4.0);
  EXPECT_EQ(all[1].row_to_col, (std::vector<int>{2, 1}));
  const auto gapped = BlockMurtyKBest(c, 10, 2.0);
  EXPECT_EQ(gapped.size(), 2u);
  EXPECT_EQ(BlockMurtyKBest(c, 3, kInf).size(), 3u);
}

}  // namespace
}  // namespace phdslam::assignment
