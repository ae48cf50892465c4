// The scenarios of the Monte Carlo runs, made once per seed: every estimator and particle count
// of one seed runs on one scenario, which is a function of the seed alone.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <utility>

#include "datasets/scenario.h"

namespace phdslam::validation {

/// The last `capacity` scenarios made, by seed. Get() is safe to call from several threads; a
/// scenario two threads ask for at once may be made twice (the same value: making a scenario is
/// deterministic in its seed), which costs time and never changes a result. An evicted scenario
/// lives on while a run still holds it.
class SeedScenarios {
 public:
  using Make = std::function<datasets::Scenario(std::uint64_t)>;

  SeedScenarios(Make make, std::size_t capacity);

  /// The scenario of `seed`, made now (and kept) unless it is kept; what `make` throws goes to
  /// the caller, and nothing is kept for that seed.
  std::shared_ptr<const datasets::Scenario> Get(std::uint64_t seed);

 private:
  Make make_;
  std::size_t capacity_;
  std::mutex mutex_;  // guards kept_
  std::deque<std::pair<std::uint64_t, std::shared_ptr<const datasets::Scenario>>> kept_;
};

}  // namespace phdslam::validation
