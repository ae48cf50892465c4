// The simulation of the delta-GLMB-SLAM paper (Moratuwage, Adams & Inostroza, Sensors 2019,
// section 5; docs/algorithms/models.md section 7), scenario "glmb-sim":
//  - stated: 23 static landmarks, a pre-planned closed loop revisited (loop closure around steps
//    125-150), speed 1 m/s, a disc field of view of radius 3 m (bearing -pi..pi), odometry noise
//    sigma 0.1 m/s in speed and 2 deg in steering, measurement noise 0.05 m and 0.5 deg (the
//    reading of the paper's "20" and "0.50" in models.md section 7.1), pD 0.7 inside the field of
//    view and 0 outside, Poisson clutter with mean clutter_rate per scan (1, 5, 10, 15 in the
//    paper);
//  - chosen here (the paper leaves them open), each an option below where it is a number:
//    * time step dt = 0.2 s (0.2 m per step): the consistency argument of models.md section 7.2, a
//      loop of about 25 m closed after about 125 steps, where a 3 m sensor sees only local
//      landmarks;
//    * motion model: the kinematic bicycle (Ackermann) model with a steering-angle control
//      [speed, steering], Euler-integrated (models::CarMotionModel without encoder or laser
//      offsets, as scphd-sim), wheelbase 1 m. The paper's "steering angle" noise and pre-planned
//      path point to Bailey's FastSLAM simulator, whose model is the same vehicle referenced at the
//      front axle (x += v dt cos(G + theta)); the suite's rear-axle form is used so every
//      estimator runs on it with its existing motion model;
//    * path: a rounded rectangle of 124 steps (24.8 m), driven counter-clockwise from (0, 0)
//      heading east: straights of 24 and 14 steps (4.8 m and 2.8 m), each followed by a left
//      corner of 12 steps at the constant steering angle that turns exactly 90 deg (33.2 deg,
//      radius about 1.5 m). The loop closes exactly; the horizon of 175 steps drives it once and
//      then again from step 124 to 174, the revisit in which loop closure happens;
//    * map: 23 landmarks at equal arc spacing along the loop (the true pose at step
//      round((i + 1/2) 124 / 23)), each landmark_offset = 1 m to the left (inside the loop) for
//      even i and to the right (outside) for odd i: no random map, the same for every seed;
//    * field of view: pD = detection_probability for a landmark at range <= 3 m (the point test
//      of SimulateRangeBearingSteps); the filters' active-set buffer range_buffer = 0.5 m (the
//      whole disc is in view, so angle_buffer is 0);
//    * clutter: clutter_rate Poisson points per scan uniform in (range, bearing) over
//      [0, fov_range) x [-fov_half_angle, fov_half_angle), noise-free and NOT thinned by pD, so its
//      intensity is exactly lambda / (2 Theta R), the ClutterSpace::kRangeBearingBox intensity the
//      scenario's sensor model gives every filter (kappa = 0.0531 per m rad at lambda = 1);
//    * detections: every landmark in the field of view is detected with probability pD, its range
//      and bearing perturbed by N(0, R), the bearing wrapped; measurements are listed landmark
//      detections first, then clutter (the filters never see the origins).
//  - data protocol (option data_protocol):
//    * per-seed (default, the suite's): odometry, detections and clutter drawn afresh for every
//      Monte Carlo seed;
//    * single-realisation (the paper's: "control commands and measurements were generated from a
//      single run ... clutter was generated in four separate runs"): every seed gets the data of
//      Monte Carlo seed data_seed, so the Monte Carlo runs differ only in the filters' random
//      numbers (their stream seeds still vary with the seed).
// Randomness: odometry noise, detection thinning and measurement noise come from the stream
// RandomStream(DeriveSeed(HashName("glmb-sim/data"), s)) and clutter from
// RandomStream(DeriveSeed(HashName("glmb-sim/clutter"), s)), s the data seed, so the landmark
// detections and the odometry are the same at every clutter rate (clutter is an overlay).
#pragma once

#include <cstdint>
#include <numbers>
#include <vector>

#include "datasets/scenario.h"
#include "src/core/angles.h"
#include "src/core/types.h"

namespace phdslam::datasets {

enum class GlmbDataProtocol {
  kPerSeed,            ///< fresh odometry and measurements for every Monte Carlo seed
  kSingleRealisation,  ///< the data of seed data_seed for every Monte Carlo seed
};

struct GlmbSimOptions {
  int steps = 175;
  double dt = 0.2;         ///< s, one control and one scan per step
  double speed = 1.0;      ///< m/s
  double wheelbase = 1.0;  ///< m
  int landmarks = 23;
  double landmark_offset = 1.0;  ///< m, distance of each landmark from the loop
  double detection_probability = 0.7;
  double clutter_rate = 1.0;  ///< Poisson mean per scan, not thinned
  double fov_range = 3.0;     ///< m
  double fov_half_angle = std::numbers::pi;
  double range_buffer = 0.5;   ///< m, the filters' active-set buffer
  double angle_buffer = 0.0;   ///< rad
  Mat2 measurement_noise_cov;  ///< default diag(0.05^2, (0.5 deg)^2)
  Mat2 control_noise_cov;      ///< default diag(0.1^2, (2 deg)^2)
  GlmbDataProtocol data_protocol = GlmbDataProtocol::kPerSeed;
  int data_seed = 1;  ///< the data's seed under kSingleRealisation

  GlmbSimOptions();  ///< sets the matrix defaults
  /// Throws std::invalid_argument naming the field: steps >= 1; dt, speed, wheelbase > 0;
  /// landmarks >= 0; landmark_offset >= 0; data_seed >= 0; and the sensor rules of
  /// SimulationSettings::Validate.
  void Validate() const;
};

/// Steps of one lap of the loop (the path repeats with this period).
inline constexpr int kGlmbSimLoopSteps = 124;

/// The noise-free poses of `steps` steps along the loop and the controls held between them.
struct GlmbSimPath {
  std::vector<Pose> poses;
  std::vector<Control> controls;
};
GlmbSimPath GlmbSimTruePath(const GlmbSimOptions& options, int steps);

/// The fixed map of the options (independent of any seed).
std::vector<Landmark> GlmbSimMap(const GlmbSimOptions& options);

/// Monte Carlo run `seed` of scenario "glmb-sim"; deterministic in (options, seed), and under
/// kSingleRealisation independent of `seed` except for Scenario::seed.
Scenario MakeGlmbSimScenario(const GlmbSimOptions& options, std::uint64_t seed);

}  // namespace phdslam::datasets
