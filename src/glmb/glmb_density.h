// A delta-GLMB map density (docs/algorithms/glmb-slam.md section 3): weighted hypotheses over
// shared immutable entries, and the quantities derived from it (existence, cardinality, the MAP
// cardinality estimate of docs/algorithms/glmb-slam.md section 8.1).
#pragma once

#include <memory>
#include <span>
#include <vector>

#include "src/glmb/track.h"

namespace phdslam::glmb {

/// The entries of one hypothesis, sorted by id, labels distinct.
using TrackSet = std::vector<TrackPtr>;

struct Hypothesis {
  std::shared_ptr<const TrackSet> tracks;  ///< shared between copies, never mutated
  double log_weight = 0.0;                 ///< normalised over the density

  [[nodiscard]] std::size_t size() const { return tracks ? tracks->size() : 0; }
};

/// One hypothesis with no entries and weight 1 (the initial map, docs/algorithms/glmb-slam.md
/// section 3.4).
std::vector<Hypothesis> EmptyDensity();

/// rho(n) = sum of the weights of the hypotheses with n entries, n = 0..max size.
std::vector<double> CardinalityDistribution(std::span<const Hypothesis> hypotheses);

/// r_l = sum of the weights of the hypotheses holding label l, for each label present, in label
/// order.
std::vector<std::pair<Label, double>> LabelExistence(std::span<const Hypothesis> hypotheses);

/// Index of the highest-weight hypothesis (first on ties); -1 when empty.
int BestHypothesis(std::span<const Hypothesis> hypotheses);

/// docs/algorithms/glmb-slam.md section 8.1: n* = argmax rho (smallest n on ties), then the
/// highest-weight hypothesis with n* entries (first on ties); -1 when empty.
int MapCardinalityHypothesis(std::span<const Hypothesis> hypotheses);

}  // namespace phdslam::glmb
