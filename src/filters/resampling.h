// ESS and the stratified resampling routine of the reference code (docs/algorithms/phd-slam.md
// section 6.2-6.3).
#pragma once

#include <span>
#include <vector>

#include "src/core/random.h"

namespace phdslam::filters {

/// Normalises log-weights with log-sum-exp and returns the linear weights.
std::vector<double> NormalisedWeights(std::span<const double> log_weights);

/// ESS = 1 / sum w^2 of normalised weights.
double EffectiveSampleSize(std::span<const double> weights);

/// Vehtari's "stratified" routine as in the reference code: walks the particles in index order
/// with an accumulator of N w_i, emitting floor copies and one more copy when the accumulator
/// passes the uniform of the next output slot. `uniforms` holds N i.i.d. U[0,1) draws.
/// Returns exactly N sorted source indices.
std::vector<int> StratifiedResample(std::span<const double> weights,
                                    std::span<const double> uniforms);

}  // namespace phdslam::filters
