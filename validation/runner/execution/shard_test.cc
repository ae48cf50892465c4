#include "validation/runner/execution/shard.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace phdslam::validation {
namespace {

TEST(ParseShard, ReadsIOfN) {
  const Shard s = ParseShard("2/3");
  EXPECT_EQ(s.index, 2);
  EXPECT_EQ(s.count, 3);
  EXPECT_EQ(s.ToString(), "2/3");
  EXPECT_FALSE(s.IsWhole());
  EXPECT_TRUE(ParseShard("1/1").IsWhole());
}

TEST(ParseShard, RejectsBadText) {
  for (const char* text :
       {"", "2", "0/3", "4/3", "1/0", "-1/3", "1/-3", "a/3", "1/3x", "1//3", "+1/3", "1/2000000"}) {
    EXPECT_THROW(ParseShard(text), std::invalid_argument) << text;
  }
}

TEST(Shard, EveryJobBelongsToExactlyOneShard) {
  for (int n = 1; n <= 4; ++n) {
    for (std::size_t job = 0; job < 20; ++job) {
      int owners = 0;
      for (int i = 1; i <= n; ++i) owners += Shard{i, n}.Contains(job) ? 1 : 0;
      EXPECT_EQ(owners, 1) << job << " of " << n;
    }
  }
  // Job j goes to shard (j mod n) + 1.
  EXPECT_TRUE((Shard{1, 3}.Contains(0)));
  EXPECT_TRUE((Shard{2, 3}.Contains(1)));
  EXPECT_TRUE((Shard{3, 3}.Contains(5)));
  EXPECT_TRUE((Shard{1, 3}.Contains(6)));
}

}  // namespace
}  // namespace phdslam::validation
