// Registry entries of the Ceres batch smoother (built only when phdslam_reference_ceres exists).
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

#include "oracle/oracle_rbpf.h"
#include "reference/ceres/batch_smoother.h"
#include "reference/ceres/filter_association.h"
#include "reference/ceres/fixed_lag_smoother.h"
#include "reference/ceres/smoother_params_json.h"
#include "reference/ceres/start_trajectory.h"
#include "reference/ceres/window_params_json.h"
#include "src/filters/phd_slam_family.h"
#include "src/filters/phd_slam_params_json.h"
#include "validation/runner/registry/estimator_registry.h"

namespace phdslam::validation {
namespace {

// `run_steps` (r.steps, 0 when not known) bounds incremental_chunk_steps given as an override:
// a chunk longer than the run would leave a single solve at its end (the default chunk is
// simply the whole of a shorter run).
void RequireChunkWithinRun(const EstimatorRequest& r, const reference::SmootherOptions& o) {
  if (r.steps == 0 || o.initialisation != reference::SmootherInitialisation::kIncremental ||
      !r.overrides.contains("incremental_chunk_steps") ||
      static_cast<std::size_t>(o.incremental_chunk_steps) <= r.steps) {
    return;
  }
  throw std::invalid_argument("estimator '" + r.name + "': parameter 'incremental_chunk_steps': " +
                              std::to_string(o.incremental_chunk_steps) +
                              " is longer than the run (" + std::to_string(r.steps) +
                              " steps): the graph would be solved only once, at its end");
}

// The association mode is fixed by the name: the table accepts an `association` override only
// when it equals `mode` (so that resolved parameters can be fed back as overrides).
reference::SmootherOptions ResolveSmoother(const EstimatorRequest& r,
                                           reference::AssociationMode mode) {
  RequireSingleParticle(r);
  reference::SmootherOptions defaults;
  defaults.association = mode;
  reference::SmootherOptions o =
      ResolveParameters(r, reference::SmootherOptionsTable(), std::move(defaults));
  // A scenario's default start_path (scenario_defaults.cc) belongs to its default start: when
  // start_from is set back to dead-reckoning and start_path is not given, no path is taken. A
  // start_path given with dead-reckoning is still an error naming it.
  if (o.start_from == reference::StartTrajectory::kDeadReckoning &&
      !r.overrides.contains("start_path")) {
    o.start_path = reference::StartPath::kEstimate;
  }
  // Likewise a scenario's default front_end=window belongs to the dead-reckoning start: a start
  // trajectory given without front_end takes the pass.
  if (o.start_from != reference::StartTrajectory::kDeadReckoning &&
      !r.overrides.contains("front_end")) {
    o.front_end = reference::OwnFrontEnd::kPass;
  }
  try {
    o.Validate();
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("estimator '" + r.name + "': " + e.what());
  }
  if (mode == reference::AssociationMode::kKnown) RequireKnownOrigins(r);
  RequireChunkWithinRun(r, o);
  return o;
}

// `run_steps` (0 when not known yet) bounds window_length: a value given as an override longer
// than the run is an error naming it, while the default is shortened to a shorter run.
reference::WindowParams ResolveWindow(const EstimatorRequest& r, bool known,
                                      std::size_t run_steps) {
  RequireSingleParticle(r);
  reference::WindowParams defaults;
  defaults.known_association = known;
  reference::WindowParams p = ResolveParameters(r, reference::WindowParamsTable(), defaults);
  if (run_steps > 0 && !r.overrides.contains("window_length") &&
      static_cast<std::size_t>(p.window_length) > run_steps) {
    p.window_length = static_cast<int>(run_steps);
  }
  try {
    p.Validate(run_steps);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("estimator '" + r.name + "': " + e.what());
  }
  if (known) RequireKnownOrigins(r);
  return p;
}

// The fixed-lag smoother with its own association and its defaults on the run's scenario, as the
// estimator `window` is built: a smoother's front end.
std::unique_ptr<reference::FixedLagSmoother> OwnAssociationWindow(const EstimatorRequest& r) {
  EstimatorRequest window = r;
  window.name = "window";
  window.overrides = nlohmann::json::object();
  window.particles = 1;
  return std::make_unique<reference::FixedLagSmoother>(RequireContext(r),
                                                       ResolveWindow(window, false, r.steps),
                                                       std::vector<std::vector<int>>{}, r.steps);
}

EstimatorEntry SmootherEntry(const std::string& name, reference::AssociationMode mode,
                             const std::string& description) {
  EstimatorEntry e;
  e.name = name;
  e.description = description;
  e.batch = true;
  e.bounded_by_run_length = true;  // incremental_chunk_steps
  e.reads_truth = mode == reference::AssociationMode::kKnown;
  e.parameters = reference::SmootherOptionsTable().Descriptions();
  e.resolved_parameters = [mode](const EstimatorRequest& r) {
    return reference::ToJson(ResolveSmoother(r, mode));
  };
  e.make_batch = [mode](const EstimatorRequest& r) -> std::unique_ptr<datasets::BatchEstimator> {
    reference::SmootherOptions o = ResolveSmoother(r, mode);
    const bool from_phd3 = o.start_from == reference::StartTrajectory::kPhd3;
    if (o.start_from == reference::StartTrajectory::kWindow) {
      return std::make_unique<reference::SmoothFromEstimatorStart>(OwnAssociationWindow(r),
                                                                   std::move(o));
    }
    if ((mode == reference::AssociationMode::kFilter &&
         o.filter_front_end == reference::FilterFrontEnd::kWindow) ||
        (mode == reference::AssociationMode::kUnknown &&
         o.front_end == reference::OwnFrontEnd::kWindow)) {
      return std::make_unique<reference::FilterThenSmooth>(OwnAssociationWindow(r), std::move(o));
    }
    if (mode != reference::AssociationMode::kFilter && !from_phd3) {
      return std::make_unique<reference::BatchSmoother>(std::move(o));
    }
    // A PHD-SLAM 3.0 run with the paper's parameters, drawn from this run's own stream: its
    // association (smoother-filter, N = 1) or only its trajectory (start_from: phd3).
    EstimatorRequest phd3 = r;
    phd3.name = "phd3";
    phd3.overrides = nlohmann::json::object();
    phd3.particles = from_phd3 ? o.start_particles : 1;
    const filters::PhdSlamParams params = ResolveParameters(phd3, filters::PhdSlamParamsTable());
    auto filter = filters::MakePhdSlam("phd3", RequireContext(r), params, r.stream_seed);
    if (from_phd3) {
      return std::make_unique<reference::SmoothFromEstimatorStart>(std::move(filter), std::move(o));
    }
    return std::make_unique<reference::FilterThenSmooth>(std::move(filter), std::move(o));
  };
  return e;
}

// The fixed-lag smoother: `window-known` reads the origin labels as the oracle does; `window`
// sees only the public context.
EstimatorEntry WindowEntry(const std::string& name, bool known, const std::string& description) {
  EstimatorEntry e;
  e.name = name;
  e.description = description;
  e.reads_truth = known;
  e.bounded_by_run_length = true;  // window_length, solve_every
  e.parameters = reference::WindowParamsTable().Descriptions();
  // The run's length, when the plan knows it (--steps), checks the overrides now, before any
  // run starts; the recorded parameters are those without it (the default window is shortened
  // only when the run is built).
  e.resolved_parameters = [known](const EstimatorRequest& r) {
    if (r.steps > 0) (void)ResolveWindow(r, known, r.steps);
    return reference::ToJson(ResolveWindow(r, known, 0));
  };
  if (known) {
    e.make_online_with_truth =
        [](const EstimatorRequest& r,
           const datasets::Scenario& with_truth) -> std::unique_ptr<filters::OnlineEstimator> {
      const reference::WindowParams p = ResolveWindow(r, true, with_truth.steps.size());
      return std::make_unique<reference::FixedLagSmoother>(with_truth.PublicContext(), p,
                                                           oracle::ScenarioOrigins(with_truth),
                                                           with_truth.steps.size());
    };
  } else {
    e.make_online = [](const EstimatorRequest& r) -> std::unique_ptr<filters::OnlineEstimator> {
      const reference::WindowParams p = ResolveWindow(r, false, r.steps);
      const filters::EstimatorContext& context = RequireContext(r);
      return std::make_unique<reference::FixedLagSmoother>(
          context, p, std::vector<std::vector<int>>{}, r.steps);
    };
  }
  return e;
}

}  // namespace

std::vector<EstimatorEntry> CeresEstimators() {
  return {SmootherEntry("smoother-known", reference::AssociationMode::kKnown,
                        "Ceres batch smoother (full SLAM graph) with the known association "
                        "(reads the hidden origin labels): the graph-optimisation lower bound. "
                        "Graph solved from dead reckoning (initialisation=batch, default) or "
                        "built in time order and solved as it grows "
                        "(initialisation=incremental, the default on mrclam), or from the "
                        "trajectory of a PHD-SLAM 3.0 "
                        "run on the same seed (start_from=phd3)"),
          SmootherEntry("smoother-filter", reference::AssociationMode::kFilter,
                        "Ceres batch smoother on the data association of a PHD-SLAM 3.0 run "
                        "(N = 1, same seed; filter_front_end=phd3, default) or on the labels of "
                        "the fixed-lag smoother's own association (filter_front_end=window); "
                        "initialisation=batch|incremental as smoother-known"),
          SmootherEntry("smoother-unknown", reference::AssociationMode::kUnknown,
                        "Ceres batch smoother with its own association: each scan associated "
                        "in a sequential EKF pass from dead reckoning (initialisation=batch, "
                        "default) or with the optimised map on marginal covariances as the "
                        "graph grows (initialisation=incremental), or the fixed-lag smoother's "
                        "own labels and trajectory instead of the pass (front_end=window, the "
                        "default on victoria-park, and on mrclam with merge_position_std=0), or "
                        "with the pass started from the trajectory of a PHD-SLAM 3.0 run on the "
                        "same seed (start_from=phd3, start_particles=5; its association is not "
                        "used; start_path=best-particle-path for its best final particle's "
                        "path), robust loss, re-association in a final full solve "
                        "(reference/ceres/README.md)"),
          WindowEntry("window-known", true,
                      "Ceres fixed-lag (sliding-window) smoother with the known association "
                      "(reads the hidden origin labels): old states marginalised into a Gaussian "
                      "prior; pose = newest window pose; parameters window_length (20), "
                      "solve_every (1)"),
          WindowEntry("window", false,
                      "Ceres fixed-lag (sliding-window) smoother with its own association: gated "
                      "nearest neighbour on marginal and pose-landmark cross-covariances, "
                      "confirmed landmarks first, tentative ones confirmed after "
                      "confirm_detections (5) scans, Huber loss (Cauchy while tentative), "
                      "outliers dropped after each solve; on mrclam by default joint "
                      "compatibility (assignment=jcbb, jcbb_null_intensity=0.0035) and the "
                      "moving-object test (static_point_chi2=9.21, static_point_failures=3), "
                      "on victoria-park joint compatibility with jcbb_null_intensity=0.035 and "
                      "landmark_keep_steps=200 "
                      "(reference/ceres/README.md)")};
}

}  // namespace phdslam::validation
