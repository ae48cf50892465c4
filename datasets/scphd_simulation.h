// The simulation of single-cluster PHD SLAM's paper (Lee, Clark & Salvi, ICRA 2012, section V)
// as far as the paper states it, scenario "scphd-sim":
//  - stated: an Ackermann-steered vehicle (control [speed, steering angle]), odometry noise
//    sigma 2 m/s in speed and 5 deg in steering, range-bearing measurement noise 1 m and 2 deg,
//    pD 0.95, Poisson clutter with mean 5 per scan, a fixed map and trajectory with the odometry
//    and the measurements drawn anew for every Monte Carlo run;
//  - chosen here (the paper leaves them open), each an option below:
//    * vehicle model: the kinematic Ackermann (bicycle) model, Euler-integrated, i.e.
//      models::CarMotionModel with wheelbase 2.83 m and no encoder or laser offsets;
//    * path: constant speed 3 m/s and the constant steering angle whose Euler steps are chords
//      of a circle of radius 40 m (heading change 2 asin(v dt / 2R) per step, steering
//      atan(L * that / (v dt)), about 4.1 deg), driven counter-clockwise from (40, 0), the first
//      heading north plus half a step's turn, so every true pose lies on the circle; two laps
//      (838 steps of dt = 0.2 s, 502.8 m; 0.2 s is the observation interval of the common
//      Ackermann SLAM simulator of Bailey et al., with one odometry reading per scan);
//    * map: 60 landmarks uniform over the annulus 20 m <= r <= 60 m around the circle's centre,
//      drawn once from the fixed stream "scphd-sim/map" (the same map for every seed);
//    * field of view: range 30 m, half-angle 90 deg (the half-plane ahead), so about 7 landmarks
//      are in view; the filters' active-set buffers 10 m and 10 deg (the PHD-SLAM paper's);
//    * clutter: uniform in (range, bearing) over the field of view, thinned by pD, as in every
//      simulated scenario of the suite (range_bearing_simulator.h).
// Randomness: scans and odometry from RandomStream(DeriveSeed(HashName("scphd-sim"), seed)) with
// the rules of SimulateRangeBearingSteps.
#pragma once

#include <cstdint>

#include "datasets/scenario.h"
#include "src/core/angles.h"
#include "src/core/types.h"

namespace phdslam::datasets {

struct ScPhdSimOptions {
  int steps = 838;
  double dt = 0.2;              ///< s, one control and one scan per step
  double speed = 3.0;           ///< m/s
  double circle_radius = 40.0;  ///< m, radius of the driven circle
  double wheelbase = 2.83;      ///< m
  int landmarks = 60;
  double map_inner_radius = 20.0;  ///< m
  double map_outer_radius = 60.0;  ///< m
  double detection_probability = 0.95;
  double clutter_rate = 5.0;  ///< Poisson mean per scan, before pD thinning
  double fov_range = 30.0;    ///< m
  double fov_half_angle = DegToRad(90.0);
  double range_buffer = 10.0;  ///< m
  double angle_buffer = DegToRad(10.0);
  Mat2 measurement_noise_cov;  ///< default diag(1^2, (2 deg)^2), the paper's
  Mat2 control_noise_cov;      ///< default diag(2^2, (5 deg)^2), the paper's

  ScPhdSimOptions();  ///< sets the matrix defaults
  /// Throws std::invalid_argument naming the field: steps >= 1; dt, speed, circle_radius,
  /// wheelbase > 0; landmarks >= 0; 0 <= inner < outer radius; and the sensor rules of
  /// SimulationSettings::Validate.
  void Validate() const;
};

/// The fixed map of the options (independent of any Monte Carlo seed).
std::vector<Landmark> ScPhdSimMap(const ScPhdSimOptions& options);

/// Monte Carlo run `seed` of scenario "scphd-sim"; deterministic in (options, seed).
Scenario MakeScPhdSimScenario(const ScPhdSimOptions& options, std::uint64_t seed);

}  // namespace phdslam::datasets
