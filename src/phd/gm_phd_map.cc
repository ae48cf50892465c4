#include "src/phd/gm_phd_map.h"

#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <memory_resource>
#include <numbers>
#include <numeric>

#include "src/core/angles.h"
#include "src/core/gaussian.h"
#include "src/core/log_sum_exp.h"
#include "src/models/range_bearing_model.h"

namespace phdslam::phd {
namespace {

/// Stack bytes for the scratch lists of one GmPhdMap::Update: room for about 100 components in
/// view and 100 gated pairs before any heap allocation.
constexpr std::size_t kUpdateArenaBytes = std::size_t{32} * 1024;
/// Stack bytes for the scratch lists of one PruneAndMerge.
constexpr std::size_t kMergeArenaBytes = std::size_t{4} * 1024;

}  // namespace

void GmPhdMap::AddBirths(const Pose& pose, std::span<const Measurement> measurements,
                         const Mat2& noise_cov, const MapParams& params) {
  active_.reserve(active_.size() + measurements.size());
  for (const Measurement& z : measurements) {
    const models::BirthGaussian birth = models::BirthFromMeasurement(pose, z, noise_cov);
    active_.push_back({birth.mean, birth.cov, params.birth_log_weight});
  }
}

PhdUpdateResult GmPhdMap::Update(const Pose& pose, std::span<const Measurement> measurements,
                                 const models::SensorModel& sensor, const MapParams& params) {
  PhdUpdateResult result;
  const int num_z = static_cast<int>(measurements.size());
  if (num_z == 0) return result;

  const double log_clutter = std::log(sensor.ClutterIntensity());
  const double log_two_pi = std::log(2.0 * std::numbers::pi);

  // Per-component predicted measurement and innovation covariance; the gain, the updated
  // covariance and the log-normaliser only for components that gate a measurement.
  // What the gating loop reads comes first, in one 64-byte cache line.
  struct Predicted {
    Measurement z_hat;
    Mat2 s_inv;
    double range_window;  // pre-gate on the range innovation (FirstCoordinateGateHalfWidth)
    bool gated = false;   // gain, cov_post and log_norm are set
    int index;
    double log_miss;  // log(1 - pD)
    double log_pd;
    double log_weight;  // eta, before this update
    Mat2 ph;            // P Hm^T
    Mat2 s;
    Mat2 gain;
    Mat2 cov_post;
    double log_norm;  // log pD + eta - log 2 pi - 1/2 log det S
  };
  // The scratch lists of this update live in a stack arena (the heap only beyond it).
  std::array<std::byte, kUpdateArenaBytes> arena_bytes;  // uninitialised: the arena writes it
  std::pmr::monotonic_buffer_resource arena(arena_bytes.data(), arena_bytes.size());
  std::pmr::vector<Predicted> predicted(&arena);
  predicted.reserve(active_.size());
  // The missed-detection mass enters the likelihood only when the reference omission is off.
  const bool needs_missed_mass = !params.reference_omit_missed_detection_mass;
  double missed_mass = 0.0;
  const models::FovView fov(sensor, pose);
  models::LogDetectionTerms log_pd;
  for (int i = 0; i < static_cast<int>(active_.size()); ++i) {
    const GaussianComponent& c = active_[i];
    const double pd = fov.DetectionProbability(c.mean);
    if (pd <= 0.0) continue;
    if (needs_missed_mass) missed_mass += pd * std::exp(c.log_weight);
    log_pd.Set(pd);
    const auto [z_hat, j] = models::PredictWithJacobians(pose, c.mean);
    const Mat2 ph = c.cov * j.hm.transpose();
    Mat2 s = j.hm * ph + sensor.noise_cov;
    Symmetrize(s);
    Predicted& pc = predicted.emplace_back();
    pc.index = i;
    pc.log_miss = log_pd.log_miss();
    pc.log_pd = log_pd.log_pd();
    pc.log_weight = c.log_weight;
    pc.z_hat = z_hat;
    pc.range_window = FirstCoordinateGateHalfWidth(s, params.gate_threshold);
    pc.ph = ph;
    pc.s = s;
    pc.s_inv = s.inverse();
  }
  const auto complete = [&](Predicted& pc) {
    pc.gain = pc.ph * pc.s_inv;
    pc.cov_post = active_[pc.index].cov - pc.gain * pc.s * pc.gain.transpose();
    Symmetrize(pc.cov_post);
    pc.log_norm = pc.log_pd + pc.log_weight - log_two_pi - 0.5 * std::log(pc.s.determinant());
    pc.gated = true;
  };

  // Gated detection terms l_ij, grouped by measurement (one flat list with offsets).
  struct Detection {
    int component;  // index into `predicted`
    double log_gain;
    Vec2 innovation;
    double nis;  // nu' S^-1 nu
  };
  std::pmr::vector<Detection> detections(&arena);
  std::pmr::vector<int> first(num_z + 1, 0, &arena);
  detections.reserve(predicted.size() * 2);
  result.ungated.reserve(num_z);
  for (int j = 0; j < num_z; ++j) {
    first[j] = static_cast<int>(detections.size());
    for (int p = 0; p < static_cast<int>(predicted.size()); ++p) {
      Predicted& pc = predicted[p];
      if (std::abs(measurements[j](0) - pc.z_hat(0)) > pc.range_window) continue;
      Vec2 nu = measurements[j] - pc.z_hat;
      nu(1) = WrapAngle(nu(1));
      const double d2 = nu.dot(pc.s_inv * nu);
      if (d2 < params.gate_threshold) {
        if (!pc.gated) complete(pc);
        detections.push_back({p, pc.log_norm - 0.5 * d2, nu, d2});
      }
    }
  }
  first[num_z] = static_cast<int>(detections.size());

  // Misdetected copies of the existing components (pD = 0 components unchanged), then the
  // detected components, ordered by measurement and then by component.
  const std::size_t old_size = active_.size();
  active_.reserve(old_size + detections.size());
  for (const Predicted& pc : predicted) {
    active_[pc.index].log_weight += pc.log_miss;
  }
  for (int j = 0; j < num_z; ++j) {
    if (first[j] == first[j + 1]) {
      result.log_likelihood += log_clutter;
      result.ungated.push_back(j);
      continue;
    }
    double c_j = log_clutter;
    int best = -1;
    for (int d = first[j]; d < first[j + 1]; ++d) {
      c_j = LogAddExp(c_j, detections[d].log_gain);
      if (best < 0 || detections[d].log_gain > detections[best].log_gain) best = d;
    }
    result.log_likelihood += c_j;
    if (detections[best].log_gain > log_clutter) {
      result.nis_sum += detections[best].nis;
      ++result.nis_count;
    }
    for (int d = first[j]; d < first[j + 1]; ++d) {
      const Predicted& pc = predicted[detections[d].component];
      // The prior mean: the misdetected copy at pc.index kept it, only its weight changed.
      const Landmark prior_mean = active_[pc.index].mean;
      active_.push_back({prior_mean + pc.gain * detections[d].innovation, pc.cov_post,
                         detections[d].log_gain - c_j});
    }
  }
  if (!params.reference_omit_missed_detection_mass) result.log_likelihood -= missed_mass;
  if (!params.reference_births_from_ungated_only) {
    result.ungated.resize(num_z);
    for (int j = 0; j < num_z; ++j) result.ungated[j] = j;
  }
  return result;
}

namespace {

/// The positions of `components` in the order of std::stable_sort by descending log-weight, into
/// `order`. Short lists (every active list of the synthetic scenario) are sorted by insertion on
/// (weight, position) pairs, which gives the same order without stable_sort's buffer.
void OrderByWeightDescending(const std::vector<GaussianComponent>& components,
                             std::pmr::vector<int>& order) {
  order.resize(components.size());
  std::iota(order.begin(), order.end(), 0);
  constexpr std::size_t kInsertionSortMax = 32;
  if (order.size() > kInsertionSortMax) {
    std::stable_sort(order.begin(), order.end(), [&components](int a, int b) {
      return components[a].log_weight > components[b].log_weight;
    });
    return;
  }
  struct Keyed {
    double log_weight;
    int position;
  };
  std::array<Keyed, kInsertionSortMax> keyed;
  for (std::size_t i = 0; i < order.size(); ++i) {
    const Keyed moving{components[i].log_weight, static_cast<int>(i)};
    std::size_t j = i;
    for (; j > 0 && moving.log_weight > keyed[j - 1].log_weight; --j) keyed[j] = keyed[j - 1];
    keyed[j] = moving;
  }
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = keyed[i].position;
}

}  // namespace

std::vector<GaussianComponent> PruneAndMerge(std::vector<GaussianComponent> components,
                                             const MapParams& params) {
  if (components.empty()) return components;
  std::array<std::byte, kMergeArenaBytes> arena_bytes;  // uninitialised: the arena writes it
  std::pmr::monotonic_buffer_resource arena(arena_bytes.data(), arena_bytes.size());
  // 1. Stable sort by log-weight, descending (the order of positions; components stay in place).
  std::pmr::vector<int> order(&arena);
  OrderByWeightDescending(components, order);
  const auto sorted = [&](std::size_t k) -> const GaussianComponent& {
    return components[order[k]];
  };
  // 2. Prune: keep the leading components above the threshold, and always the first.
  std::size_t kept = 1;
  while (kept < components.size() && sorted(kept).log_weight >= params.prune_log_weight) {
    ++kept;
  }

  // 3. Greedy merge in descending order.
  std::vector<GaussianComponent> merged;
  merged.reserve(kept);
  std::pmr::vector<char> used(kept, 0, &arena);
  // The x coordinates of the kept components in sorted order, contiguous for the pre-gate scan.
  std::pmr::vector<double> sorted_x(kept, 0.0, &arena);
  for (std::size_t k = 0; k < kept; ++k) sorted_x[k] = sorted(k).mean(0);
  std::pmr::vector<int> members(&arena);
  std::pmr::vector<double> member_log_w(&arena);
  std::pmr::vector<double> member_w(&arena);
  constexpr std::size_t kTypicalMembers = 8;
  members.reserve(kTypicalMembers);
  member_log_w.reserve(kTypicalMembers);
  member_w.reserve(kTypicalMembers);
  for (std::size_t i = 0; i < kept; ++i) {
    if (used[i]) continue;
    const GaussianComponent& lead = sorted(i);
    members.clear();
    member_log_w.clear();
    members.push_back(static_cast<int>(i));
    member_log_w.push_back(lead.log_weight);
    used[i] = 1;
    Mat2 lead_inv;  // lead.cov^-1, formed when the first candidate passes the pre-gate
    bool have_lead_inv = false;
    // With the leading covariance, a pre-gate on the x offset skips the far components.
    const double x_window = params.reference_merge_leading_covariance
                                ? FirstCoordinateGateHalfWidth(lead.cov, params.merge_threshold)
                                : std::numeric_limits<double>::infinity();
    const double lead_x = sorted_x[i];
    for (std::size_t j = i + 1; j < kept; ++j) {
      if (std::abs(lead_x - sorted_x[j]) > x_window) continue;
      if (!params.reference_merge_double_membership && used[j]) continue;
      const GaussianComponent& candidate = sorted(j);
      const Vec2 d = lead.mean - candidate.mean;
      if (params.reference_merge_leading_covariance && !have_lead_inv) {
        lead_inv = lead.cov.inverse();
        have_lead_inv = true;
      }
      const double dist = params.reference_merge_leading_covariance
                              ? d.dot(lead_inv * d)
                              : d.dot(candidate.cov.inverse() * d);
      if (dist < params.merge_threshold) {
        members.push_back(static_cast<int>(j));
        member_log_w.push_back(candidate.log_weight);
        used[j] = 1;
      }
    }
    GaussianComponent out;
    if (members.size() == 1) {
      out = lead;
    } else {
      out.log_weight = LogSumExp(member_log_w);
      member_w.clear();
      for (const double log_w : member_log_w) member_w.push_back(std::exp(log_w - out.log_weight));
      Vec2 mean = Vec2::Zero();
      for (std::size_t m = 0; m < members.size(); ++m) {
        mean += member_w[m] * sorted(members[m]).mean;
      }
      Mat2 cov = Mat2::Zero();
      for (std::size_t m = 0; m < members.size(); ++m) {
        const GaussianComponent& c = sorted(members[m]);
        const Vec2 dm = mean - c.mean;
        cov += member_w[m] * (c.cov + dm * dm.transpose());
      }
      Symmetrize(cov);
      out.mean = mean;
      out.cov = cov;
    }
    // 4. Spread kill, singletons included.
    if (params.reference_spread_kill && out.cov.trace() > params.merge_threshold) {
      out.log_weight = params.spread_kill_log_weight;
    }
    merged.push_back(out);
  }
  return merged;
}

GmPhdMap::ChunkPtr GmPhdMap::MakeChunk(std::vector<GaussianComponent> components) {
  auto chunk = std::make_shared<PassiveChunk>();
  chunk->lo = components.front().mean;
  chunk->hi = chunk->lo;
  for (const GaussianComponent& c : components) {
    chunk->lo = chunk->lo.cwiseMin(c.mean);
    chunk->hi = chunk->hi.cwiseMax(c.mean);
  }
  chunk->components = std::move(components);
  return chunk;
}

GmPhdMap::BlockPtr GmPhdMap::MakeBlock(std::vector<ChunkPtr> chunks) {
  auto block = std::make_shared<PassiveBlock>();
  block->lo = chunks.front()->lo;
  block->hi = chunks.front()->hi;
  for (const ChunkPtr& chunk : chunks) {
    block->lo = block->lo.cwiseMin(chunk->lo);
    block->hi = block->hi.cwiseMax(chunk->hi);
  }
  block->chunks = std::move(chunks);
  return block;
}

void GmPhdMap::AppendPassive(std::vector<GaussianComponent>& components) {
  if (components.empty()) return;
  passive_size_ += components.size();
  std::vector<ChunkPtr> chunks;
  if (!passive_.empty() &&
      (passive_.back()->chunks.size() < kChunksPerBlock ||
       passive_.back()->chunks.back()->components.size() < kPassiveChunkSize)) {
    chunks = passive_.back()->chunks;
    passive_.pop_back();
  }
  std::vector<GaussianComponent> run;
  if (!chunks.empty() && chunks.back()->components.size() < kPassiveChunkSize) {
    run = chunks.back()->components;
    chunks.pop_back();
  }
  std::size_t next = 0;
  while (next < components.size()) {
    while (next < components.size() && run.size() < kPassiveChunkSize) {
      run.push_back(std::move(components[next++]));
    }
    chunks.push_back(MakeChunk(std::move(run)));
    run = {};
  }
  for (std::size_t first = 0; first < chunks.size(); first += kChunksPerBlock) {
    const std::size_t last = std::min(first + kChunksPerBlock, chunks.size());
    passive_.push_back(MakeBlock(std::vector<ChunkPtr>(chunks.begin() + static_cast<long>(first),
                                                       chunks.begin() + static_cast<long>(last))));
  }
}

void GmPhdMap::SetPassive(std::vector<GaussianComponent> components) {
  passive_.clear();
  passive_size_ = 0;
  AppendPassive(components);
}

std::vector<GaussianComponent> GmPhdMap::passive() const {
  std::vector<GaussianComponent> out;
  out.reserve(passive_size_);
  for (const BlockPtr& block : passive_) {
    for (const ChunkPtr& chunk : block->chunks) {
      out.insert(out.end(), chunk->components.begin(), chunk->components.end());
    }
  }
  return out;
}

void GmPhdMap::CountBytes(ByteTally& tally) const {
  tally.AddVector(active_);
  tally.AddVector(passive_);
  for (const BlockPtr& block : passive_) {
    tally.Add(block.get(), sizeof(PassiveBlock));
    tally.AddVector(block->chunks);
    for (const ChunkPtr& chunk : block->chunks) {
      tally.Add(chunk.get(), sizeof(PassiveChunk));
      tally.AddVector(chunk->components);
    }
  }
}

GmPhdMap::ChunkPtr GmPhdMap::SplitChunk(const ChunkPtr& chunk, const models::FovView& fov,
                                        std::vector<GaussianComponent>& entering) {
  if (fov.BoxSurelyOutsideEnlargedFov(chunk->lo, chunk->hi)) return chunk;
  const auto& components = chunk->components;
  std::size_t first_in = 0;
  while (first_in < components.size() && !fov.InEnlargedFov(components[first_in].mean)) {
    ++first_in;
  }
  if (first_in == components.size()) return chunk;
  std::vector<GaussianComponent> rest(components.begin(),
                                      components.begin() + static_cast<long>(first_in));
  for (std::size_t c = first_in; c < components.size(); ++c) {
    if (fov.InEnlargedFov(components[c].mean)) {
      entering.push_back(components[c]);
      --passive_size_;
    } else {
      rest.push_back(components[c]);
    }
  }
  return rest.empty() ? nullptr : MakeChunk(std::move(rest));
}

void GmPhdMap::Reduce(const Pose& pose, const models::SensorModel& sensor,
                      const MapParams& params) {
  std::vector<GaussianComponent> merged = PruneAndMerge(std::move(active_), params);
  // 5. Active/passive split at the sampled pose with the enlarged FOV; 6. resulting order.
  const models::FovView fov(sensor, pose);
  std::vector<GaussianComponent> leaving;
  std::size_t kept_active = 0;
  for (std::size_t i = 0; i < merged.size(); ++i) {
    if (fov.InEnlargedFov(merged[i].mean)) {
      if (kept_active != i) merged[kept_active] = std::move(merged[i]);
      ++kept_active;
    } else if (merged[i].log_weight > params.prune_log_weight) {
      leaving.push_back(std::move(merged[i]));
    }
  }
  merged.resize(kept_active);
  // Passive components re-entering the enlarged FOV move back; the rest keep their order. Blocks
  // and chunks beyond the enlarged range, and those none of whose components re-enter, stay
  // shared.
  std::size_t kept_blocks = 0;
  std::vector<ChunkPtr> chunks;
  for (std::size_t i = 0; i < passive_.size(); ++i) {
    BlockPtr block = std::move(passive_[i]);
    if (!fov.BoxSurelyOutsideEnlargedFov(block->lo, block->hi)) {
      chunks.clear();
      bool changed = false;
      for (const ChunkPtr& chunk : block->chunks) {
        ChunkPtr next = SplitChunk(chunk, fov, merged);
        changed = changed || next != chunk;
        if (next) chunks.push_back(std::move(next));
      }
      if (changed) block = chunks.empty() ? nullptr : MakeBlock(chunks);
    }
    if (block) passive_[kept_blocks++] = std::move(block);
  }
  passive_.resize(kept_blocks);
  AppendPassive(leaving);
  active_ = std::move(merged);
}

std::vector<GaussianComponent> GmPhdMap::Estimate(double log_weight_threshold) const {
  std::vector<GaussianComponent> out;
  for (const GaussianComponent& c : active_) {
    if (c.log_weight > log_weight_threshold) out.push_back(c);
  }
  for (const BlockPtr& block : passive_) {
    for (const ChunkPtr& chunk : block->chunks) {
      for (const GaussianComponent& c : chunk->components) {
        if (c.log_weight > log_weight_threshold) out.push_back(c);
      }
    }
  }
  return out;
}

}  // namespace phdslam::phd
