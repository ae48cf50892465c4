// The largest simulated scenarios the generators build, and the physical ranges of their options.
// A request beyond one of these is refused with a usage error naming the option and the cap
// before anything is allocated; the caps are far above every scenario of the paper and of the
// benchmarks (the map-scaling benchmark's 10^5 landmarks over a few hundred steps).
#pragma once

#include <string>
#include <string_view>

namespace phdslam::datasets {

inline constexpr int kMaxSimulatedSteps = 1'000'000;  ///< steps of one simulated scenario
/// Landmarks of one simulated map. The map metrics match the estimate against the true map (a
/// cost matrix of true x estimated landmarks): 10^5 landmarks already run out of memory on a
/// 20-step run of dead reckoning, 10^4 take well under a GB.
inline constexpr int kMaxSimulatedLandmarks = 10'000;
/// Largest steps x clutter_rate: the expected clutter points of one scenario.
inline constexpr double kMaxSimulatedClutter = 5e7;
/// Largest number of measurements one simulated scenario holds (landmarks in view and clutter
/// over all steps, about 40 bytes each); the simulator stops with a usage error beyond it.
inline constexpr double kMaxSimulatedMeasurements = 5e7;
/// Largest steps x landmarks: the landmark visibility tests of one scenario (time, not memory).
inline constexpr double kMaxVisibilityTests = 1e11;

inline constexpr double kMaxTimeStep = 60.0;  ///< s, dt of a simulated step
inline constexpr double kMaxSpeed = 100.0;    ///< m/s
inline constexpr double kMaxTurnRate = 10.0;  ///< rad/s
inline constexpr double kMaxDistance = 1e5;   ///< m: ranges, radii, widths, offsets, buffers
/// m: the narrowest corridor of generated landmarks; the corridor is rasterised in cells of a
/// 32nd of its half width, and a width far below any vehicle's made the raster overflow.
inline constexpr double kMinCorridorHalfWidth = 0.1;
inline constexpr double kMaxCoordinate = 1e7;  ///< m: |x|, |y| of an initial pose
inline constexpr double kMaxVariance = 1e6;    ///< (m or rad)^2: a noise covariance entry

/// A number as a short text: integers up to 10^15 in full, anything else in "%.6g" form (so a
/// 300-digit value prints as 1e+300).
std::string CompactNumber(double v);

/// Throws std::invalid_argument naming `owner` and the option when steps > kMaxSimulatedSteps,
/// landmarks > kMaxSimulatedLandmarks, steps * clutter_rate > kMaxSimulatedClutter or
/// steps * landmarks > kMaxVisibilityTests; each message gives the cap.
void CheckSimulationSize(std::string_view owner, double steps, double landmarks,
                         double clutter_rate);

}  // namespace phdslam::datasets
