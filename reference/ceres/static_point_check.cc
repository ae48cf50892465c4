#include "reference/ceres/static_point_check.h"

#include <Eigen/LU>
#include <cmath>

#include "reference/ceres/pose_covariance_propagation.h"
#include "src/core/gaussian.h"
#include "src/models/range_bearing_model.h"

namespace phdslam::reference {

Eigen::Matrix<double, 2, 3> InverseModelPoseJacobian(const Pose& x, const Measurement& z) {
  const double a = x(2) + z(1);
  Eigen::Matrix<double, 2, 3> jx;
  jx << 1.0, 0.0, -z(0) * std::sin(a), 0.0, 1.0, z(0) * std::cos(a);
  return jx;
}

StaticPointAnchor AnchorAt(const Measurement& z, const Mat2& r) {
  StaticPointAnchor anchor;
  anchor.point = models::InverseMeasurement(Pose::Zero(), z);
  anchor.point_cov = models::BirthCovariance(Pose::Zero(), z, r);
  return anchor;
}

void AdvanceAnchor(const OdometryIncrement& increment, StaticPointAnchor* anchor) {
  if (!increment.propagated) return;
  anchor->relative_cov = PropagatePoseCovariance(anchor->relative, increment, anchor->relative_cov);
  Symmetrize(anchor->relative_cov);
  anchor->relative = ComposeRelative(anchor->relative, increment.delta);
}

double StaticPointChi2(const StaticPointAnchor& anchor, const Measurement& z, const Mat2& r) {
  const Eigen::Matrix<double, 2, 3> jx = InverseModelPoseJacobian(anchor.relative, z);
  Mat2 c = models::BirthCovariance(anchor.relative, z, r) +
           jx * anchor.relative_cov * jx.transpose() + anchor.point_cov;
  Symmetrize(c);
  const Vec2 d = models::InverseMeasurement(anchor.relative, z) - anchor.point;
  return d.dot(c.ldlt().solve(d));
}

void AdvanceTrack(const OdometryIncrement& increment, StaticPointTrack* track) {
  AdvanceAnchor(increment, &track->first);
  AdvanceAnchor(increment, &track->latest);
}

bool MovingAfter(const Measurement& z, const Mat2& r, const StaticPointOptions& options,
                 StaticPointTrack* track) {
  const double sd = options.heading_std;
  if (track->first.relative_cov(2, 2) > sd * sd) track->first = track->latest;
  const bool moves = StaticPointChi2(track->first, z, r) > options.chi2 &&
                     StaticPointChi2(track->latest, z, r) <= options.chi2;
  track->failures = moves ? track->failures + 1 : 0;
  if (moves && track->failures >= options.failures_required) return true;
  track->latest = AnchorAt(z, r);
  return false;
}

}  // namespace phdslam::reference
