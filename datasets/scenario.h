// The Scenario: everything one Monte Carlo run of one data set holds.
//
// An estimator sees only StepData (time stamps, controls, measurements) and the EstimatorContext
// built from the scenario's public part. The origin of each measurement (landmark index or
// clutter) is hidden: only the oracle and the metrics read ScenarioStep::origin.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "src/core/step_data.h"
#include "src/core/types.h"
#include "src/filters/estimator.h"
#include "src/models/car_motion_model.h"
#include "src/models/motion_model.h"
#include "src/models/sensor_model.h"

namespace phdslam::datasets {

/// Origin label of a clutter measurement.
inline constexpr int kClutter = -1;
/// Origin label of a real detection whose landmark is unknown (real data sets).
inline constexpr int kUnknownOrigin = -2;

/// What an estimator receives at one filter step (defined below the filters, in src/core).
using StepData = phdslam::StepData;

struct ScenarioStep {
  StepData data;
  /// Hidden: for each measurement its landmark index (0-based), kClutter, or kUnknownOrigin for
  /// a real detection of an unidentified landmark. Empty when nothing is known.
  std::vector<int> origin;
};

struct GpsFix {
  double t = 0.0;  ///< s, on the scenario's clock
  Vec2 position = Vec2::Zero();
};

struct GroundTruth {
  std::vector<Pose> poses;          ///< one per step (empty for real data)
  std::vector<Landmark> landmarks;  ///< true map (empty for real data)
  std::vector<GpsFix> gps;          ///< GPS fixes (real data)
  /// Per step: false where poses[k] is only a stand-in (real data without truth at that step:
  /// a gap in the reference system) and the step is left out of every pose metric. Empty when
  /// every pose is known.
  std::vector<bool> pose_scored;

  [[nodiscard]] bool PoseScored(std::size_t k) const {
    return pose_scored.empty() || pose_scored[k];
  }
};

enum class MotionKind { kVelocity, kCar };

struct Scenario {
  std::string name;
  std::uint64_t seed = 0;  ///< Monte Carlo seed the measurements were generated with
  Pose initial_pose = Pose::Zero();
  MotionKind motion = MotionKind::kVelocity;
  models::CarGeometry car;                    ///< used when motion == kCar
  Mat2 control_noise_cov = Mat2::Identity();  ///< Q_u
  models::SensorModel sensor;
  std::vector<ScenarioStep> steps;
  GroundTruth truth;

  [[nodiscard]] std::unique_ptr<models::MotionModel> MakeMotionModel() const;
  /// The public part an online estimator may see: initial pose, motion and sensor models, noise.
  [[nodiscard]] filters::EstimatorContext PublicContext() const;
  /// The time stamp of step k (its last time stamp).
  [[nodiscard]] double StepTime(std::size_t k) const { return steps[k].data.times.back(); }
};

}  // namespace phdslam::datasets
