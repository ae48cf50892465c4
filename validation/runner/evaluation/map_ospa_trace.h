// The opt-in per-step map metric of steps.csv (`phdslam run --map-ospa`): OSPA of order
// kMapOspaOrder = 1 with cut-off c (default kMapOspaCutoff = 5 m, the metric of single-cluster PHD
// SLAM's paper, Lee, Clark & Salvi 2012; `--map-ospa-cutoff` or the experiment key
// map_ospa_cutoff sets it, e.g. 0.5 m for the delta-GLMB-SLAM paper) between the map estimate
// after step k and the true landmarks detected at least once in steps 0..k (by the hidden origin
// labels).
#pragma once

#include <vector>

#include "datasets/scenario.h"
#include "validation/runner/evaluation/run_record.h"

namespace phdslam::validation {

inline constexpr double kMapOspaOrder = 1.0;
inline constexpr double kMapOspaCutoff = 5.0;  ///< m

/// Per step, the map OSPA (m); empty when the record has no per-step maps (not requested, or a
/// batch estimator) or the scenario has no true map or origin labels.
/// `cutoff` (m) must be finite and > 0.
std::vector<double> MapOspaTrace(const RunRecord& record, const datasets::Scenario& scenario,
                                 double cutoff = kMapOspaCutoff);

}  // namespace phdslam::validation
