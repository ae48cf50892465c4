#include "validation/metrics/gps_position_error.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <string>

namespace phdslam::validation {
namespace {

void CheckGpsOrder(const std::vector<datasets::GpsFix>& gps) {
  for (std::size_t i = 1; i < gps.size(); ++i) {
    if (!(gps[i].t > gps[i - 1].t)) {
      throw std::invalid_argument(
          "GPS fix " + std::to_string(i) + " at t = " + std::to_string(gps[i].t) +
          " s does not come after the previous one (t = " + std::to_string(gps[i - 1].t) + " s)");
    }
  }
}

}  // namespace

GpsErrors ComputeGpsErrors(const std::vector<double>& step_times,
                           const std::vector<Pose>& estimates,
                           const std::vector<datasets::GpsFix>& gps, double window) {
  if (step_times.size() != estimates.size()) {
    throw std::invalid_argument("ComputeGpsErrors: " + std::to_string(step_times.size()) +
                                " step times but " + std::to_string(estimates.size()) +
                                " estimates");
  }
  if (!(window >= 0.0)) {
    throw std::invalid_argument("ComputeGpsErrors: window must be >= 0, got " +
                                std::to_string(window));
  }
  CheckGpsOrder(gps);

  GpsErrors out;
  out.error_m.assign(step_times.size(), std::numeric_limits<double>::quiet_NaN());
  out.fix_index.assign(step_times.size(), -1);
  if (gps.empty()) return out;
  for (std::size_t k = 0; k < step_times.size(); ++k) {
    const double t = step_times[k];
    // First fix at or after t; the nearest fix is it or the one before it.
    const auto after = std::lower_bound(
        gps.begin(), gps.end(), t, [](const datasets::GpsFix& f, double v) { return f.t < v; });
    auto nearest = after;
    if (after == gps.end()) {
      nearest = std::prev(after);
    } else if (after != gps.begin()) {
      const auto before = std::prev(after);
      if (t - before->t <= after->t - t) nearest = before;
    }
    if (!(std::abs(nearest->t - t) <= window + kGpsTimeSlack)) continue;
    out.error_m[k] = (nearest->position - estimates[k].head<2>()).norm();
    out.fix_index[k] = static_cast<int>(std::distance(gps.begin(), nearest));
    ++out.matched;
  }
  return out;
}

std::vector<datasets::GpsFix> RemoveGpsOutliers(const std::vector<datasets::GpsFix>& gps,
                                                double max_jump, double neighbour_window) {
  if (!(max_jump > 0.0)) {
    throw std::invalid_argument("RemoveGpsOutliers: max_jump must be > 0, got " +
                                std::to_string(max_jump));
  }
  if (!(neighbour_window >= 0.0)) {
    throw std::invalid_argument("RemoveGpsOutliers: neighbour_window must be >= 0, got " +
                                std::to_string(neighbour_window));
  }
  CheckGpsOrder(gps);
  std::vector<datasets::GpsFix> kept;
  kept.reserve(gps.size());
  for (std::size_t i = 0; i < gps.size(); ++i) {
    bool spike = false;
    if (i > 0 && i + 1 < gps.size()) {
      const auto& prev = gps[i - 1];
      const auto& next = gps[i + 1];
      const bool both_near_in_time =
          gps[i].t - prev.t <= neighbour_window && next.t - gps[i].t <= neighbour_window;
      spike = both_near_in_time && (gps[i].position - prev.position).norm() > max_jump &&
              (gps[i].position - next.position).norm() > max_jump;
    }
    if (!spike) kept.push_back(gps[i]);
  }
  return kept;
}

}  // namespace phdslam::validation
