// The information-reduction factor (docs/algorithms/pcrb.md section 4): the fraction of a
// detection's Fisher information that survives missed detections and Poisson clutter, for a
// range-bearing detection in the whitened measurement space, in the manner of Niu, Willett and
// Bar-Shalom and of Hernandez, Farina and Ristic.
//
// In whitened coordinates (unit noise covariance) the set of measurements near the true
// prediction is the detection, with probability pD, drawn from N(0, I), and Poisson clutter of
// mean beta pi g^2 uniform in the gate disc of radius g (beta: clutter per unit whitened area).
// The score of the set with respect to the prediction, at the truth, is
//
//   s = pD sum_j N(z_j) z_j / ((1 - pD) beta + pD sum_j N(z_j)),
//
// (s = z_d for a detection outside the disc, which only the landmark explains), and the factor is
// q = E[|s|^2] / 2 (the information is q I by symmetry). Without clutter q = pD exactly. With
// clutter the expectation is a Monte Carlo integral over `samples` draws of the given stream.
#pragma once

#include <cstdint>

namespace phdslam::reference::pcrb {

struct ReductionSettings {
  double detection_probability = 1.0;  ///< pD in (0, 1]
  double clutter_per_area = 0.0;       ///< beta >= 0, clutter per unit whitened area
  double gate_sigma = 5.0;             ///< g > 0, the disc's radius in standard deviations
  int samples = 100000;                ///< Monte Carlo draws (clutter only)
};

/// The factor q in (0, pD]; throws std::invalid_argument naming the setting that is out of range.
double InformationReductionFactor(const ReductionSettings& settings, std::uint64_t stream_seed);

}  // namespace phdslam::reference::pcrb
