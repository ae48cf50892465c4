// Implemented by online estimators that solve an optimisation problem during the run (graph
// optimisers such as the fixed-lag smoother), so that a solve that did not converge shows in the
// run's metrics instead of passing unnoticed.
#pragma once

namespace phdslam::filters {

struct SolveCounts {
  int solves = 0;
  int unconverged = 0;  ///< solves that ended without convergence
};

class SolveCounter {
 public:
  virtual ~SolveCounter() = default;
  /// Counts over every step so far.
  [[nodiscard]] virtual SolveCounts Solves() const = 0;
};

}  // namespace phdslam::filters
