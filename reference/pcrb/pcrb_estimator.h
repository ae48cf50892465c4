// The two bounds as batch estimators of the registry (docs/algorithms/pcrb.md): Solve returns the
// true poses with the bound as their covariance, and the true landmarks that carry information
// with their 2x2 bound. The runner's evaluation turns these into the rows of a bound
// (validation/runner/evaluation/run_metrics.h): the bound where other rows hold an error.
#pragma once

#include <cstdint>
#include <string>

#include "datasets/batch_estimator.h"
#include "reference/pcrb/pcrb_params.h"

namespace phdslam::reference::pcrb {

enum class BoundKind { kFiltering, kSmoothing };

class PcrbEstimator : public datasets::BatchEstimator {
 public:
  PcrbEstimator(std::string name, BoundKind kind, const PcrbParams& params,
                std::uint64_t stream_seed)
      : name_(std::move(name)), kind_(kind), params_(params), stream_seed_(stream_seed) {}

  /// Reads the scenario's truth and origin labels; throws std::invalid_argument as Linearise.
  datasets::BatchResult Solve(const datasets::Scenario& scenario) override;

 private:
  std::string name_;
  BoundKind kind_;
  PcrbParams params_;
  std::uint64_t stream_seed_;
};

}  // namespace phdslam::reference::pcrb
