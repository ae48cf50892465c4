// Generator of new synthetic scenarios of the paper's kind (velocity motion model, range-bearing
// sensor, same measurement rules), for scaling and sensitivity studies.
//
// Trajectory: from initial_pose, the true control of step k (0-based, t_k = k dt) is
// [speed, omega(t_k)] with the smooth turn-rate profile
//   omega(t) = turn_amplitude * (0.5 sin(2 pi t / 400 s + 0.3) + 0.3 sin(2 pi t / 170 s + 1.9)
//                                + 0.2 sin(2 pi t / 1100 s + 4.1)),
// so |omega| <= turn_amplitude; the truth is the velocity motion model applied to these controls.
// The trajectory depends on the options only, not on the seed.
//
// Landmarks: `landmarks` points drawn uniformly over the corridor, the set of points within
// corridor_half_width of the true path (the polyline through the true positions). The corridor
// is rasterised on a square grid of cell corridor_half_width / 32 (coarser only for very long
// paths); a cell belongs to the corridor when its centre does, and landmarks are drawn by
// rejection from the corridor's bounding box, so their density is uniform over the rasterised
// corridor.
//
// Randomness: landmarks come from RandomStream(DeriveSeed(HashName("generated/landmarks"),
// seed)); scans and odometry from RandomStream(DeriveSeed(HashName("generated"), seed)), with the
// rules of SimulateRangeBearingSteps (range_bearing_simulator.h). Changing a sensor option thus
// leaves the map of a seed unchanged.
#pragma once

#include <cstdint>

#include "datasets/scenario.h"
#include "src/core/angles.h"
#include "src/core/types.h"

namespace phdslam::datasets {

struct GeneratorOptions {
  int steps = 1000;
  double dt = 1.0;                    ///< s
  double speed = 1.0;                 ///< m/s
  double turn_amplitude = 0.02;       ///< rad/s, bound of the sum-of-sines turn-rate profile
  int landmarks = 100;                ///< number of landmarks, scattered along the trajectory
  double corridor_half_width = 60.0;  ///< m, landmarks lie within this distance of the path
  double detection_probability = 0.95;
  double clutter_rate = 5.0;  ///< Poisson mean per scan, before pD thinning
  double fov_range = 150.0;   ///< m
  double fov_half_angle = DegToRad(90.0);
  double range_buffer = 10.0;  ///< m
  double angle_buffer = DegToRad(10.0);
  Mat2 measurement_noise_cov;  ///< default diag(0.8^2, (0.3 deg)^2), as in the paper
  Mat2 control_noise_cov;      ///< default diag(0.8^2, (0.5 deg)^2), as in the paper
  Pose initial_pose = Pose::Zero();

  GeneratorOptions();  ///< sets the matrix defaults
  /// Throws std::invalid_argument naming the field: steps >= 1; dt > 0; speed >= 0;
  /// turn_amplitude >= 0; landmarks >= 0; corridor_half_width > 0; initial_pose finite; and the
  /// sensor rules of SyntheticOptions::Validate.
  void Validate() const;
};

/// A scenario named "generated" with the given seed; deterministic in (options, seed).
/// Throws std::invalid_argument when the options are invalid.
Scenario GenerateScenario(const GeneratorOptions& options, std::uint64_t seed);

/// The first `simulated_steps` steps of GenerateScenario(options, seed): the same landmarks
/// (over the corridor of the whole options.steps path) and the same first scans, odometry and
/// true poses, without simulating the rest (for very long paths, e.g. the map scaling
/// benchmark). Throws std::invalid_argument when the options are invalid or simulated_steps is
/// not in [1, options.steps].
Scenario GenerateScenarioPrefix(const GeneratorOptions& options, std::uint64_t seed,
                                int simulated_steps);

/// Options (paper sensor, default speed and turn profile, `steps` steps) whose landmarks are
/// spread with a uniform density chosen so that on average about `landmarks_in_fov` of them lie
/// inside the field of view at every step. The corridor half-width is set to the FOV range, so
/// the whole FOV sector (area fov_half_angle * fov_range^2) always lies inside the corridor, and
/// the landmark count is round(landmarks_in_fov * corridor_area / sector_area), with the corridor
/// area measured on the same raster GenerateScenario uses. Throws std::invalid_argument when
/// landmarks_in_fov < 0 or steps < 1.
GeneratorOptions OptionsForLandmarksInView(int landmarks_in_fov, int steps);

}  // namespace phdslam::datasets
