#include "src/glmb/entry_terms.h"

#include <Eigen/LU>
#include <cmath>

#include "src/core/angles.h"
#include "src/core/gaussian.h"
#include "src/core/log_sum_exp.h"
#include "src/models/range_bearing_model.h"

namespace phdslam::glmb {

namespace {

struct ComponentInnovation {
  Vec2 nu;
  Mat2 s;
  Mat2 hm;
  double log_pdf;
  double d2;
};

ComponentInnovation Innovate(const TrackComponent& c, const Pose& x, const Measurement& z,
                             const MeasurementSetup& setup) {
  const models::RangeBearingJacobians jac = models::MeasurementJacobians(x, c.mean);
  Vec2 nu = z - models::PredictMeasurement(x, c.mean);
  nu(1) = WrapAngle(nu(1));
  Mat2 s = jac.hm * c.cov * jac.hm.transpose() + setup.noise_cov;
  if (!setup.pose_cov.isZero()) s += jac.hx * setup.pose_cov * jac.hx.transpose();
  Symmetrize(s);
  const Gaussian2Eval e = EvalGaussian2(nu, s);
  return {nu, s, jac.hm, e.log_pdf, e.mahalanobis2};
}

}  // namespace

EntryTerms ComputeEntryTerms(const Track& track, const Pose& x,
                             std::span<const Measurement> measurements,
                             const MeasurementSetup& setup) {
  EntryTerms t;
  const TrackComponent& heaviest = track.Heaviest();
  t.pd = setup.sensor->DetectionProbability(x, heaviest.mean);
  t.in_fov = t.pd > 0.0;
  if (!t.in_fov) return t;
  std::vector<double> terms;
  for (int j = 0; j < static_cast<int>(measurements.size()); ++j) {
    terms.clear();
    DetectionTerm d;
    d.measurement = j;
    double best = kNegInf;
    for (const TrackComponent& c : track.gm) {
      const ComponentInnovation in = Innovate(c, x, measurements[j], setup);
      if (!(in.d2 <= setup.gate)) continue;
      const double v = c.log_weight + in.log_pdf;
      terms.push_back(v);
      if (v > best) {
        best = v;
        d.nu = in.nu;
        d.s = in.s;
      }
    }
    if (terms.empty()) continue;
    d.log_q = LogSumExp(terms);
    t.detections.push_back(d);
  }
  return t;
}

std::optional<Track> DetectionChild(const Track& track, const Pose& x, const Measurement& z,
                                    const MeasurementSetup& setup) {
  MeasurementSetup no_pose = setup;
  no_pose.pose_cov.setZero();
  Track child;
  child.label = track.label;
  std::vector<double> log_w;
  for (const TrackComponent& c : track.gm) {
    const ComponentInnovation in = Innovate(c, x, z, no_pose);
    if (!(in.d2 <= setup.gate)) continue;
    const Eigen::Matrix<double, 2, 2> k = c.cov * in.hm.transpose() * in.s.inverse();
    const Mat2 a = Mat2::Identity() - k * in.hm;
    Mat2 p = a * c.cov * a.transpose() + k * setup.noise_cov * k.transpose();
    Symmetrize(p);
    child.gm.push_back(TrackComponent{c.log_weight + in.log_pdf, c.mean + k * in.nu, p});
    log_w.push_back(c.log_weight + in.log_pdf);
  }
  if (child.gm.empty()) return std::nullopt;
  const double norm = LogSumExp(log_w);
  for (TrackComponent& c : child.gm) c.log_weight -= norm;
  return child;
}

}  // namespace phdslam::glmb
