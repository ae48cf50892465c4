// An online estimator that names its own landmarks, so that a smoother can take its association
// as it is (FilterThenSmooth) instead of linking the associated means of consecutive scans.
#pragma once

#include <vector>

namespace phdslam::reference {

class LabelledAssociation {
 public:
  virtual ~LabelledAssociation() = default;
  /// Per step, per measurement: the label (>= 0) of the landmark the detection is finally kept
  /// on, or -1 (clutter, a landmark deleted since, a detection rejected after a solve).
  [[nodiscard]] virtual std::vector<std::vector<int>> FinalLabels() const = 0;
};

}  // namespace phdslam::reference
