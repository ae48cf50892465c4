#include "src/core/keyed_stream.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

namespace phdslam {
namespace {

TEST(KeyedStream, TheDrawsOfATagDependOnTheTagAlone) {
  // The same tag gives the same numbers however many numbers other tags drew before it.
  KeyedStream first = DrawKeyStream(42, 7, 3, DrawPurpose::kPose);
  for (int i = 0; i < 100; ++i) DrawKeyStream(42, 6, i, DrawPurpose::kResample).Uniform();
  KeyedStream again = DrawKeyStream(42, 7, 3, DrawPurpose::kPose);
  for (int i = 0; i < 6; ++i) EXPECT_EQ(first.Normal(), again.Normal());
}

TEST(KeyedStream, DifferentTagsAndSeedsGiveDifferentNumbers) {
  std::set<double> seen;
  for (std::uint64_t seed : {1ULL, 2ULL}) {
    for (int step = 0; step < 5; ++step) {
      for (int particle = 0; particle < 5; ++particle) {
        for (DrawPurpose p :
             {DrawPurpose::kComponent, DrawPurpose::kPose, DrawPurpose::kResample}) {
          seen.insert(DrawKeyStream(seed, step, particle, p).Uniform());
        }
      }
    }
  }
  EXPECT_EQ(seen.size(), 2U * 5U * 5U * 3U);
}

TEST(KeyedStream, UniformsAndNormalsHaveTheirMoments) {
  double sum = 0.0;
  double sum_normal = 0.0;
  double sum_normal2 = 0.0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    KeyedStream s = DrawKeyStream(9, i, 0, DrawPurpose::kComponent);
    const double u = s.Uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum += u;
    const double z = s.Normal();
    sum_normal += z;
    sum_normal2 += z * z;
  }
  EXPECT_NEAR(sum / n, 0.5, 0.01);
  EXPECT_NEAR(sum_normal / n, 0.0, 0.03);
  EXPECT_NEAR(sum_normal2 / n, 1.0, 0.04);
}

}  // namespace
}  // namespace phdslam
