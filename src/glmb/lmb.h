// Labelled multi-Bernoulli maps for LMB-SLAM (docs/algorithms/glmb-slam.md section 7): the
// conversions to and from a delta-GLMB, the per-track Gaussian-mixture reduction and the LMB
// estimate (docs/algorithms/glmb-slam.md section 8.2).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "src/glmb/glmb_density.h"

namespace phdslam::glmb {

/// One labelled Bernoulli: its density (the entry) and existence r.
struct Bernoulli {
  TrackPtr track;
  double existence = 0.0;
};

/// The product-form delta-GLMB of an LMB: every subset I of the tracks with weight
/// prod_{l in I} r_l prod_{l not in I} (1 - r_l) (subsets with weight 0 left out). 2^n
/// hypotheses: for tests and small n; the filter itself uses the single-hypothesis form with
/// existence in the eta rows (joint_update.h).
std::vector<Hypothesis> LmbToGlmb(std::span<const Bernoulli> lmb);

/// [V] glmb2lmb: r_l = sum_h w_h [l in L(I_h)], and p_l the mixture of the entries with label l,
/// each weighted by sum_{h holding it} w_h / r_l. A label with one entry keeps that entry; a
/// label with several gets a new entry (id from next_id) holding their components. Label order.
std::vector<Bernoulli> GlmbToLmb(std::span<const Hypothesis> hypotheses, std::uint64_t& next_id);

struct MixtureReduction {
  double prune_threshold = 1e-5;  ///< components with normalised weight below are dropped
  double merge_distance2 = 4.0;   ///< squared Mahalanobis distance under the heaviest's cov
  int max_components = 10;        ///< L_max
};

/// [V]'s per-track reduction: prune, then greedily merge around the heaviest remaining
/// component (moment-matched, with the spread-of-means term), cap at the heaviest L_max,
/// renormalise. Covariances stay symmetric (symmetrised sums of PSD terms).
std::vector<TrackComponent> ReduceMixture(std::vector<TrackComponent> gm,
                                          const MixtureReduction& settings);

/// rho(n) of the LMB with each r clipped to [0.001, 0.999] ([V]: prod(1 - r) ESF(r / (1 - r)),
/// evaluated as the Poisson-binomial recursion).
std::vector<double> LmbCardinality(std::span<const Bernoulli> lmb);

/// docs/algorithms/glmb-slam.md section 8.2: N = min(#tracks, argmax rho), the indices of the N
/// tracks with the largest r (stable on ties).
std::vector<int> LmbEstimateIndices(std::span<const Bernoulli> lmb);

}  // namespace phdslam::glmb
