#include "validation/runner/execution/seed_scenarios.h"

#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace phdslam::validation {
namespace {

/// A scenario function that counts its calls and names each scenario after its seed.
struct CountingMake {
  std::shared_ptr<std::atomic<int>> calls = std::make_shared<std::atomic<int>>(0);
  datasets::Scenario operator()(std::uint64_t seed) const {
    ++*calls;
    if (seed == 99) throw std::runtime_error("no scenario for seed 99");
    datasets::Scenario s;
    s.name = "seed-" + std::to_string(seed);
    s.seed = seed;
    return s;
  }
};

TEST(SeedScenarios, MakesEachSeedOnceWhileItIsKept) {
  const CountingMake make;
  SeedScenarios cache(make, 2);
  const auto a = cache.Get(1);
  EXPECT_EQ(cache.Get(1), a);  // the same object, not made again
  EXPECT_EQ(a->name, "seed-1");
  EXPECT_EQ(cache.Get(2)->name, "seed-2");
  EXPECT_EQ(*make.calls, 2);
  EXPECT_EQ(cache.Get(3)->name, "seed-3");  // seed 1 leaves
  EXPECT_EQ(cache.Get(2)->name, "seed-2");
  EXPECT_EQ(*make.calls, 3);
  EXPECT_EQ(cache.Get(1)->name, "seed-1");  // made again
  EXPECT_EQ(*make.calls, 4);
  EXPECT_EQ(a->name, "seed-1");  // an evicted scenario lives on while held
}

TEST(SeedScenarios, PassesOnAFailureAndKeepsNothingForIt) {
  const CountingMake make;
  SeedScenarios cache(make, 2);
  EXPECT_THROW(cache.Get(99), std::runtime_error);
  EXPECT_THROW(cache.Get(99), std::runtime_error);
  EXPECT_EQ(*make.calls, 2);
  EXPECT_EQ(cache.Get(4)->seed, 4U);
}

TEST(SeedScenarios, GivesEveryThreadTheScenarioOfItsSeed) {
  const CountingMake make;
  SeedScenarios cache(make, 3);
  std::atomic<int> wrong{0};
  std::vector<std::thread> threads;
  threads.reserve(4);
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&cache, &wrong, t] {
      for (std::uint64_t seed = 1; seed <= 50; ++seed) {
        const std::uint64_t asked = seed + static_cast<std::uint64_t>(t % 2);
        if (cache.Get(asked)->seed != asked) ++wrong;
      }
    });
  }
  for (std::thread& thread : threads) thread.join();
  EXPECT_EQ(wrong, 0);
  EXPECT_GE(*make.calls, 51);
}

TEST(SeedScenarios, RejectsNonsense) {
  EXPECT_THROW(SeedScenarios(SeedScenarios::Make(), 2), std::invalid_argument);
  EXPECT_THROW(SeedScenarios(CountingMake(), 0), std::invalid_argument);
}

}  // namespace
}  // namespace phdslam::validation
