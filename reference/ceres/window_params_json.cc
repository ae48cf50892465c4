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
                                               {{true, "known"}, {false, "unknown"}}),
                    "fixed by the estimator's name (window-known, window)"),
      // Bounded below here; the run's length bounds it above when the run is built.
      params::IntField<P>(
          "window_length", [](auto& p) -> auto& { return p.window_length; }, AtLeast(1)),
      params::IntField<P>(
          "solve_every", [](auto& p) -> auto& { return p.solve_every; }, AtLeast(1)),
      params::IntField<P>(
          "max_iterations", [](auto& p) -> auto& { return p.max_iterations; }, AtLeast(1)),
      params::NumberField<P>(
          "function_tolerance", [](auto& p) -> auto& { return p.function_tolerance; }, Above(0.0)),
      params::EnumField<P, OdometryResidual>("odometry_residual",
                                             [](auto& p) -> auto& { return p.odometry_residual; },
                                             {{OdometryResidual::kControlSpace, "control_space"},
                                              {OdometryResidual::kPoseSpace, "pose_space"}}),
      params::StructArrayField<P, F>(
          "odometry_floor", [](auto& p) -> auto& { return p.odometry_floor; },
          {{"position_std", &F::position_std}, {"heading_std", &F::heading_std}}, Above(0.0)),
      params::NumberField<P>(
          "gate_chi2", [](auto& p) -> auto& { return p.gate_chi2; }, Above(0.0)),
      params::IntField<P>(
          "confirm_detections", [](auto& p) -> auto& { return p.confirm_detections; }, AtLeast(1)),
      params::NumberField<P>(
          "confirm_ratio", [](auto& p) -> auto& { return p.confirm_ratio; }, Between(0.0, 1.0)),
      // "cauchy", "huber" or "none": checked by WindowParams::Validate().
      params::StringField<P>(
          "robust_loss", [](auto& p) -> auto& { return p.robust_loss; }),
      params::NumberField<P>(
          "robust_scale", [](auto& p) -> auto& { return p.robust_scale; }, Above(0.0)),
      params::NumberField<P>(
          "tentative_robust_scale", [](auto& p) -> auto& { return p.tentative_robust_scale; },
          Above(0.0)),
      params::BoolField<P>(
          "reject_outliers", [](auto& p) -> auto& { return p.reject_outliers; }),
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
