#include "src/glmb/joint_update.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>

#include "src/core/log_sum_exp.h"

namespace phdslam::glmb {

namespace {

double LogOrNegInf(double v) { return v > 0.0 ? std::log(v) : kNegInf; }

/// The eta row of an entry with existence e (p_S for a survivor, r_B for a birth, p_S r for an
/// LMB track) and its terms (docs/algorithms/glmb-slam.md section 4.2).
EtaRow MakeEtaRow(double e, const EntryTerms& terms, double log_kappa) {
  EtaRow row;
  row.log_death = e >= 1.0 ? kNegInf : std::log1p(-e);
  const double log_e = LogOrNegInf(e);
  row.log_miss = log_e + (terms.pd >= 1.0 ? kNegInf : std::log1p(-terms.pd));
  const double log_pd = LogOrNegInf(terms.pd);
  row.detections.reserve(terms.detections.size());
  for (const DetectionTerm& d : terms.detections) {
    row.detections.emplace_back(d.measurement, log_e + log_pd + d.log_q - log_kappa);
  }
  return row;
}

/// A map from track id to an int (its entry, or kOutside), by open addressing in one
/// allocation sized for at most `capacity` ids.
class IdIndex {
 public:
  static constexpr int kOutside = -1;

  explicit IdIndex(std::size_t capacity) {
    std::size_t n = 16;
    while (n < 2 * capacity) n *= 2;
    slots_.assign(n, Slot{});
  }

  /// The value of `id`, inserted as `value` when absent (then `inserted` is true).
  std::pair<int*, bool> Emplace(std::uint64_t id, int value) {
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t i = MixSeed(id) & mask;; i = (i + 1) & mask) {
      Slot& slot = slots_[i];
      if (!slot.used) {
        slot = Slot{id, value, true};
        return {&slot.value, true};
      }
      if (slot.id == id) return {&slot.value, false};
    }
  }

 private:
  struct Slot {
    std::uint64_t id = 0;
    int value = 0;
    bool used = false;
  };
  std::vector<Slot> slots_;
};

/// log eta_e(gamma) of every entry e of a problem for gamma in -1..M, so that an association's
/// weight is one look-up per row: the values of LogEta, summed in the same row order as
/// LogAssociationWeight, for associations known to be valid.
class LogEtaTable {
 public:
  LogEtaTable(std::span<const EtaRow> eta, int measurements)
      : width_(static_cast<std::size_t>(measurements) + 2), values_(eta.size() * width_, kNegInf) {
    for (std::size_t e = 0; e < eta.size(); ++e) {
      double* row = values_.data() + e * width_;
      row[0] = eta[e].log_death;
      row[1] = eta[e].log_miss;
      for (const auto& [j, v] : eta[e].detections) row[j + 2] = v;
    }
  }

  /// sum_i log eta_{rows[i]}(gamma_i) for a valid gamma.
  [[nodiscard]] double LogWeight(std::span<const int> rows, const Association& gamma) const {
    double total = 0.0;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      total += values_[static_cast<std::size_t>(rows[i]) * width_ +
                       static_cast<std::size_t>(gamma[i] + 1)];
    }
    return total;
  }

 private:
  std::size_t width_;
  std::vector<double> values_;
};

}  // namespace

