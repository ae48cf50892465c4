#include "datasets/simulation_limits.h"

#include <array>
#include <charconv>
#include <cmath>
#include <stdexcept>

namespace phdslam::datasets {

std::string CompactNumber(double v) {
  if (std::isfinite(v) && v == std::floor(v) && std::abs(v) <= 1e15) {
    return std::to_string(static_cast<long long>(v));
  }
  std::array<char, 32> buffer{};
  const auto result =
      std::to_chars(buffer.data(), buffer.data() + buffer.size(), v, std::chars_format::general, 6);
  return {buffer.data(), result.ptr};
}

void CheckSimulationSize(std::string_view owner, double steps, double landmarks,
                         double clutter_rate) {
  const auto fail = [owner](const std::string& what) {
    throw std::invalid_argument(std::string(owner) + ": " + what +
                                " (a usage limit of the simulator: split the study into smaller "
                                "scenarios)");
  };
  if (steps > kMaxSimulatedSteps) {
    fail("steps " + CompactNumber(steps) + " exceeds the cap of " +
         CompactNumber(kMaxSimulatedSteps));
  }
  if (landmarks > kMaxSimulatedLandmarks) {
    fail("landmarks " + CompactNumber(landmarks) + " exceeds the cap of " +
         CompactNumber(kMaxSimulatedLandmarks));
  }
  if (steps * clutter_rate > kMaxSimulatedClutter) {
    fail("steps x clutter_rate = " + CompactNumber(steps * clutter_rate) +
         " expected clutter points exceeds the cap of " + CompactNumber(kMaxSimulatedClutter));
  }
  if (steps * landmarks > kMaxVisibilityTests) {
    fail("steps x landmarks = " + CompactNumber(steps * landmarks) + " exceeds the cap of " +
         CompactNumber(kMaxVisibilityTests));
  }
}

}  // namespace phdslam::datasets
