#include "reference/ceres/window_params_json.h"

#include <string>
#include <utility>
#include <vector>

namespace phdslam::reference {

const params::ParameterTable<WindowParams>& WindowParamsTable() {
  using params::Above;
  using params::AtLeast;
  using params::Between;
  using P = WindowParams;
  using F = OdometryNoiseFloor;
  static const params::ParameterTable<P> table({
      params::Fixed(params::EnumField<P, bool>("association",
                                               [](auto& p) -> auto& { return p.known_association; },
                                               {{true, "known"}, {false, "unknown"}})
                        .Means("known (the generator's labels, window-known) or the smoother's own "
                               "association (window)"),
                    "fixed by the estimator's name (window-known, window)"),
      // Bounded below here; the run's length bounds it above when the run is built.
      params::IntField<P>(
          "window_length", [](auto& p) -> auto& { return p.window_length; }, AtLeast(1))
          .Means("poses kept in the window after each solve (at most the run's length)"),
      params::IntField<P>(
          "solve_every", [](auto& p) -> auto& { return p.solve_every; }, AtLeast(1))
          .Means("steps between two solves of the window"),
      params::IntField<P>(
          "max_iterations", [](auto& p) -> auto& { return p.max_iterations; }, AtLeast(1))
          .Means("most Levenberg-Marquardt iterations per solve"),
      params::NumberField<P>(
          "function_tolerance", [](auto& p) -> auto& { return p.function_tolerance; }, Above(0.0))
          .Means("relative cost decrease that ends a solve"),
      params::EnumField<P, OdometryResidual>("odometry_residual",
                                             [](auto& p) -> auto& { return p.odometry_residual; },
                                             {{OdometryResidual::kControlSpace, "control_space"},
                                              {OdometryResidual::kPoseSpace, "pose_space"}})
          .Means("odometry residual in the space of the controls (control_space) or of the pose "
                 "increments (pose_space)"),
      params::StructArrayField<P, F>(
          "odometry_floor", [](auto& p) -> auto& { return p.odometry_floor; },
          {{"position_std", &F::position_std}, {"heading_std", &F::heading_std}}, Above(0.0))
          .Means("floor on the odometry noise [position_std m, heading_std rad], as the batch "
                 "smoother's"),
      params::NumberField<P>(
          "gate_chi2", [](auto& p) -> auto& { return p.gate_chi2; }, Above(0.0))
          .Means("chi-square (2 dof) gate of the nearest-neighbour association on the marginal "
                 "innovation covariance"),
      params::EnumField<P, ScanAssignment>(
          "assignment", [](auto& p) -> auto& { return p.assignment; },
          {{ScanAssignment::kNearestNeighbour, "nearest_neighbour"},
           {ScanAssignment::kJointCompatibility, "jcbb"}})
          .Means("own association: each scan's gated pairs by greedy nearest neighbour or by joint "
                 "compatibility branch and bound (jcbb)"),
      params::IntField<P>(
          "jcbb_max_nodes", [](auto& p) -> auto& { return p.jcbb_max_nodes; }, AtLeast(1))
          .Means("jcbb: joint compatibility tests per scan before the search keeps its best")
          .UsedOnlyWith("assignment", {"jcbb"}),
      params::NumberField<P>(
          "jcbb_null_intensity", [](auto& p) -> auto& { return p.jcbb_null_intensity; },
          AtLeast(0.0))
          .Means("jcbb: 0 takes the most jointly compatible pairs; > 0 the most likely "
                 "assignment, a measurement left out weighed by this intensity (per m per rad)")
          .UsedOnlyWith("assignment", {"jcbb"}),
      params::IntField<P>(
          "landmark_keep_steps", [](auto& p) -> auto& { return p.landmark_keep_steps; }, AtLeast(0))
          .Means("a landmark no window pose observes stays in the window, held by the marginal "
                 "prior with its correlations, until unobserved for this many steps (0: "
                 "marginalised at once)"),
      params::IntField<P>(
          "confirm_detections", [](auto& p) -> auto& { return p.confirm_detections; }, AtLeast(1))
          .Means("scans that must associate with a tentative landmark (its first included) before "
                 "it is confirmed"),
      params::NumberField<P>(
          "confirm_ratio", [](auto& p) -> auto& { return p.confirm_ratio; }, Between(0.0, 1.0))
          .Means("a tentative landmark is deleted once its detections fall below this fraction of "
                 "the scans expected to detect it"),
      // "cauchy", "huber" or "none": checked by WindowParams::Validate().
      params::StringField<P>(
          "robust_loss", [](auto& p) -> auto& { return p.robust_loss; })
          .Means("loss on the detections of confirmed landmarks: huber, cauchy or none"),
      params::NumberField<P>(
          "robust_scale", [](auto& p) -> auto& { return p.robust_scale; }, Above(0.0))
          .Means("scale of the robust loss of confirmed landmarks, in standard deviations"),
      params::NumberField<P>(
          "tentative_robust_scale", [](auto& p) -> auto& { return p.tentative_robust_scale; },
          Above(0.0))
          .Means("scale of the Cauchy loss on the detections of tentative landmarks, in standard "
                 "deviations"),
      params::BoolField<P>(
          "reject_outliers", [](auto& p) -> auto& { return p.reject_outliers; })
          .Means("after each solve, drop the detections of confirmed landmarks outside the gate "
                 "and solve again"),
      params::NumberField<P>(
          "static_point_chi2", [](auto& p) -> auto& { return p.static_point_chi2; }, AtLeast(0.0))
          .Means("moving-object test: a detection beyond this chi-square (2 dof) of its landmark's "
                 "first detection, carried by the odometry, and within it of the latest one "
                 "moves; the landmark's detections then count as clutter (0: off)")
          .UsedOnlyWith("association", {"unknown"}),
      params::NumberField<P>(
          "static_point_heading_std", [](auto& p) -> auto& { return p.static_point_heading_std; },
          Above(0.0))
          .Means("the moving-object test compares with the first detection only while the "
                 "odometry heading std since stays below this (rad)")
          .UsedOnlyWith("association", {"unknown"})
          .UsedOnlyWithout("static_point_chi2", 0.0),
      params::IntField<P>(
          "static_point_failures", [](auto& p) -> auto& { return p.static_point_failures; },
          AtLeast(1))
          .Means("consecutive moving detections that make a landmark a moving object")
          .UsedOnlyWith("association", {"unknown"})
          .UsedOnlyWithout("static_point_chi2", 0.0),
  });
  return table;
}

nlohmann::json ToJson(const WindowParams& params) { return WindowParamsTable().ToJson(params); }

void ApplyJson(const nlohmann::json& overrides, WindowParams& params) {
  WindowParams p = params;
  WindowParamsTable().Apply(overrides, p);
  p.Validate();
  params = std::move(p);
}

}  // namespace phdslam::reference