JointProblem BuildJointProblem(std::span<const Hypothesis> prior, std::span<const double> existence,
                               std::span<const BirthTrack> births, const Pose& x,
                               std::span<const Measurement> measurements,
                               const MeasurementSetup& setup, const UpdateSettings& settings) {
  JointProblem p;
  p.measurements = static_cast<int>(measurements.size());
  p.log_ck = -settings.clutter_rate + p.measurements * settings.log_clutter_intensity;
  // Out-of-FOV entries never enter the problem (they pass through, BuildPosterior). Each id is
  // tested once: `index` holds its entry, or kOutside; the hypotheses share most tracks.
  const models::FovView fov(*setup.sensor, x);
  std::size_t listed = 0;
  for (const Hypothesis& h : prior) listed += h.tracks->size();
  IdIndex index(listed);
  std::vector<double> entry_existence;
  std::vector<std::vector<int>> in_fov(prior.size());
  for (std::size_t h = 0; h < prior.size(); ++h) {
    const TrackSet& tracks = *prior[h].tracks;
    for (std::size_t i = 0; i < tracks.size(); ++i) {
      const TrackPtr& t = tracks[i];
      const auto [entry, inserted] = index.Emplace(t->id, IdIndex::kOutside);
      if (inserted && fov.DetectionProbability(t->Heaviest().mean) > 0.0) {
        *entry = static_cast<int>(p.entries.size());
        p.entries.push_back(t);
        p.terms.push_back(ComputeEntryTerms(*t, x, measurements, setup));
        const double mult = existence.empty() ? 1.0 : existence[i];
        entry_existence.push_back(mult * settings.survival_probability);
      }
      if (*entry != IdIndex::kOutside) in_fov[h].push_back(*entry);
    }
  }
  p.prior_entries = static_cast<int>(p.entries.size());
  for (const BirthTrack& b : births) {
    p.entries.push_back(b.track);
    p.terms.push_back(ComputeEntryTerms(*b.track, x, measurements, setup));
    entry_existence.push_back(b.existence);
  }
  p.eta.reserve(p.entries.size());
  for (std::size_t e = 0; e < p.entries.size(); ++e) {
    p.eta.push_back(MakeEtaRow(entry_existence[e], p.terms[e], settings.log_clutter_intensity));
  }
  p.parents.reserve(prior.size());
  for (std::size_t h = 0; h < prior.size(); ++h) {
    JointProblem::Parent parent;
    parent.log_weight = prior[h].log_weight;
    parent.tracks = prior[h].tracks;
    parent.rows.reserve(in_fov[h].size() + p.entries.size() - p.prior_entries);
    parent.rows.assign(in_fov[h].begin(), in_fov[h].end());
    parent.in_fov_rows = static_cast<int>(parent.rows.size());
    // A birth outside the FOV cannot be detected: its row still decides born / not born.
    for (int b = p.prior_entries; b < static_cast<int>(p.entries.size()); ++b) {
      parent.rows.push_back(b);
    }
    p.parents.push_back(std::move(parent));
  }
  return p;
}

std::vector<SampledAssociation> SampleAssociations(const JointProblem& problem,
                                                   const UpdateSettings& settings,
                                                   RandomStream& rng) {
  std::vector<double> half_log_w;
  half_log_w.reserve(problem.parents.size());
  for (const JointProblem::Parent& h : problem.parents) half_log_w.push_back(0.5 * h.log_weight);
  const double norm = LogSumExp(half_log_w);
  std::vector<SampledAssociation> out;
  const SamplerRows sampler_rows = MakeSamplerRows(problem.eta, problem.measurements);
  GibbsScratch scratch;  // reused by every parent's chain
  const LogEtaTable log_eta(problem.eta, problem.measurements);
  for (int h = 0; h < static_cast<int>(problem.parents.size()); ++h) {
    const JointProblem::Parent& parent = problem.parents[h];
    const EtaRows eta = problem.EtaOf(static_cast<std::size_t>(h));
    const double share = std::exp(half_log_w[h] - norm) * settings.samples;
    const int t_h = std::max(1, static_cast<int>(std::lround(share)));
    std::optional<Association> start;
    if (!settings.optimal_start) {
      start = Association(parent.rows.size(), 0);
      if (LogAssociationWeight(eta, *start) == kNegInf) start.reset();
    }
    if (!start) start = OptimalAssociation(eta, problem.measurements);
    if (!start) continue;
    std::vector<Association> distinct =
        t_h == 1 ? std::vector<Association>{*start}
                 : DistinctGibbsSamples(sampler_rows, parent.rows, problem.measurements, *start,
                                        t_h, rng, scratch);
    for (Association& gamma : distinct) {
      // Valid: a chain's sample, or a start checked above.
      const double lw = parent.log_weight + log_eta.LogWeight(parent.rows, gamma) + problem.log_ck;
      out.push_back(SampledAssociation{h, std::move(gamma), lw});
    }
  }
  return out;
}

