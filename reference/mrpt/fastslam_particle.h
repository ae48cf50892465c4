// The state one FastSLAM particle carries: a pose and one EKF per landmark, each with the
// existence counter that removes clutter-born landmarks.
#pragma once

#include <vector>

#include "src/core/types.h"
#include "src/filters/innovation_stats.h"
#include "src/filters/pose_mixture_moments.h"

namespace phdslam::reference {

struct FastSlamLandmark {
  Landmark mean = Landmark::Zero();
  Mat2 cov = Mat2::Identity();
  /// Existence counter: 0 at creation, +1 for each associated measurement, -1 for each step in
  /// which the landmark was predicted visible (pD > 0 at the particle's pose) but not associated.
  /// The landmark is removed when the counter drops below zero.
  int counter = 0;
  int associations = 0;  ///< measurements associated since creation (creation excluded)
  int birth_step = 0;    ///< index of the step that created the landmark
  bool confirmed = false;
};

struct FastSlamParticle {
  Pose pose = Pose::Zero();  ///< sampled pose; the heading is not wrapped
  std::vector<FastSlamLandmark> landmarks;
  /// The Gaussian the last step drew `pose` from (FastSLAM 1.0: the predicted Gaussian; 2.0: the
  /// measurement-conditioned one), with the log-weight the particle carried into that step.
  filters::PoseMoments proposal;
  /// NIS of the last step's associated measurements, with the innovation covariances the weight
  /// used (1.0: at the sampled pose; 2.0: the sequential ones including the pose uncertainty).
  filters::InnovationStats nis;
};

}  // namespace phdslam::reference
