// Per-particle Gaussian-mixture PHD map with the active/passive split of the PHD-SLAM 3.0
// reference code (docs/algorithms/phd-slam.md section 3).
//
// Active components are those inside the FOV enlarged by the buffers at the particle's last
// sampled pose; only they are predicted into the measurement space, updated, pruned and merged.
// Passive components are kept unchanged until they re-enter the enlarged FOV.
//
// Storage: the active list is a plain vector (it is small and changes every step). The passive
// list, which holds almost the whole map, is a two-level tree of immutable parts: blocks of at
// most kChunksPerBlock chunks, chunks of at most kPassiveChunkSize components, each held by
// std::shared_ptr<const ...>. The passive order is the blocks' order, then the chunks', then the
// order within each chunk. Copying a map (resampling) copies only the block pointers, so copies
// share their passive storage; a map that changes a chunk (a component re-entering the FOV,
// components leaving it) builds a new chunk and a new block holding it, and leaves the shared ones
// untouched (copy-on-write of map parts). Blocks and chunks keep the bounding box of their
// means, which is the spatial index: the active/passive split skips the blocks, and within a
// block the chunks, that lie beyond the enlarged FOV range without reading their components, so
// its cost depends on the components near the pose, not on the size of the map.
#pragma once

#include <memory>
#include <span>
#include <vector>

#include "src/core/byte_tally.h"
#include "src/core/types.h"
#include "src/models/sensor_model.h"
#include "src/phd/gaussian_component.h"
#include "src/phd/map_params.h"

namespace phdslam::phd {

/// Result of one PHD measurement update.
struct PhdUpdateResult {
  /// Measurement part of the particle log-weight: sum_j log(lambda_c + sum_i exp(l_ij))
  /// (and -sum pD eta when the reference omission is switched off).
  double log_likelihood = 0.0;
  /// Indices of the measurements that gated with no component with pD > 0 (the next births).
  std::vector<int> ungated;
  /// NIS of the measurements the update explains best by a landmark: for each measurement whose
  /// largest detection term pD w N(z; z_hat, S) exceeds the clutter intensity, nu' S^-1 nu of that
  /// component (its S at this pose); the sum over those measurements and their count.
  double nis_sum = 0.0;
  int nis_count = 0;
};

class GmPhdMap {
 public:
  [[nodiscard]] const std::vector<GaussianComponent>& active() const { return active_; }
  /// The passive components, in order (a copy assembled from the chunks).
  [[nodiscard]] std::vector<GaussianComponent> passive() const;
  [[nodiscard]] std::size_t passive_size() const { return passive_size_; }
  [[nodiscard]] std::size_t size() const { return active_.size() + passive_size_; }

  /// Appends one birth per measurement, by the inverse model at `pose` (the pose the measurements
  /// were taken from), with covariance G R G^T and log-weight params.birth_log_weight.
  void AddBirths(const Pose& pose, std::span<const Measurement> measurements, const Mat2& noise_cov,
                 const MapParams& params);

  /// GM-PHD update (docs/algorithms/phd-slam.md section 3.2) at the sampled pose. Returns
  /// immediately with a zero increment when there are no measurements.
  PhdUpdateResult Update(const Pose& pose, std::span<const Measurement> measurements,
                         const models::SensorModel& sensor, const MapParams& params);

  /// Sort, prune, greedy merge, spread kill and active/passive split (docs/algorithms/phd-slam.md
  /// section 3.3-3.4) at `pose`.
  void Reduce(const Pose& pose, const models::SensorModel& sensor, const MapParams& params);

  /// Components (active and passive) with log-weight strictly above `log_weight_threshold`.
  [[nodiscard]] std::vector<GaussianComponent> Estimate(double log_weight_threshold) const;

  /// Replaces the active list (tests and filters that manage components themselves).
  void SetActive(std::vector<GaussianComponent> components) { active_ = std::move(components); }
  /// Replaces the passive list, cut into chunks in the given order (give spatially coherent
  /// orders, e.g. the order in which a path passes them, for the chunk boxes to be tight).
  void SetPassive(std::vector<GaussianComponent> components);

  /// Adds the heap bytes of the component storage to `tally` (shared storage counted once).
  void CountBytes(ByteTally& tally) const;

  static constexpr std::size_t kPassiveChunkSize = 64;
  static constexpr std::size_t kChunksPerBlock = 64;

 private:
  /// An immutable run of passive components with the bounding box of their means.
  struct PassiveChunk {
    std::vector<GaussianComponent> components;
    Landmark lo;
    Landmark hi;
  };
  using ChunkPtr = std::shared_ptr<const PassiveChunk>;
  /// An immutable run of chunks with the bounding box of all their means.
  struct PassiveBlock {
    std::vector<ChunkPtr> chunks;
    Landmark lo;
    Landmark hi;
  };
  using BlockPtr = std::shared_ptr<const PassiveBlock>;

  static ChunkPtr MakeChunk(std::vector<GaussianComponent> components);
  static BlockPtr MakeBlock(std::vector<ChunkPtr> chunks);
  /// Appends components after the last chunk (filling it and its block up first, by copies).
  void AppendPassive(std::vector<GaussianComponent>& components);
  /// Moves the components of `chunk` inside the enlarged FOV to `entering` (in order); returns
  /// the chunk itself when none is, else a new chunk of the rest (null when empty).
  ChunkPtr SplitChunk(const ChunkPtr& chunk, const models::FovView& fov,
                      std::vector<GaussianComponent>& entering);

  std::vector<GaussianComponent> active_;
  std::vector<BlockPtr> passive_;
  std::size_t passive_size_ = 0;
};

/// Sort, prune and greedily merge a component list as the reference code does
/// (docs/algorithms/phd-slam.md section 3.3). Exposed for unit tests and for filters that reduce
/// other mixtures.
std::vector<GaussianComponent> PruneAndMerge(std::vector<GaussianComponent> components,
                                             const MapParams& params);

}  // namespace phdslam::phd