namespace {

/// A child hypothesis: the first sample giving it (which lists its entries) and its weight.
struct Child {
  double log_weight = kNegInf;
  int sample = 0;
};

/// A hash of a child's sorted entry ids (its key for merging duplicates).
struct IdSetHash {
  std::size_t operator()(const std::vector<std::uint64_t>& ids) const {
    std::uint64_t h = 0x9e3779b97f4a7c15ULL;
    for (std::uint64_t id : ids) h = MixSeed(h ^ id);
    return static_cast<std::size_t>(h);
  }
};

void NormaliseLogWeights(std::vector<Child>& children) {
  std::vector<double> lw;
  lw.reserve(children.size());
  for (const Child& c : children) lw.push_back(c.log_weight);
  const double norm = LogSumExp(lw);
  for (Child& c : children) c.log_weight -= norm;
}

/// Normalise, prune w <= threshold (the best hypothesis is always kept), renormalise, sort
/// descending (stable), cap, renormalise: docs/algorithms/glmb-slam.md section 4.4, in [V]'s order.
void Truncate(std::vector<Child>& children, const UpdateSettings& settings) {
  NormaliseLogWeights(children);
  std::stable_sort(children.begin(), children.end(),
                   [](const Child& a, const Child& b) { return a.log_weight > b.log_weight; });
  const double log_tau = std::log(settings.prune_threshold);
  std::size_t keep = 1;
  while (keep < children.size() && children[keep].log_weight > log_tau) ++keep;
  keep = std::min<std::size_t>(keep, std::max(1, settings.max_hypotheses));
  children.resize(keep);
  NormaliseLogWeights(children);
}

}  // namespace

