// Position error against GPS for real data (Victoria Park, docs/algorithms/metrics.md section 1.3):
// each filter step is compared with the GPS fix nearest to it in time.
#pragma once

#include <cstddef>
#include <vector>

#include "datasets/scenario.h"
#include "src/core/types.h"

namespace phdslam::validation {

struct GpsErrors {
  /// One entry per step: ||gps - estimated (x, y)|| (m), NaN where no fix is close enough.
  std::vector<double> error_m;
  std::size_t matched = 0;  ///< number of finite entries
  /// One entry per step: index into the GPS track of the matched fix, -1 where unmatched.
  std::vector<int> fix_index;
};

/// Slack on the time window (s). Victoria Park clocks tick in whole milliseconds, so a fix exactly
/// 25 ms away is matched whatever rounding the subtraction of two stamps gives. (The reference
/// evaluation compares the rounded differences of ms/1000 stamps, which keeps only some of these
/// borderline fixes: 26 of the 38 exactly-25-ms steps of Victoria Park.)
inline constexpr double kGpsTimeSlack = 1e-9;

/// For each step time, the GPS fix nearest in time (the earlier one on a tie); the step is matched
/// only when |t_gps - t_step| <= window + kGpsTimeSlack (s). GPS gaps therefore leave steps
/// unmatched. Jumps are kept, as in the reference evaluation: apply RemoveGpsOutliers first to
/// drop them.
/// `gps` must be in strictly increasing time order. Throws std::invalid_argument when the sizes
/// of step_times and estimates differ, the GPS times are not strictly increasing, or window < 0.
GpsErrors ComputeGpsErrors(const std::vector<double>& step_times,
                           const std::vector<Pose>& estimates,
                           const std::vector<datasets::GpsFix>& gps, double window = 0.025);

/// Optional cleaning of a GPS track with jumps (the Victoria Park unit was failing at times):
/// a fix is dropped when it has a fix on each side within `neighbour_window` seconds and lies
/// farther than `max_jump` metres from both of them, i.e. it is an isolated spike. Fixes at the
/// ends of the track or next to a gap are kept (nothing to judge them against). Decisions use the
/// input track only, so the result does not depend on processing order. Throws
/// std::invalid_argument when max_jump <= 0 or neighbour_window < 0.
std::vector<datasets::GpsFix> RemoveGpsOutliers(const std::vector<datasets::GpsFix>& gps,
                                                double max_jump, double neighbour_window = 2.0);

}  // namespace phdslam::validation
