#include "src/filters/resampling.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace phdslam::filters {
namespace {

TEST(StratifiedResample, HandComputedCounts) {
  // N w = [2, 1, 1, 0]: whole copies only.
  EXPECT_EQ(StratifiedResample(std::vector<double>{0.5, 0.25, 0.25, 0.0},
                               std::vector<double>{0.1, 0.2, 0.3, 0.4}),
            (std::vector<int>{0, 0, 1, 2}));
  // N w = [0.9, 0.9, 1.2], r = [0.5, 0.95, 0.1]:
  // i=0: c=0.9 >= r0 -> emit 0, c=-0.1; i=1: c=0.8 < r1; i=2: c=2.0 -> emit 2, 2.
  EXPECT_EQ(
      StratifiedResample(std::vector<double>{0.3, 0.3, 0.4}, std::vector<double>{0.5, 0.95, 0.1}),
      (std::vector<int>{0, 2, 2}));
  // Same weights, r = [0.95, 0.5, 0.1]: i=0: c=0.9 < r0; i=1: c=1.8 -> emit 1, c=0.8 >= r1 ->
  // emit 1, c=-0.2; i=2: c=1.0 -> emit 2.
  EXPECT_EQ(
      StratifiedResample(std::vector<double>{0.3, 0.3, 0.4}, std::vector<double>{0.95, 0.5, 0.1}),
      (std::vector<int>{1, 1, 2}));
}

TEST(StratifiedResample, IsUnbiasedAndSorted) {
  const std::vector<double> w = {0.05, 0.4, 0.15, 0.3, 0.1};
  const int n = static_cast<int>(w.size());
  RandomStream rng(11);
  std::vector<double> counts(n, 0.0);
  const int trials = 100000;
  std::vector<double> u(n);
  for (int t = 0; t < trials; ++t) {
    for (double& x : u) x = rng.Uniform();
    const auto idx = StratifiedResample(w, u);
    ASSERT_EQ(static_cast<int>(idx.size()), n);
    for (int k = 1; k < n; ++k) ASSERT_LE(idx[k - 1], idx[k]);
    for (int i : idx) counts[i] += 1.0;
  }
  for (int i = 0; i < n; ++i) EXPECT_NEAR(counts[i] / trials, n * w[i], 0.01) << i;
}

TEST(EffectiveSampleSize, UniformAndDegenerate) {
  EXPECT_NEAR(EffectiveSampleSize(std::vector<double>{0.25, 0.25, 0.25, 0.25}), 4.0, 1e-12);
  EXPECT_NEAR(EffectiveSampleSize(std::vector<double>{1.0, 0.0, 0.0}), 1.0, 1e-12);
  const auto w = NormalisedWeights(std::vector<double>{-1000.0, -1000.0 + std::log(3.0)});
  EXPECT_NEAR(w[0], 0.25, 1e-12);
  EXPECT_NEAR(w[1], 0.75, 1e-12);
}

}  // namespace
}  // namespace phdslam::filters
