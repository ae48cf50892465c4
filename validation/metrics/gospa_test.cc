#include "validation/metrics/gospa.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "src/core/random.h"

namespace phdslam::validation {
namespace {

// GOSPA (alpha = 2) straight from its definition: the minimum over every partial assignment of
// sum d^p + c^p / 2 (|X| + |Y| - 2 |gamma|), with the raw (uncut) distance d.
struct BruteGospa {
  double value_p = std::numeric_limits<double>::infinity();
  double localisation = 0.0;
  std::vector<std::pair<int, int>> pairs;
};

BruteGospa BruteForceGospa(const std::vector<Vec2>& x, const std::vector<Vec2>& y, double c,
                           double p) {
  BruteGospa best;
  std::vector<int> match(x.size(), -1);
  std::vector<char> used(y.size(), 0);
  const auto recurse = [&](const auto& self, std::size_t i) -> void {
    if (i == x.size()) {
      double loc = 0.0;
      int n_pairs = 0;
      for (std::size_t a = 0; a < x.size(); ++a) {
        if (match[a] < 0) continue;
        loc += std::pow((x[a] - y[match[a]]).norm(), p);
        ++n_pairs;
      }
      const double total =
          loc + 0.5 * std::pow(c, p) * static_cast<double>(x.size() + y.size() - 2 * n_pairs);
      if (total < best.value_p) {
        best.value_p = total;
        best.localisation = loc;
        best.pairs.clear();
        for (std::size_t a = 0; a < x.size(); ++a) {
          if (match[a] >= 0) best.pairs.emplace_back(static_cast<int>(a), match[a]);
        }
      }
      return;
    }
    match[i] = -1;
    self(self, i + 1);
    for (std::size_t j = 0; j < y.size(); ++j) {
      if (used[j]) continue;
      used[j] = 1;
      match[i] = static_cast<int>(j);
      self(self, i + 1);
      used[j] = 0;
      match[i] = -1;
    }
  };
  recurse(recurse, 0);
  return best;
}

// OSPA from its definition: minimum over injections of the smaller set into the larger.
double BruteForceOspa(const std::vector<Vec2>& x, const std::vector<Vec2>& y, double c, double p) {
  const std::vector<Vec2>& small = x.size() <= y.size() ? x : y;
  const std::vector<Vec2>& large = x.size() <= y.size() ? y : x;
  const std::size_t n = large.size();
  if (n == 0) return 0.0;
  double best = std::numeric_limits<double>::infinity();
  std::vector<char> used(n, 0);
  const auto recurse = [&](const auto& self, std::size_t i, double sum) -> void {
    if (i == small.size()) {
      best = std::min(best, sum);
      return;
    }
    for (std::size_t j = 0; j < n; ++j) {
      if (used[j]) continue;
      used[j] = 1;
      self(self, i + 1, sum + std::pow(std::min((small[i] - large[j]).norm(), c), p));
      used[j] = 0;
    }
  };
  recurse(recurse, 0, 0.0);
  return std::pow((best + std::pow(c, p) * static_cast<double>(n - small.size())) / n, 1.0 / p);
}

std::vector<Vec2> RandomPoints(RandomStream& rng, int n, double extent) {
  std::vector<Vec2> points;
  for (int i = 0; i < n; ++i) points.emplace_back(rng.Uniform(0, extent), rng.Uniform(0, extent));
  return points;
}

TEST(Gospa, HandComputedMissedTarget) {
  const GospaResult r = Gospa({Vec2(0, 0), Vec2(10, 0)}, {Vec2(1, 0)}, 20.0, 2.0);
  EXPECT_NEAR(r.gospa, std::sqrt(1.0 + 200.0), 1e-12);
  EXPECT_DOUBLE_EQ(r.localisation, 1.0);
  EXPECT_DOUBLE_EQ(r.missed, 200.0);
  EXPECT_DOUBLE_EQ(r.false_, 0.0);
  EXPECT_EQ(r.n_missed, 1);
  EXPECT_EQ(r.n_false, 0);
  ASSERT_EQ(r.pairs.size(), 1u);
  EXPECT_EQ(r.pairs[0], std::make_pair(0, 0));
}

TEST(Gospa, HandComputedFalseAndFarPoints) {
  // (0,0)-(3,4) at d = 5 < c = 6 is a pair; (100,0) and (0,100) are farther than c apart, so they
  // count as one missed and one false point; (50,50) is a false estimate.
  const GospaResult r =
      Gospa({Vec2(0, 0), Vec2(100, 0)}, {Vec2(3, 4), Vec2(0, 100), Vec2(50, 50)}, 6.0, 1.0);
  EXPECT_DOUBLE_EQ(r.localisation, 5.0);
  EXPECT_EQ(r.n_missed, 1);
  EXPECT_EQ(r.n_false, 2);
  EXPECT_DOUBLE_EQ(r.missed, 3.0);
  EXPECT_DOUBLE_EQ(r.false_, 6.0);
  EXPECT_DOUBLE_EQ(r.gospa, 14.0);
}

TEST(Gospa, AssignmentIsSolvedOnCutOffDistances) {
  // On raw distances (0,0)-(-3.5,0) and (100,0)-(3,0) (3.5 + 97 = 100.5) beats (0,0)-(3,0) and
  // (100,0)-(-3.5,0) (3 + 103.5 = 106.5), but with the cut-off c = 5 the second is better:
  // 3 + 5 = 8 < 3.5 + 5.
  const GospaResult r = Gospa({Vec2(0, 0), Vec2(100, 0)}, {Vec2(3, 0), Vec2(-3.5, 0)}, 5.0, 1.0);
  EXPECT_DOUBLE_EQ(r.gospa, 8.0);
  ASSERT_EQ(r.pairs.size(), 1u);
  EXPECT_EQ(r.pairs[0], std::make_pair(0, 0));
  const OspaResult o = Ospa({Vec2(0, 0), Vec2(100, 0)}, {Vec2(3, 0), Vec2(-3.5, 0)}, 5.0, 1.0);
  EXPECT_DOUBLE_EQ(o.ospa, 4.0);
}

TEST(Gospa, EmptySets) {
  const GospaResult both = Gospa({}, {}, 20.0, 2.0);
  EXPECT_EQ(both.gospa, 0.0);
  EXPECT_TRUE(both.pairs.empty());
  const GospaResult no_estimate = Gospa({Vec2(1, 1), Vec2(2, 2), Vec2(3, 3)}, {}, 20.0, 2.0);
  EXPECT_NEAR(no_estimate.gospa, std::sqrt(3 * 200.0), 1e-12);
  EXPECT_EQ(no_estimate.n_missed, 3);
  const GospaResult no_truth = Gospa({}, {Vec2(1, 1)}, 20.0, 2.0);
  EXPECT_NEAR(no_truth.gospa, std::sqrt(200.0), 1e-12);
  EXPECT_EQ(no_truth.n_false, 1);
  EXPECT_DOUBLE_EQ(no_truth.false_, 200.0);

  EXPECT_EQ(Ospa({}, {}, 20.0, 2.0).ospa, 0.0);
  const OspaResult one_empty = Ospa({Vec2(1, 1)}, {}, 20.0, 2.0);
  EXPECT_DOUBLE_EQ(one_empty.ospa, 20.0);
  EXPECT_DOUBLE_EQ(one_empty.cardinality, 20.0);
  EXPECT_DOUBLE_EQ(one_empty.localisation, 0.0);
}

TEST(Gospa, RejectsBadParameters) {
  EXPECT_THROW(Gospa({}, {}, 0.0, 2.0), std::invalid_argument);
  EXPECT_THROW(Gospa({}, {}, 20.0, 0.5), std::invalid_argument);
  EXPECT_THROW(Ospa({}, {}, std::nan(""), 2.0), std::invalid_argument);
  EXPECT_THROW(Gospa({Vec2(std::nan(""), 0)}, {}, 20.0, 2.0), std::invalid_argument);
}

TEST(Gospa, MatchesBruteForceOnRandomSets) {
  int with_far_pairs = 0;
  for (int trial = 0; trial < 600; ++trial) {
    RandomStream rng(DeriveSeed(HashName("gospa_test"), trial));
    const int nx = static_cast<int>(rng.Uniform(0.0, 6.0));
    const int ny = static_cast<int>(rng.Uniform(0.0, 6.0));
    const std::vector<Vec2> x = RandomPoints(rng, nx, 30.0);
    const std::vector<Vec2> y = RandomPoints(rng, ny, 30.0);
    for (const double p : {1.0, 2.0}) {
      for (const double c : {3.0, 10.0, 20.0, 100.0}) {
        SCOPED_TRACE(::testing::Message() << "trial " << trial << " p " << p << " c " << c);
        const GospaResult r = Gospa(x, y, c, p);
        const BruteGospa expected = BruteForceGospa(x, y, c, p);
        const double scale = std::pow(c, p) * 10.0;
        EXPECT_NEAR(std::pow(r.gospa, p), expected.value_p, 1e-12 * scale);
        EXPECT_NEAR(r.localisation + r.missed + r.false_, std::pow(r.gospa, p), 1e-12 * scale);
        EXPECT_NEAR(r.localisation, expected.localisation, 1e-12 * scale);
        EXPECT_EQ(r.pairs, expected.pairs);
        EXPECT_EQ(r.n_missed, nx - static_cast<int>(r.pairs.size()));
        EXPECT_EQ(r.n_false, ny - static_cast<int>(r.pairs.size()));
        EXPECT_DOUBLE_EQ(r.missed, 0.5 * std::pow(c, p) * r.n_missed);
        EXPECT_DOUBLE_EQ(r.false_, 0.5 * std::pow(c, p) * r.n_false);
        if (std::min(nx, ny) > static_cast<int>(r.pairs.size())) ++with_far_pairs;

        const OspaResult o = Ospa(x, y, c, p);
        EXPECT_NEAR(o.ospa, BruteForceOspa(x, y, c, p), 1e-12 * c);
        EXPECT_NEAR(std::pow(o.localisation, p) + std::pow(o.cardinality, p), std::pow(o.ospa, p),
                    1e-12 * std::pow(c, p));
      }
    }
  }
  EXPECT_GT(with_far_pairs, 100);  // the sets exercise points farther than c apart
}

}  // namespace
}  // namespace phdslam::validation
