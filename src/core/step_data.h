// What an estimator receives at one filter step: the public part of a scenario step.
#pragma once

#include <vector>

#include "src/core/types.h"

namespace phdslam {

struct StepData {
  /// Time stamps [t_prev, ..., t_k] (s). A single entry means no propagation at this step
  /// (docs/algorithms/models.md section 4.2).
  std::vector<double> times;
  /// controls[i] is held over [times[i], times[i+1]] (zero-order hold): size times.size() - 1.
  std::vector<Control> controls;
  /// Range-bearing measurements of this scan, bearings wrapped.
  std::vector<Measurement> measurements;
};

}  // namespace phdslam
