// The options of the two bounds (docs/algorithms/pcrb.md section 5) and their parameter table.
#pragma once

#include "src/core/parameter_table.h"

namespace phdslam::reference::pcrb {

/// How missed detections and clutter enter the bound.
enum class DetectionModel {
  /// The detections the simulator produced for the run (its origin labels), each with the
  /// clutter's information-reduction factor at pD = 1; averaged over seeds by the tables. The
  /// default: the tighter of the two, the one to quote.
  kConditioned,
  /// Every landmark inside the true field of view is a potential detection with its information
  /// scaled by the information-reduction factor q(pD, clutter); the same for every seed.
  kIrf,
};

struct PcrbParams {
  DetectionModel detection_model = DetectionModel::kConditioned;
  double gate_sigma = 5.0;   ///< radius of the clutter disc of the reduction factor (std devs)
  int irf_samples = 100000;  ///< Monte Carlo draws of the reduction factor (with clutter only)
};

/// detection_model ("conditioned" | "irf"), gate_sigma (> 0), irf_samples (>= 1000).
const params::ParameterTable<PcrbParams>& PcrbParamsTable();

}  // namespace phdslam::reference::pcrb
