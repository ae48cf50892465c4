#include "src/glmb/joint_update.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numeric>

#include "src/core/log_sum_exp.h"
#include "src/glmb/hash_slots.h"

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
  [[nodiscard]] double LogWeight(std::span<const int> rows, std::span<const int> gamma) const {
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
  p.parents.resize(prior.size());
  for (std::size_t h = 0; h < prior.size(); ++h) {
    const TrackSet& tracks = *prior[h].tracks;
    std::vector<int>& in_fov = p.parents[h].rows;  // the births follow below
    in_fov.reserve(tracks.size() + births.size());
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
      if (*entry != IdIndex::kOutside) in_fov.push_back(*entry);
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
  for (std::size_t h = 0; h < prior.size(); ++h) {
    JointProblem::Parent& parent = p.parents[h];
    parent.log_weight = prior[h].log_weight;
    parent.tracks = prior[h].tracks;
    parent.in_fov_rows = static_cast<int>(parent.rows.size());
    // A birth outside the FOV cannot be detected: its row still decides born / not born.
    for (int b = p.prior_entries; b < static_cast<int>(p.entries.size()); ++b) {
      parent.rows.push_back(b);
    }
  }
  return p;
}

SampledAssociations SampleAssociations(const JointProblem& problem, const UpdateSettings& settings,
                                       RandomStream& rng) {
  std::vector<double> half_log_w;
  half_log_w.reserve(problem.parents.size());
  for (const JointProblem::Parent& h : problem.parents) half_log_w.push_back(0.5 * h.log_weight);
  const double norm = LogSumExp(half_log_w);
  SampledAssociations out;
  const SamplerRows sampler_rows = MakeSamplerRows(problem.eta, problem.measurements);
  GibbsScratch scratch;   // reused by every parent's chain
  std::vector<int> flat;  // a chain's distinct samples, one after the other
  Association start;      // a parent's start, and its scratch
  AssociationScratch association_scratch;
  const LogEtaTable log_eta(problem.eta, problem.measurements);
  for (int h = 0; h < static_cast<int>(problem.parents.size()); ++h) {
    const JointProblem::Parent& parent = problem.parents[h];
    const EtaRows eta = problem.EtaOf(static_cast<std::size_t>(h));
    const double share = std::exp(half_log_w[h] - norm) * settings.samples;
    const int t_h = std::max(1, static_cast<int>(std::lround(share)));
    bool have_start = false;
    if (!settings.optimal_start) {
      start.assign(parent.rows.size(), 0);
      have_start = LogAssociationWeight(eta, start) > kNegInf;
    }
    if (!have_start) {
      have_start = OptimalAssociation(eta, problem.measurements, start, association_scratch);
    }
    if (!have_start) continue;
    auto add = [&](std::span<const int> gamma) {
      // Valid: a chain's sample, or a start checked above.
      const double lw = parent.log_weight + log_eta.LogWeight(parent.rows, gamma) + problem.log_ck;
      out.values.insert(out.values.end(), gamma.begin(), gamma.end());
      out.samples.push_back(SampledAssociation{h, {}, lw});
    };
    if (t_h == 1) {
      add(start);
      continue;
    }
    const std::size_t count = DistinctGibbsSamples(sampler_rows, parent.rows, problem.measurements,
                                                   start, t_h, rng, scratch, flat);
    for (std::size_t k = 0; k < count; ++k) {
      add(std::span<const int>(flat).subspan(k * start.size(), start.size()));
    }
  }
  // The views, once the buffer has stopped growing: the samples' values lie one after the other.
  std::size_t first = 0;
  for (SampledAssociation& sample : out.samples) {
    const std::size_t rows = problem.parents[sample.parent].rows.size();
    sample.gamma = std::span<const int>(out.values).subspan(first, rows);
    first += rows;
  }
  return out;
}

namespace {

/// A child hypothesis: the first sample giving it (which lists its entries), its weight and the
/// hash of its entry-id set (ChildIndex::SampleHash).
struct Child {
  double log_weight = kNegInf;
  int sample = 0;
  std::uint64_t hash = 0;
};

/// A child's entry-id set is hashed as the sum of one term per id, so that a sample's hash is its
/// parent's pass-through part plus one term per row.
std::uint64_t IdTerm(std::uint64_t id) { return MixSeed(id); }

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

/// The detection children of one update. Each (entry, measurement) pair takes its id from
/// `next_id` at its first use, in the order of use; its track, the EKF child, is made only when a
/// kept hypothesis holds it. Ids and tracks are those of making every child at its first use.
class DetectionChildren {
 public:
  DetectionChildren(const JointProblem& problem, const Pose& x,
                    std::span<const Measurement> measurements, const MeasurementSetup& setup,
                    std::uint64_t& next_id)
      : problem_(problem),
        x_(x),
        measurements_(measurements),
        setup_(setup),
        next_id_(next_id),
        slots_(problem.entries.size() * static_cast<std::size_t>(problem.measurements)) {}

  /// The id of the child of entry e detected by z_j, taken from next_id at its first use.
  std::uint64_t Id(int e, int j) { return Named(e, j).id; }

  /// IdTerm of that id, computed once.
  std::uint64_t IdTermOf(int e, int j) { return Named(e, j).id_term; }

  /// The child's track, made at the first call; its id was taken before (Id).
  const TrackPtr& TrackOf(int e, int j) {
    Slot& slot = At(e, j);
    if (!slot.track) {
      std::optional<Track> c = DetectionChild(*problem_.entries[e], x_, measurements_[j], setup_);
      // A gated pair always has a gated component, so c exists.
      c->id = slot.id;
      slot.track = std::make_shared<const Track>(std::move(*c));
    }
    return slot.track;
  }

 private:
  struct Slot {
    std::uint64_t id = 0;
    std::uint64_t id_term = 0;
    bool has_id = false;
    TrackPtr track;
  };
  /// The slot of (e, j) with its id, taken from next_id at its first use.
  Slot& Named(int e, int j) {
    Slot& slot = At(e, j);
    if (!slot.has_id) {
      slot.id = next_id_++;
      slot.id_term = IdTerm(slot.id);
      slot.has_id = true;
    }
    return slot;
  }
  Slot& At(int e, int j) {
    return slots_[static_cast<std::size_t>(e) * static_cast<std::size_t>(problem_.measurements) +
                  static_cast<std::size_t>(j)];
  }

  const JointProblem& problem_;
  const Pose& x_;
  std::span<const Measurement> measurements_;
  const MeasurementSetup& setup_;
  std::uint64_t& next_id_;
  std::vector<Slot> slots_;
};

/// One entry of a child: its id and where its track is (a prior or problem entry, or the
/// detection child of entry `entry` and measurement `measurement`).
struct ChildEntry {
  std::uint64_t id = 0;
  const TrackPtr* track = nullptr;  ///< null for a detection child
  int entry = -1;
  int measurement = -1;
};

/// The children of the samples, keyed by entry-id set: each sample's set is hashed from its rows
/// (SampleHash), and the sets themselves are listed only to confirm a hash match and for the
/// children kept.
class ChildIndex {
 public:
  ChildIndex(const JointProblem& problem, std::span<const SampledAssociation> samples,
             DetectionChildren& detection)
      : problem_(problem),
        samples_(samples),
        detection_(detection),
        pass_through_(problem.parents.size()) {
    entry_id_.reserve(problem.entries.size());
    entry_id_term_.reserve(problem.entries.size());
    for (const TrackPtr& t : problem.entries) {
      entry_id_.push_back(t->id);
      entry_id_term_.push_back(IdTerm(t->id));
    }
  }

  /// Adds sample s to its child, or starts a child; detection ids are taken in row order.
  void Add(int s) {
    const std::uint64_t hash = SampleHash(s);
    const int found = slots_.Find(
        hash, [&](int k) { return children_[k].hash == hash && SameIds(children_[k].sample, s); });
    if (found >= 0) {
      Child& c = children_[found];
      c.log_weight = LogAddExp(c.log_weight, samples_[s].log_weight);
      return;
    }
    children_.push_back(Child{samples_[s].log_weight, s, hash});
    slots_.Insert(static_cast<int>(children_.size()) - 1, [&](int e) { return children_[e].hash; });
  }

  std::vector<Child>& children() { return children_; }

  /// The entries of sample s's child in id order, and its detected measurements in row order.
  void Gather(int s, std::vector<ChildEntry>& entries, std::vector<int>& assigned) {
    const SampledAssociation& sample = samples_[s];
    const JointProblem::Parent& parent = problem_.parents[sample.parent];
    entries.clear();
    kept_.clear();
    detected_.clear();
    assigned.clear();
    auto take = [&](std::size_t i, std::vector<ChildEntry>& missed) {
      const int g = sample.gamma[i];
      const int e = parent.rows[i];
      if (g == 0) missed.push_back(ChildEntry{entry_id_[e], &problem_.entries[e]});
      if (g > 0) {
        detected_.push_back(ChildEntry{detection_.Id(e, g - 1), nullptr, e, g - 1});
        assigned.push_back(g - 1);
      }
    };
    for (int i = 0; i < parent.in_fov_rows; ++i) take(i, kept_);
    // The prior entries in id order (the pass-through ones and the in-FOV rows each are), the
    // births kept after them (ids above every prior entry), the detection children (created
    // here) after those.
    const auto by_id = [](const ChildEntry& a, const ChildEntry& b) { return a.id < b.id; };
    const std::span<const ChildEntry> pass = PassThrough(sample.parent);
    std::merge(pass.begin(), pass.end(), kept_.begin(), kept_.end(), std::back_inserter(entries),
               by_id);
    for (std::size_t i = parent.in_fov_rows; i < parent.rows.size(); ++i) take(i, entries);
    std::sort(detected_.begin(), detected_.end(), by_id);
    entries.insert(entries.end(), detected_.begin(), detected_.end());
    if (!std::is_sorted(entries.begin(), entries.end(), by_id)) {
      std::sort(entries.begin(), entries.end(), by_id);
    }
  }

 private:
  /// The sum of IdTerm over the entry ids of sample s's child.
  std::uint64_t SampleHash(int s) {
    const SampledAssociation& sample = samples_[s];
    const JointProblem::Parent& parent = problem_.parents[sample.parent];
    std::uint64_t hash = PassThroughHash(sample.parent);
    for (std::size_t i = 0; i < parent.rows.size(); ++i) {
      const int g = sample.gamma[i];
      const int e = parent.rows[i];
      if (g == 0) hash += entry_id_term_[e];
      if (g > 0) hash += detection_.IdTermOf(e, g - 1);
    }
    return hash;
  }

  /// The sum of IdTerm over parent h's entries outside the FOV (they pass through).
  std::uint64_t PassThroughHash(int h) {
    ListPassThrough(h);
    return pass_through_[h].hash;
  }

  /// Parent h's entries outside the FOV, in the order of its entries (id order).
  std::span<const ChildEntry> PassThrough(int h) {
    ListPassThrough(h);
    const PassThroughPart& part = pass_through_[h];
    return std::span<const ChildEntry>(pass_through_entries_).subspan(part.begin, part.size);
  }

  void ListPassThrough(int h) {
    PassThroughPart& part = pass_through_[h];
    if (part.listed) return;
    const JointProblem::Parent& parent = problem_.parents[h];
    part.begin = pass_through_entries_.size();
    std::size_t r = 0;
    for (const TrackPtr& t : *parent.tracks) {
      if (r < static_cast<std::size_t>(parent.in_fov_rows) &&
          problem_.entries[parent.rows[r]] == t) {
        ++r;  // an in-FOV row: its sample decides
      } else {
        pass_through_entries_.push_back(ChildEntry{t->id, &t});
        part.hash += IdTerm(t->id);
      }
    }
    part.size = pass_through_entries_.size() - part.begin;
    part.listed = true;
  }

  /// Whether the children of samples a and b hold the same entry ids. Distinct samples of one
  /// parent never do: a row whose values differ drops its entry, keeps it or replaces it by a
  /// detection child, each with an id no other row holds.
  bool SameIds(int a, int b) {
    if (samples_[a].parent == samples_[b].parent) return false;
    Gather(a, scratch_a_, assigned_);
    Gather(b, scratch_b_, assigned_);
    return std::equal(scratch_a_.begin(), scratch_a_.end(), scratch_b_.begin(), scratch_b_.end(),
                      [](const ChildEntry& x, const ChildEntry& y) { return x.id == y.id; });
  }

  const JointProblem& problem_;
  std::span<const SampledAssociation> samples_;
  DetectionChildren& detection_;
  std::vector<std::uint64_t> entry_id_;
  std::vector<std::uint64_t> entry_id_term_;  ///< IdTerm of entry_id_
  /// A parent's pass-through entries: pass_through_entries_[begin, begin + size) and their hash.
  struct PassThroughPart {
    std::size_t begin = 0;
    std::size_t size = 0;
    std::uint64_t hash = 0;
    bool listed = false;
  };
  std::vector<PassThroughPart> pass_through_;
  std::vector<ChildEntry> pass_through_entries_;
  std::vector<Child> children_;
  std::vector<int> table_;  ///< the storage of slots_
  HashSlots slots_{table_};
  std::vector<ChildEntry> kept_, detected_, scratch_a_, scratch_b_;
  std::vector<int> assigned_;
};

}  // namespace

UpdateResult BuildPosterior(const JointProblem& problem,
                            std::span<const SampledAssociation> samples, const Pose& x,
                            std::span<const Measurement> measurements,
                            const MeasurementSetup& setup, const UpdateSettings& settings,
                            std::uint64_t& next_id) {
  const int m = problem.measurements;
  DetectionChildren detection(problem, x, measurements, setup, next_id);
  ChildIndex index(problem, samples, detection);
  std::vector<double> all_log_w;
  all_log_w.reserve(samples.size());
  // Children are merged by their id sets; their tracks are made only for those kept.
  for (int s = 0; s < static_cast<int>(samples.size()); ++s) {
    all_log_w.push_back(samples[s].log_weight);
    index.Add(s);
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
  std::vector<Child>& children = index.children();
  if (children.empty()) return result;
  Truncate(children, settings);
  result.hypotheses.reserve(children.size());
  std::vector<ChildEntry> entries;
  std::vector<int> assigned;
  for (const Child& c : children) {
    index.Gather(c.sample, entries, assigned);
    const double w = std::exp(c.log_weight);
    for (int j : assigned) result.measurement_assigned[j] += w;
    TrackSet tracks;
    tracks.reserve(entries.size());
    for (const ChildEntry& t : entries) {
      tracks.push_back(t.track != nullptr ? *t.track : detection.TrackOf(t.entry, t.measurement));
    }
    result.hypotheses.push_back(
        Hypothesis{std::make_shared<const TrackSet>(std::move(tracks)), c.log_weight});
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
  const SampledAssociations sampled = SampleAssociations(problem, settings, rng);
  UpdateResult result =
      BuildPosterior(problem, sampled.samples, x, measurements, at_pose, settings, next_id);
  if (result.hypotheses.empty()) {
    result.hypotheses.assign(prior.begin(), prior.end());
    result.log_normaliser = kNegInf;
  }
  return result;
}

}  // namespace phdslam::glmb
