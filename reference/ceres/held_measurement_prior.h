// The measurements taken from held poses of the incremental solve, as a fixed Gaussian prior on
// their landmarks (README.md, "Incremental solve"). A held pose is a constant, so each of its
// range-bearing factors depends on its landmark alone; the factors of a landmark are linearised
// once, when their pose becomes held, at the landmark's estimate of that moment, and summed in
// information form:
//   Lambda += w J^T J,   b += w J^T (J m0 - r0),   J = W Hm(x, m0), r0 = W e(x, m0),
// with W the measurement whitening and w the robust loss's weight rho'(|r0|^2) at m0 (1 for the
// squared loss; a gross outlier folds in with a weight near 0). The prior factor is
// r = U (m - Lambda^-1 b), U^T U = Lambda: the sum of the linearised factors up to a constant.
// So a chunk solve evaluates the measurements of its free poses and one prior per landmark, and
// its cost no longer grows with the measurements of the held past.
#pragma once

#include <ceres/ceres.h>

#include <vector>

#include "datasets/scenario.h"
#include "reference/ceres/landmark_association.h"
#include "src/core/types.h"

namespace phdslam::reference {

/// The folded measurements of the held steps [0, folded()) per landmark.
class HeldMeasurementPriors {
 public:
  /// `loss` (may be null: squared loss) weighs each measurement as it is folded; not owned.
  HeldMeasurementPriors(const datasets::Scenario& scenario, const ceres::LossFunction* loss);

  /// Folds the associated measurements of steps [folded(), end) at `poses` and the current
  /// `landmarks`. Steps already folded are not revisited. Throws std::invalid_argument when the
  /// association is shorter than `end` or a step's labels do not match its measurements.
  void FoldUntil(std::size_t end, const Association& association, const std::vector<Pose>& poses,
                 const std::vector<Landmark>& landmarks);

  [[nodiscard]] std::size_t folded() const { return folded_; }
  /// Whether landmark i has a folded measurement.
  [[nodiscard]] bool Has(std::size_t i) const { return i < count_.size() && count_[i] > 0; }
  [[nodiscard]] const Mat2& information(std::size_t i) const { return information_[i]; }
  /// Lambda^-1 b.
  [[nodiscard]] Landmark Mean(std::size_t i) const;
  /// The prior factor r = U (m - Lambda^-1 b), U^T U = Lambda, of landmark i on its parameter
  /// block `block` (Has(i) must hold): a LinearPrior (linear_prior.h) with A = U, b = 0;
  /// nullptr when its information is not positive definite.
  [[nodiscard]] ceres::CostFunction* MakeFactor(std::size_t i, double* block) const;

 private:
  const datasets::Scenario& scenario_;
  const ceres::LossFunction* loss_;
  Mat2 whitening_;
  std::size_t folded_ = 0;
  std::vector<Mat2> information_;
  std::vector<Vec2> vector_;  ///< b
  std::vector<int> count_;
};

}  // namespace phdslam::reference
