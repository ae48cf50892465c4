// Keyed random streams for common random numbers: the numbers a particle filter draws for one
// (step, particle, purpose) come from a short stream of their own, a counter-based generator keyed
// by the run's stream seed and that tag, instead of from one sequential stream. A change that
// makes a filter draw more or fewer numbers at one step (resampling at another step, say) then
// leaves every other draw of the run where it was, so two versions of a filter run on the same
// seed stay paired (ci/GATES.md, "Common random numbers").
#pragma once

#include <cstdint>

#include "src/core/draw_replay.h"
#include "src/core/random.h"

namespace phdslam {

/// Where a particle filter's draws come from.
enum class DrawStreams {
  kSequential,  ///< one RandomStream per run, consumed in order (the default)
  kKeyed,       ///< a KeyedStream per (step, particle, purpose): common random numbers
};

/// The numbers of one key: the i-th uniform is MixSeed(key + i * golden ratio), i = 1, 2, ...
/// (SplitMix64's sequence), normals by the polar method as RandomStream draws them (PolarNormals).
class KeyedStream {
 public:
  explicit KeyedStream(std::uint64_t key) : state_(key) {}

  /// Uniform on [0, 1).
  double Uniform() {
    state_ += 0x9e3779b97f4a7c15ULL;
    return static_cast<double>(MixSeed(state_) >> 11) * 0x1.0p-53;
  }

  /// Standard normal (Marsaglia polar method, one cached value, as RandomStream).
  double Normal() { return normals_.Next(*this); }

 private:
  std::uint64_t state_;
  PolarNormals normals_;
};

/// The stream of the draws tagged (step, particle, purpose) of the run with `stream_seed`.
inline KeyedStream DrawKeyStream(std::uint64_t stream_seed, int step, int particle,
                                 DrawPurpose purpose) {
  const auto tag =
      (static_cast<std::uint64_t>(particle) << 2U) | static_cast<std::uint64_t>(purpose);
  return KeyedStream(DeriveSeed(stream_seed, static_cast<std::uint64_t>(step), tag));
}

}  // namespace phdslam
