// The state one FastSLAM particle carries: a pose and one EKF per landmark, each with the
// existence counter that removes clutter-born landmarks.
#pragma once

#include <vector>

#include "src/core/types.h"

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
};

}  // namespace phdslam::reference
