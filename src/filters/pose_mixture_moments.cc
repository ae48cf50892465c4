#include "src/filters/pose_mixture_moments.h"

#include <cmath>

#include "src/core/angles.h"
#include "src/core/gaussian.h"
#include "src/core/log_sum_exp.h"

namespace phdslam::filters {
namespace {

// mu_t - reference with the heading difference wrapped.
Vec3 WrappedDifference(const Pose& mu, const Pose& reference) {
  Vec3 d = mu - reference;
  d(2) = WrapAngle(d(2));
  return d;
}

}  // namespace

std::optional<PoseMoments> MatchMoments(std::span<const PoseMoments> components) {
  if (components.empty()) return std::nullopt;
  double log_total = kNegInf;
  for (const PoseMoments& c : components) log_total = LogAddExp(log_total, c.log_weight);
  if (!std::isfinite(log_total)) return std::nullopt;
  const Pose& reference = components.front().mean;
  Vec3 offset = Vec3::Zero();
  for (const PoseMoments& c : components) {
    offset += std::exp(c.log_weight - log_total) * WrappedDifference(c.mean, reference);
  }
  PoseMoments out;
  out.log_weight = log_total;
  out.mean = reference + offset;
  for (const PoseMoments& c : components) {
    const double w = std::exp(c.log_weight - log_total);
    if (w == 0.0) continue;
    const Vec3 d = WrappedDifference(c.mean, out.mean);
    out.cov += w * (c.cov + d * d.transpose());
  }
  Symmetrize(out.cov);
  return out;
}

PoseMoments ProposalMoments(const PreparedProposal& proposal, const Pose& fallback) {
  const GaussianMixtureProposal& g = proposal.mixture;
  // Single-component fast path (the prior, 2.0a/2.0b and most 3.0 steps): no wrapping needed.
  if (g.size() == 1) {
    if (proposal.chol[0]) return {0.0, g.means[0], g.covs[0]};
    return {0.0, fallback, Mat3::Zero()};
  }
  const Pose& reference = proposal.chol[0] ? g.means[0] : fallback;
  Vec3 offset = Vec3::Zero();
  for (std::size_t t = 0; t < g.size(); ++t) {
    const Pose& mu = proposal.chol[t] ? g.means[t] : fallback;
    offset += std::exp(g.log_weights[t]) * WrappedDifference(mu, reference);
  }
  PoseMoments out;
  out.mean = reference + offset;
  for (std::size_t t = 0; t < g.size(); ++t) {
    const double w = std::exp(g.log_weights[t]);
    if (w == 0.0) continue;
    const bool valid = proposal.chol[t].has_value();
    const Vec3 d = WrappedDifference(valid ? g.means[t] : fallback, out.mean);
    out.cov += w * d * d.transpose();
    if (valid) out.cov += w * g.covs[t];
  }
  Symmetrize(out.cov);
  return out;
}

}  // namespace phdslam::filters
