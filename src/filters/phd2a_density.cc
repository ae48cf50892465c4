#include "src/filters/phd2a_density.h"

#include <Eigen/LU>
#include <array>
#include <cmath>
#include <cstddef>
#include <memory_resource>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "src/core/angles.h"
#include "src/core/gaussian.h"
#include "src/core/log_sum_exp.h"
#include "src/models/range_bearing_model.h"
#include "src/models/sensor_model.h"

namespace phdslam::filters {
namespace {

/// Stack bytes for the scratch lists of one Build: room for about 40 gated pairs.
constexpr std::size_t kPhd2aScratchArenaBytes = std::size_t{12} * 1024;

/// One gated (component, measurement) pair.
struct Pair {
  int component;  ///< active-list index
  int measurement;
  int conditional;  ///< index of the component's conditional covariance
  double log_gain;  ///< log g_ij = log pD_i + eta_i + log N(nu_ij; 0, S_i)
  Pose mean;        ///< mu_0 + K_i nu_ij
};

}  // namespace

MomentMatchedGaussian MomentMatch(std::span<const double> log_weights, std::span<const Pose> means,
                                  std::span<const Mat3> covs) {
  if (log_weights.size() != means.size() || means.size() != covs.size()) {
    throw std::invalid_argument("MomentMatch: log_weights, means and covs must have equal sizes");
  }
  const double total = LogSumExp(log_weights);
  if (!std::isfinite(total)) {
    throw std::invalid_argument("MomentMatch: expected at least one finite log-weight");
  }
  // Moments about the first mean keep the differences small (poses are hundreds of metres).
  const Pose& origin = means[0];
  Vec3 offset = Vec3::Zero();
  Mat3 second = Mat3::Zero();
  for (std::size_t k = 0; k < means.size(); ++k) {
    if (log_weights[k] == kNegInf) continue;
    const double w = std::exp(log_weights[k] - total);
    const Vec3 d = means[k] - origin;
    offset += w * d;
    second += w * (covs[k] + d * d.transpose());
  }
  MomentMatchedGaussian g;
  g.mean = origin + offset;
  g.cov = second - offset * offset.transpose();
  Symmetrize(g.cov);
  return g;
}

ProposalOutput MergedEkfDensity::Build(const ProposalInput& input) const {
  const std::span<const phd::GaussianComponent> active = input.landmarks;
  const int num_z = static_cast<int>(input.measurements.size());
  if (active.empty() || num_z == 0) return PriorProposal(input);

  const double log_clutter = std::log(input.sensor->ClutterIntensity());
  const double log_two_pi = std::log(2.0 * std::numbers::pi);
  const Pose& mu0 = input.predicted_mean;
  const Mat3& sigma0 = input.predicted_cov;
  const models::FovView fov(*input.sensor, mu0);

  // The scratch lists of this build live in a stack arena (the heap only beyond it).
  std::array<std::byte, kPhd2aScratchArenaBytes> arena_bytes;  // uninitialised: the arena writes it
  std::pmr::monotonic_buffer_resource arena(arena_bytes.data(), arena_bytes.size());
  std::pmr::vector<Pair> pairs(&arena);
  std::pmr::vector<Mat3> conditional_covs(&arena);
  double log_missed_mass = kNegInf;
  models::LogDetectionTerms log_pd;
  for (int i = 0; i < static_cast<int>(active.size()); ++i) {
    const phd::GaussianComponent& comp = active[i];
    const double pd = fov.DetectionProbability(comp.mean);
    if (pd <= 0.0) continue;
    log_pd.Set(pd);
    log_missed_mass = LogAddExp(log_missed_mass, log_pd.log_miss() + comp.log_weight);
    const auto [z_hat, j] = models::PredictWithJacobians(mu0, comp.mean);
    const Mat32 pht = sigma0 * j.hx.transpose();
    Mat2 s = j.hx * pht + j.hm * comp.cov * j.hm.transpose() + input.sensor->noise_cov;
    Symmetrize(s);
    const Mat2 s_inv = s.inverse();
    const double log_norm =
        log_pd.log_pd() + comp.log_weight - log_two_pi - 0.5 * std::log(s.determinant());
    const Mat32 gain = pht * s_inv;
    const double range_window = FirstCoordinateGateHalfWidth(s, params_.map.gate_threshold);
    int conditional = -1;
    for (int jz = 0; jz < num_z; ++jz) {
      if (std::abs(input.measurements[jz](0) - z_hat(0)) > range_window) continue;
      Vec2 nu = input.measurements[jz] - z_hat;
      nu(1) = WrapAngle(nu(1));
      const double d2 = nu.dot(s_inv * nu);
      if (!(d2 < params_.map.gate_threshold)) continue;
      if (conditional < 0) {
        Mat3 cov = sigma0 - gain * s * gain.transpose();
        Symmetrize(cov);
        conditional = static_cast<int>(conditional_covs.size());
        conditional_covs.push_back(cov);
      }
      pairs.push_back({i, jz, conditional, log_norm - 0.5 * d2, mu0 + gain * nu});
    }
  }
  if (pairs.empty()) return PriorProposal(input);

  // Per-measurement normaliser log(lambda_c + sum_i g_ij) and best explanation.
  std::pmr::vector<double> log_denominator(num_z, log_clutter, &arena);
  std::pmr::vector<double> best_gain(num_z, log_clutter, &arena);
  ProposalOutput out;
  out.best_association.assign(num_z, -1);
  for (const Pair& p : pairs) {
    log_denominator[p.measurement] = LogAddExp(log_denominator[p.measurement], p.log_gain);
    if (p.log_gain > best_gain[p.measurement]) {
      best_gain[p.measurement] = p.log_gain;
      out.best_association[p.measurement] = p.component;
    }
  }

  // The mixture to collapse: the prior with the misdetection mass, then every conditional.
  std::pmr::vector<double> log_weights(&arena);
  std::pmr::vector<Pose> means(&arena);
  std::pmr::vector<Mat3> covs(&arena);
  log_weights.reserve(pairs.size() + 1);
  means.reserve(pairs.size() + 1);
  covs.reserve(pairs.size() + 1);
  log_weights.push_back(log_missed_mass);
  means.push_back(mu0);
  covs.push_back(sigma0);
  for (const Pair& p : pairs) {
    log_weights.push_back(p.log_gain - log_denominator[p.measurement]);
    means.push_back(p.mean);
    covs.push_back(conditional_covs[p.conditional]);
  }
  const MomentMatchedGaussian merged = MomentMatch(log_weights, means, covs);
  out.mixture.Add(0.0, merged.mean, merged.cov);
  return out;
}

}  // namespace phdslam::filters
