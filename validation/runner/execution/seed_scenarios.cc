#include "validation/runner/execution/seed_scenarios.h"

#include <algorithm>
#include <stdexcept>

namespace phdslam::validation {

SeedScenarios::SeedScenarios(Make make, std::size_t capacity)
    : make_(std::move(make)), capacity_(capacity) {
  if (!make_) throw std::invalid_argument("SeedScenarios: no scenario function");
  if (capacity_ == 0) throw std::invalid_argument("SeedScenarios: capacity must be >= 1");
}

std::shared_ptr<const datasets::Scenario> SeedScenarios::Get(std::uint64_t seed) {
  const auto held = [&]() -> std::shared_ptr<const datasets::Scenario> {
    const auto it = std::find_if(kept_.begin(), kept_.end(),
                                 [seed](const auto& entry) { return entry.first == seed; });
    return it == kept_.end() ? nullptr : it->second;
  };
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (auto scenario = held()) return scenario;
  }
  // Made outside the lock, so that the other workers' runs go on meanwhile.
  auto made = std::make_shared<const datasets::Scenario>(make_(seed));
  const std::lock_guard<std::mutex> lock(mutex_);
  if (auto scenario = held()) return scenario;  // another thread made it meanwhile
  kept_.emplace_back(seed, made);
  if (kept_.size() > capacity_) kept_.pop_front();
  return made;
}

}  // namespace phdslam::validation
