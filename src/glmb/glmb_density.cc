#include "src/glmb/glmb_density.h"

#include <cmath>
#include <map>

namespace phdslam::glmb {

std::vector<Hypothesis> EmptyDensity() {
  return {Hypothesis{std::make_shared<const TrackSet>(), 0.0}};
}

std::vector<double> CardinalityDistribution(std::span<const Hypothesis> hypotheses) {
  std::vector<double> rho;
  for (const Hypothesis& h : hypotheses) {
    if (rho.size() <= h.size()) rho.resize(h.size() + 1, 0.0);
    rho[h.size()] += std::exp(h.log_weight);
  }
  return rho;
}

std::vector<std::pair<Label, double>> LabelExistence(std::span<const Hypothesis> hypotheses) {
  std::map<Label, double> r;
  for (const Hypothesis& h : hypotheses) {
    const double w = std::exp(h.log_weight);
    for (const TrackPtr& t : *h.tracks) r[t->label] += w;
  }
  return {r.begin(), r.end()};
}

int BestHypothesis(std::span<const Hypothesis> hypotheses) {
  int best = -1;
  for (int h = 0; h < static_cast<int>(hypotheses.size()); ++h) {
    if (best < 0 || hypotheses[h].log_weight > hypotheses[best].log_weight) best = h;
  }
  return best;
}

int MapCardinalityHypothesis(std::span<const Hypothesis> hypotheses) {
  const std::vector<double> rho = CardinalityDistribution(hypotheses);
  if (rho.empty()) return -1;
  std::size_t n_star = 0;
  for (std::size_t n = 1; n < rho.size(); ++n) {
    if (rho[n] > rho[n_star]) n_star = n;
  }
  int best = -1;
  for (int h = 0; h < static_cast<int>(hypotheses.size()); ++h) {
    if (hypotheses[h].size() != n_star) continue;
    if (best < 0 || hypotheses[h].log_weight > hypotheses[best].log_weight) best = h;
  }
  return best;
}

}  // namespace phdslam::glmb
