#include "src/glmb/lmb.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

#include "src/core/gaussian.h"
#include "src/core/log_sum_exp.h"

namespace phdslam::glmb {

std::vector<Hypothesis> LmbToGlmb(std::span<const Bernoulli> lmb) {
  const std::size_t n = lmb.size();
  std::vector<Hypothesis> out;
  for (std::size_t mask = 0; mask < (std::size_t{1} << n); ++mask) {
    double lw = 0.0;
    TrackSet set;
    for (std::size_t i = 0; i < n; ++i) {
      const double r = lmb[i].existence;
      if ((mask >> i) & 1U) {
        lw += std::log(r);
        set.push_back(lmb[i].track);
      } else {
        lw += std::log1p(-r);
      }
    }
    if (lw == kNegInf) continue;
    std::sort(set.begin(), set.end(),
              [](const TrackPtr& a, const TrackPtr& b) { return a->id < b->id; });
    out.push_back(Hypothesis{std::make_shared<const TrackSet>(std::move(set)), lw});
  }
  return out;
}

std::vector<Bernoulli> GlmbToLmb(std::span<const Hypothesis> hypotheses, std::uint64_t& next_id) {
  struct LabelMass {
    double r = 0.0;
    std::vector<TrackPtr> entries;  // first-seen order
    std::vector<double> weights;
  };
  std::map<Label, LabelMass> labels;
  for (const Hypothesis& h : hypotheses) {
    const double w = std::exp(h.log_weight);
    for (const TrackPtr& t : *h.tracks) {
      LabelMass& l = labels[t->label];
      l.r += w;
      auto it = std::find(l.entries.begin(), l.entries.end(), t);
      if (it == l.entries.end()) {
        l.entries.push_back(t);
        l.weights.push_back(w);
      } else {
        l.weights[it - l.entries.begin()] += w;
      }
    }
  }
  std::vector<Bernoulli> out;
  out.reserve(labels.size());
  for (auto& [label, l] : labels) {
    if (l.entries.size() == 1) {
      out.push_back(Bernoulli{l.entries.front(), std::min(l.r, 1.0)});
      continue;
    }
    Track merged;
    merged.id = next_id++;
    merged.label = label;
    for (std::size_t e = 0; e < l.entries.size(); ++e) {
      const double lw = std::log(l.weights[e] / l.r);
      for (const TrackComponent& c : l.entries[e]->gm) {
        merged.gm.push_back(TrackComponent{c.log_weight + lw, c.mean, c.cov});
      }
    }
    out.push_back(Bernoulli{std::make_shared<const Track>(std::move(merged)), std::min(l.r, 1.0)});
  }
  return out;
}

std::vector<TrackComponent> ReduceMixture(std::vector<TrackComponent> gm,
                                          const MixtureReduction& settings) {
  if (gm.size() <= 1) {
    for (TrackComponent& c : gm) c.log_weight = 0.0;
    return gm;
  }
  std::vector<double> lw;
  lw.reserve(gm.size());
  for (const TrackComponent& c : gm) lw.push_back(c.log_weight);
  const double norm = LogSumExp(lw);
  const double log_prune = std::log(settings.prune_threshold);
  std::vector<TrackComponent> left;
  for (TrackComponent& c : gm) {
    c.log_weight -= norm;
    if (c.log_weight >= log_prune) left.push_back(c);
  }
  if (left.empty())
    left.push_back(*std::max_element(gm.begin(), gm.end(),
                                     [](const TrackComponent& a, const TrackComponent& b) {
                                       return a.log_weight < b.log_weight;
                                     }));
  std::vector<TrackComponent> merged;
  while (!left.empty()) {
    std::size_t j = 0;
    for (std::size_t i = 1; i < left.size(); ++i) {
      if (left[i].log_weight > left[j].log_weight) j = i;
    }
    const Mat2 pinv = left[j].cov.inverse();
    const Landmark mj = left[j].mean;
    std::vector<TrackComponent> group;
    std::vector<TrackComponent> rest;
    for (const TrackComponent& c : left) {
      const Vec2 d = c.mean - mj;
      if (d.dot(pinv * d) <= settings.merge_distance2) {
        group.push_back(c);
      } else {
        rest.push_back(c);
      }
    }
    std::vector<double> glw;
    glw.reserve(group.size());
    for (const TrackComponent& c : group) glw.push_back(c.log_weight);
    const double gnorm = LogSumExp(glw);
    Landmark mean = Landmark::Zero();
    for (const TrackComponent& c : group) mean += std::exp(c.log_weight - gnorm) * c.mean;
    Mat2 cov = Mat2::Zero();
    for (const TrackComponent& c : group) {
      const Vec2 d = c.mean - mean;
      cov += std::exp(c.log_weight - gnorm) * (c.cov + d * d.transpose());
    }
    Symmetrize(cov);
    merged.push_back(TrackComponent{gnorm, mean, cov});
    left = std::move(rest);
  }
  std::stable_sort(
      merged.begin(), merged.end(),
      [](const TrackComponent& a, const TrackComponent& b) { return a.log_weight > b.log_weight; });
  if (static_cast<int>(merged.size()) > settings.max_components) {
    merged.resize(std::max(1, settings.max_components));
  }
  lw.clear();
  for (const TrackComponent& c : merged) lw.push_back(c.log_weight);
  const double final_norm = LogSumExp(lw);
  for (TrackComponent& c : merged) c.log_weight -= final_norm;
  return merged;
}

std::vector<double> LmbCardinality(std::span<const Bernoulli> lmb) {
  std::vector<double> rho{1.0};
  for (const Bernoulli& b : lmb) {
    const double r = std::clamp(b.existence, 0.001, 0.999);
    rho.push_back(0.0);
    for (std::size_t n = rho.size() - 1; n > 0; --n) rho[n] = rho[n] * (1.0 - r) + rho[n - 1] * r;
    rho[0] *= 1.0 - r;
  }
  return rho;
}

std::vector<int> LmbEstimateIndices(std::span<const Bernoulli> lmb) {
  const std::vector<double> rho = LmbCardinality(lmb);
  const auto n_star =
      static_cast<std::size_t>(std::max_element(rho.begin(), rho.end()) - rho.begin());
  std::vector<int> order(lmb.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return lmb[a].existence > lmb[b].existence; });
  order.resize(std::min(n_star, order.size()));
  return order;
}

}  // namespace phdslam::glmb
