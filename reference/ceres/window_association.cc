#include "reference/ceres/window_association.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <tuple>

#include "src/core/angles.h"
#include "src/models/range_bearing_model.h"

namespace phdslam::reference {

std::vector<int> GatedNearestNeighbour(const Pose& x, const Mat3& pose_cov,
                                       const std::vector<Measurement>& measurements,
                                       const std::vector<AssociationCandidate>& candidates,
                                       const Mat2& noise_cov, double gate_chi2) {
  std::vector<std::tuple<double, std::size_t, std::size_t>> pairs;  // distance, measurement, cand.
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const AssociationCandidate& c = candidates[i];
    if ((c.mean - x.head<2>()).squaredNorm() < 1e-18) continue;
    const Measurement h = models::PredictMeasurement(x, c.mean);
    const models::RangeBearingJacobians j = models::MeasurementJacobians(x, c.mean);
    const Mat2 cross = j.hm * c.pose_cross * j.hx.transpose();
    const Mat2 s = j.hx * pose_cov * j.hx.transpose() + j.hm * c.cov * j.hm.transpose() + cross +
                   cross.transpose() + noise_cov;
    const Eigen::LLT<Mat2> llt(s);
    if (llt.info() != Eigen::Success) continue;
    for (std::size_t m = 0; m < measurements.size(); ++m) {
      const Vec2 nu(h(0) - measurements[m](0), WrapAngle(h(1) - measurements[m](1)));
      const double d2 = nu.dot(llt.solve(nu));
      if (d2 < gate_chi2) pairs.emplace_back(d2, m, i);
    }
  }
  std::sort(pairs.begin(), pairs.end());
  std::vector<int> labels(measurements.size(), -1);
  std::vector<bool> taken(candidates.size(), false);
  for (const auto& [d2, m, i] : pairs) {
    if (labels[m] >= 0 || taken[i]) continue;
    labels[m] = candidates[i].label;
    taken[i] = true;
  }
  return labels;
}

}  // namespace phdslam::reference
