// Consistency checks of a Scenario, run by loaders and by consumers that accept scenarios from
// outside.
#pragma once

#include <string_view>

#include "datasets/scenario.h"

namespace phdslam::datasets {

/// Throws std::invalid_argument when the scenario is not usable. The message starts with
/// `source` and names the 0-based step index, the field and the measurement/control index, e.g.
/// "paper-synthetic seed 3: step 12: measurement 4: range is nan".
/// Checked:
///  - parameters: initial_pose, control_noise_cov, sensor (FOV range > 0, half-angle in (0, pi],
///    buffers >= 0, pd_max in [0, 1], pd_nominal in (0, 1], noise_cov, clutter_rate >= 0) and car
///    geometry finite and in range;
///  - every step: at least one time stamp, all finite and non-decreasing, within the step and
///    from the previous step's last time stamp; controls.size() == times.size() - 1; controls and
///    measurements finite; origin empty or of the measurements' size, each entry kClutter or a
///    valid index into truth.landmarks (when that is known);
///  - truth: poses empty or one per step, all finite; landmarks and GPS fixes finite.
void CheckScenario(const Scenario& scenario, std::string_view source);

}  // namespace phdslam::datasets
