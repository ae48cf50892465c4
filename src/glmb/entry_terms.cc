#include "src/glmb/entry_terms.h"

#include <Eigen/LU>
#include <array>
#include <cmath>
#include <numbers>
#include <span>
#include <vector>

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

namespace {

/// The measurement-independent part of Innovate for one component: h(m_c), S_c and the constant
/// of its log-density, so that each measurement costs a subtraction and a quadratic form. The
/// same operations in the same order as Innovate and EvalGaussian2: the same values bit for bit.
struct ComponentPrediction {
  Measurement z_hat;
  Mat2 s;
  double det;
  double log_norm;  ///< -log(2 pi) - log(det) / 2
};

ComponentPrediction Predict(const TrackComponent& c, const Pose& x, const MeasurementSetup& setup) {
  const models::RangeBearingJacobians jac = models::MeasurementJacobians(x, c.mean);
  ComponentPrediction p;
  p.z_hat = models::PredictMeasurement(x, c.mean);
  p.s = jac.hm * c.cov * jac.hm.transpose() + setup.noise_cov;
  if (!setup.pose_cov.isZero()) p.s += jac.hx * setup.pose_cov * jac.hx.transpose();
  Symmetrize(p.s);
  p.det = p.s(0, 0) * p.s(1, 1) - p.s(0, 1) * p.s(1, 0);
  p.log_norm = -std::log(2.0 * std::numbers::pi) - 0.5 * std::log(p.det);
  return p;
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
  // Entries of the delta-GLMB filters have one component; LMB tracks a few.
  constexpr std::size_t kInline = 4;
  std::array<ComponentPrediction, kInline> inline_predictions;
  std::vector<ComponentPrediction> many;
  std::span<ComponentPrediction> predictions;
  if (track.gm.size() <= kInline) {
    predictions = std::span(inline_predictions.data(), track.gm.size());
  } else {
    many.resize(track.gm.size());
    predictions = many;
  }
  for (std::size_t c = 0; c < track.gm.size(); ++c) predictions[c] = Predict(track.gm[c], x, setup);
  std::vector<double> terms;
  for (int j = 0; j < static_cast<int>(measurements.size()); ++j) {
    terms.clear();
    DetectionTerm d;
    d.measurement = j;
    double best = kNegInf;
    for (std::size_t c = 0; c < track.gm.size(); ++c) {
      const ComponentPrediction& p = predictions[c];
      Vec2 nu = measurements[j] - p.z_hat;
      nu(1) = WrapAngle(nu(1));
      const Mat2& s = p.s;
      const double d2 = (s(1, 1) * nu(0) * nu(0) - (s(0, 1) + s(1, 0)) * nu(0) * nu(1) +
                         s(0, 0) * nu(1) * nu(1)) /
                        p.det;
      if (!(d2 <= setup.gate)) continue;
      const double v = track.gm[c].log_weight + (p.log_norm - 0.5 * d2);
      terms.push_back(v);
      if (v > best) {
        best = v;
        d.nu = nu;
        d.s = s;
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
