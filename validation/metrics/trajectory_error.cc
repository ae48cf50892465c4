#include "validation/metrics/trajectory_error.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace phdslam::validation {

PoseErrors ComputePoseErrors(const std::vector<Pose>& truth, const std::vector<Pose>& estimate) {
  if (truth.size() != estimate.size()) {
    throw std::invalid_argument("ComputePoseErrors: " + std::to_string(truth.size()) +
                                " true poses but " + std::to_string(estimate.size()) +
                                " estimates; expected one estimate per step");
  }
  PoseErrors errors;
  errors.position_m.reserve(truth.size());
  errors.heading_rad.reserve(truth.size());
  for (std::size_t k = 0; k < truth.size(); ++k) {
    if (!truth[k].allFinite() || !estimate[k].allFinite()) {
      throw std::invalid_argument("ComputePoseErrors: pose at step " + std::to_string(k) +
                                  " is not finite");
    }
    errors.position_m.push_back((truth[k].head<2>() - estimate[k].head<2>()).norm());
    errors.heading_rad.push_back(std::abs(truth[k](2) - estimate[k](2)));
  }
  return errors;
}

void RmseAccumulator::Add(double error) {
  if (!std::isfinite(error)) {
    throw std::invalid_argument("RmseAccumulator::Add: error " + std::to_string(error) +
                                " is not finite");
  }
  ++count_;
  sum_squares_ += error * error;
  const double delta = error - mean_;
  mean_ += delta / static_cast<double>(count_);
  sum_sq_deviation_ += delta * (error - mean_);
}

void RmseAccumulator::Add(const std::vector<double>& errors) {
  for (const double e : errors) Add(e);
}

std::size_t RmseAccumulator::AddSkippingNaN(const std::vector<double>& errors) {
  std::size_t added = 0;
  for (const double e : errors) {
    if (std::isnan(e)) continue;
    Add(e);
    ++added;
  }
  return added;
}

void RmseAccumulator::Merge(const RmseAccumulator& other) {
  if (other.count_ == 0) return;
  if (count_ == 0) {
    *this = other;
    return;
  }
  const double n_a = static_cast<double>(count_);
  const double n_b = static_cast<double>(other.count_);
  const double n = n_a + n_b;
  const double delta = other.mean_ - mean_;
  sum_sq_deviation_ += other.sum_sq_deviation_ + delta * delta * n_a * n_b / n;
  mean_ += delta * n_b / n;
  sum_squares_ += other.sum_squares_;
  count_ += other.count_;
}

PooledRmse RmseAccumulator::Result() const {
  PooledRmse result;
  result.count = count_;
  if (count_ == 0) {
    result.rmse = std::numeric_limits<double>::quiet_NaN();
    result.error_std = std::numeric_limits<double>::quiet_NaN();
    return result;
  }
  result.rmse = std::sqrt(sum_squares_ / static_cast<double>(count_));
  result.error_std =
      count_ > 1 ? std::sqrt(sum_sq_deviation_ / static_cast<double>(count_ - 1)) : 0.0;
  return result;
}

}  // namespace phdslam::validation
