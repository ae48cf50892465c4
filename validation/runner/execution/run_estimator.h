// Runs one estimator over one scenario and records what it produced (RunRecord).
#pragma once

#include <cstddef>
#include <functional>

#include "datasets/scenario.h"
#include "validation/runner/evaluation/run_record.h"
#include "validation/runner/registry/estimator_registry.h"

namespace phdslam::validation {

/// Builds the estimator of `entry` from `request` (whose scenario must be `scenario`) and runs it:
/// an online estimator is stepped through every scenario step, with steady_clock wall time
/// measured around each Step call only; a batch estimator solves the whole scenario once. Throws
/// whatever the estimator throws, and std::runtime_error when a batch result has the wrong
/// number of poses. `on_steps_done(n)`, when set, is called after every online step with n = 1
/// and once after a batch solve with n = the number of steps (progress reporting). With
/// `record_particles`, an online estimator's ParticleStates() are kept after every step (outside
/// the timed Step call); the record keeps none when the estimator exposes none. With
/// `record_maps`, an online estimator's map estimate means are kept after every step (outside the
/// timed Step call; RunRecord::step_maps).
/// A copy of `scenario` without its hidden parts: no origin labels and no ground truth.
datasets::Scenario WithoutTruth(const datasets::Scenario& scenario);

RunRecord RunEstimator(const EstimatorEntry& entry, const EstimatorRequest& request,
                       const datasets::Scenario& scenario,
                       const std::function<void(std::size_t)>& on_steps_done = {},
                       bool record_particles = false, bool record_maps = false);

}  // namespace phdslam::validation
