// Whether a landmark's detections are those of one static point (README.md, "Moving objects").
//
// A landmark is anchored at its first detection z_a: its inverse-model point q_a = g(0, z_a) in
// the frame of that detection's pose, with covariance G R G^T. The pose of every later step is
// then carried in that frame by the odometry alone, T_k = d_{a+1} (+) ... (+) d_k, with the
// propagated covariance P_k (pose_covariance_propagation.h; the odometry model's own floor). A
// later detection z_k of a static landmark gives the same point, q_k = g(T_k, z_k), up to
//   C = G_k R G_k^T + J_k P_k J_k^T + G R G^T,  J_k = d g / d T_k,
// so d = q_k - q_a has d^T C^-1 d ~ chi-square(2). A detection of a moving object does not: an
// object that moves while the vehicle stands still implies a rotation or translation of the
// vehicle that the odometry does not allow, which a joint solve would otherwise impose on the
// trajectory. The test is independent of the solve (it uses only the odometry between the two
// detections and the two measurements), so a solve that has already bent the trajectory to hold
// the object still cannot hide it.
#pragma once

#include "reference/ceres/odometry_increment.h"
#include "src/core/types.h"

namespace phdslam::reference {

/// d m / d x of the inverse model m = g(x, z).
Eigen::Matrix<double, 2, 3> InverseModelPoseJacobian(const Pose& x, const Measurement& z);

/// A landmark's anchor: its first detection's point and the odometry since.
struct StaticPointAnchor {
  Landmark point = Landmark::Zero();  ///< g(0, z_a), frame of the first detection's pose
  Mat2 point_cov = Mat2::Zero();      ///< G R G^T at z_a
  Pose relative = Pose::Zero();       ///< the current pose in that frame, by odometry
  Mat3 relative_cov = Mat3::Zero();   ///< its covariance (the odometry's alone)
};

/// The anchor of a landmark first detected as z (noise covariance r) at the current pose.
StaticPointAnchor AnchorAt(const Measurement& z, const Mat2& r);

/// Carries the anchor's current pose by one step's odometry (kept symmetric).
void AdvanceAnchor(const OdometryIncrement& increment, StaticPointAnchor* anchor);

/// d^T C^-1 d of a detection z at the anchor's current pose against the anchored point.
double StaticPointChi2(const StaticPointAnchor& anchor, const Measurement& z, const Mat2& r);

/// The check's settings (README.md, "Moving objects").
struct StaticPointOptions {
  double chi2 = 13.8;         ///< a detection beyond this (2 dof) of an anchor fails against it
  double heading_std = 0.2;   ///< the first anchor gives way to the latest beyond this (rad)
  int failures_required = 1;  ///< consecutive moving detections that delete the landmark
};

/// A landmark's state in the check: its first and latest detection, and how many consecutive
/// detections so far failed against the first while agreeing with the latest.
struct StaticPointTrack {
  StaticPointAnchor first;
  StaticPointAnchor latest;
  int failures = 0;
};

/// Carries both anchors by one step's odometry.
void AdvanceTrack(const OdometryIncrement& increment, StaticPointTrack* track);

/// Whether z, a detection associated with the track's landmark, makes it a moving object: the
/// first anchor gives way to the latest once its heading standard deviation exceeds
/// options.heading_std; z "moves" when it fails against the first anchor but not against the
/// latest, and the landmark is a moving object at the failures_required-th such detection in a
/// row (a detection that does not move resets the count). When it is not, z becomes the latest
/// anchor. A z that fails against both is kept: a misassociation, not evidence of motion.
bool MovingAfter(const Measurement& z, const Mat2& r, const StaticPointOptions& options,
                 StaticPointTrack* track);

}  // namespace phdslam::reference
