// Parameters of the particle-filter skeleton (particle_filter.h).
#pragma once

#include "src/core/keyed_stream.h"
#include "src/core/types.h"

namespace phdslam::filters {

/// When resampling happens.
enum class EssThresholdKind {
  kRelative,  ///< resample when ESS <= threshold * N (synthetic: 0.2)
  kAbsolute,  ///< resample when ESS <= threshold (Victoria Park: 1)
};

/// The skeleton's own parameters (each filter maps its parameter struct onto them).
struct ParticleFilterParams {
  int particles = 1;
  bool resampling = true;
  EssThresholdKind ess_threshold_kind = EssThresholdKind::kRelative;
  double ess_threshold = 0.2;
  /// Q_n, added once per step before propagation.
  Mat3 pose_regularisation = Vec3(1e-9, 1e-9, 1e-18).asDiagonal();
  /// Copies of one resampled parent share one proposal (no effect on results).
  bool reuse_parent_proposal = true;
  /// Where the random draws come from: one sequential stream, or keyed streams per (step,
  /// particle, purpose) for common random numbers between versions of a filter.
  DrawStreams draw_streams = DrawStreams::kSequential;
};

}  // namespace phdslam::filters