UpdateResult BuildPosterior(const JointProblem& problem,
                            std::span<const SampledAssociation> samples, const Pose& x,
                            std::span<const Measurement> measurements,
                            const MeasurementSetup& setup, const UpdateSettings& settings,
                            std::uint64_t& next_id) {
  const int m = problem.measurements;
  std::vector<TrackPtr> child_cache(problem.entries.size() * static_cast<std::size_t>(m));
  auto child_of = [&](int e, int j) -> const TrackPtr& {
    TrackPtr& slot = child_cache[static_cast<std::size_t>(e) * m + j];
    if (!slot) {
      std::optional<Track> c = DetectionChild(*problem.entries[e], x, measurements[j], setup);
      // A gated pair always has a gated component, so c exists.
      c->id = next_id++;
      slot = std::make_shared<const Track>(std::move(*c));
    }
    return slot;
  };
  std::vector<Child> children;
  std::unordered_map<std::vector<std::uint64_t>, int, IdSetHash> seen;
  std::vector<double> all_log_w;
  all_log_w.reserve(samples.size());
  // Scratch reused over the samples: the child's entries with their ids (pointers into the
  // problem, the prior and the child cache, all stable here), the new detection children, the
  // id key.
  using TaggedTrack = std::pair<std::uint64_t, const TrackPtr*>;
  std::vector<TaggedTrack> tracks;
  std::vector<TaggedTrack> detected;
  std::vector<int> assigned;
  std::vector<std::uint64_t> key;
  const auto by_id = [](const TaggedTrack& a, const TaggedTrack& b) { return a.first < b.first; };
  const auto tag = [](const TrackPtr& t) { return TaggedTrack{t->id, &t}; };
  // The entries of sample s's child, in id order, into `tracks` (and its detected measurements
  // into `assigned`): the prior entries (pass-through, or kept when missed), then the births kept
  // (ids above every prior entry), then the new detection children (sorted: created here).
  auto gather = [&](int s) {
    const SampledAssociation& sample = samples[s];
    const JointProblem::Parent& parent = problem.parents[sample.parent];
    tracks.clear();
    detected.clear();
    assigned.clear();
    auto take = [&](std::size_t i) {
      const int g = sample.gamma[i];
      if (g == 0) tracks.push_back(tag(problem.entries[parent.rows[i]]));
      if (g > 0) {
        detected.push_back(tag(child_of(parent.rows[i], g - 1)));
        assigned.push_back(g - 1);
      }
    };
    std::size_t r = 0;
    for (const TrackPtr& t : *parent.tracks) {
      if (r < static_cast<std::size_t>(parent.in_fov_rows) &&
          problem.entries[parent.rows[r]] == t) {
        take(r++);
      } else {
        tracks.push_back(tag(t));
      }
    }
    for (std::size_t i = parent.in_fov_rows; i < parent.rows.size(); ++i) take(i);
    std::sort(detected.begin(), detected.end(), by_id);
    tracks.insert(tracks.end(), detected.begin(), detected.end());
    if (!std::is_sorted(tracks.begin(), tracks.end(), by_id)) {
      std::sort(tracks.begin(), tracks.end(), by_id);
    }
  };
  // Children are merged by their id sets; their entries are copied only for those kept.
  for (int s = 0; s < static_cast<int>(samples.size()); ++s) {
    all_log_w.push_back(samples[s].log_weight);
    gather(s);
    key.resize(tracks.size());
    for (std::size_t i = 0; i < key.size(); ++i) key[i] = tracks[i].first;
    const auto [it, inserted] = seen.try_emplace(key, static_cast<int>(children.size()));
    if (inserted) {
      Child c;
      c.sample = s;
      c.log_weight = samples[s].log_weight;
      children.push_back(std::move(c));
    } else {
      Child& d = children[it->second];
      d.log_weight = LogAddExp(d.log_weight, samples[s].log_weight);
    }
  }
  UpdateResult result;
  result.log_normaliser = LogSumExp(all_log_w);
  result.measurement_assigned.assign(m, 0.0);
  result.measurement_gates_best_prior.assign(m, 0);
  int best_parent = -1;
  for (int h = 0; h < static_cast<int>(problem.parents.size()); ++h) {
    if (best_parent < 0 ||
        problem.parents[h].log_weight > problem.parents[best_parent].log_weight) {
      best_parent = h;
    }
  }
  if (best_parent >= 0) {
    for (int e : problem.parents[best_parent].rows) {
      if (e >= problem.prior_entries) continue;
      for (const DetectionTerm& d : problem.terms[e].detections) {
        result.measurement_gates_best_prior[d.measurement] = 1;
      }
    }
  }
  if (children.empty()) return result;
  Truncate(children, settings);
  result.hypotheses.reserve(children.size());
  for (const Child& c : children) {
    gather(c.sample);
    const double w = std::exp(c.log_weight);
    for (int j : assigned) result.measurement_assigned[j] += w;
    TrackSet entries;
    entries.reserve(tracks.size());
    for (const TaggedTrack& t : tracks) entries.push_back(*t.second);
    result.hypotheses.push_back(
        Hypothesis{std::make_shared<const TrackSet>(std::move(entries)), c.log_weight});
  }
  const SampledAssociation& top = samples[children.front().sample];
  const JointProblem::Parent& parent = problem.parents[top.parent];
  for (std::size_t i = 0; i < parent.rows.size(); ++i) {
    const int g = top.gamma[i];
    if (g <= 0) continue;
    for (const DetectionTerm& d : problem.terms[parent.rows[i]].detections) {
      if (d.measurement == g - 1) result.best_innovations.emplace_back(d.nu, d.s);
    }
  }
  return result;
}

UpdateResult JointUpdate(std::span<const Hypothesis> prior, std::span<const double> existence,
                         std::span<const BirthTrack> births, const Pose& x,
                         std::span<const Measurement> measurements, const MeasurementSetup& setup,
                         const UpdateSettings& settings, RandomStream& rng,
                         std::uint64_t& next_id) {
  MeasurementSetup at_pose = setup;
  at_pose.pose_cov.setZero();
  const JointProblem problem =
      BuildJointProblem(prior, existence, births, x, measurements, at_pose, settings);
  const std::vector<SampledAssociation> samples = SampleAssociations(problem, settings, rng);
  UpdateResult result =
      BuildPosterior(problem, samples, x, measurements, at_pose, settings, next_id);
  if (result.hypotheses.empty()) {
    result.hypotheses.assign(prior.begin(), prior.end());
    result.log_normaliser = kNegInf;
  }
  return result;
}

}  // namespace phdslam::glmb
