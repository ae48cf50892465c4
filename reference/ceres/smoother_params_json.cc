#include "reference/ceres/smoother_params_json.h"

#include <string>
#include <utility>
#include <vector>

namespace phdslam::reference {

namespace {

/// A noise floor as [position_std, heading_std].
std::vector<std::pair<std::string, double OdometryNoiseFloor::*>> FloorMembers() {
  return {{"position_std", &OdometryNoiseFloor::position_std},
          {"heading_std", &OdometryNoiseFloor::heading_std}};
}

}  // namespace

const params::ParameterTable<SmootherOptions>& SmootherOptionsTable() {
  using params::Above;
  using params::AtLeast;
  using O = SmootherOptions;
  using F = OdometryNoiseFloor;
  static const params::ParameterTable<O> table({
      params::Fixed(params::EnumField<O, AssociationMode>(
                        "association", [](auto& o) -> auto& { return o.association; },
                        {{AssociationMode::kKnown, "known"},
                         {AssociationMode::kFilter, "filter"},
                         {AssociationMode::kUnknown, "unknown"}}),
                    "fixed by the estimator's name (smoother-known, smoother-filter, "
                    "smoother-unknown)"),
      params::EnumField<O, SmootherInitialisation>(
          "initialisation", [](auto& o) -> auto& { return o.initialisation; },
          {{SmootherInitialisation::kIncremental, "incremental"},
           {SmootherInitialisation::kBatch, "batch"}}),
      params::IntField<O>(
          "incremental_chunk_steps", [](auto& o) -> auto& { return o.incremental_chunk_steps; },
          AtLeast(1)),
      params::IntField<O>(
          "incremental_active_steps", [](auto& o) -> auto& { return o.incremental_active_steps; },
          AtLeast(0)),
      params::BoolField<O>(
          "incremental_held_prior", [](auto& o) -> auto& { return o.incremental_held_prior; }),
      params::BoolField<O>(
          "incremental_squared_marginals",
          [](auto& o) -> auto& { return o.incremental_squared_marginals; }),
      params::BoolField<O>(
          "incremental_delete_collapsed",
          [](auto& o) -> auto& { return o.incremental_delete_collapsed; }),
      params::BoolField<O>(
          "incremental_marginals_without_collapsed",
          [](auto& o) -> auto& { return o.incremental_marginals_without_collapsed; }),
      params::BoolField<O>(
          "incremental_skip_ambiguous",
          [](auto& o) -> auto& { return o.incremental_skip_ambiguous; }),
      params::BoolField<O>(
          "incremental_birth_outside_gates",
          [](auto& o) -> auto& { return o.incremental_birth_outside_gates; }),
      params::BoolField<O>(
          "incremental_pose_landmark_cross",
          [](auto& o) -> auto& { return o.incremental_pose_landmark_cross; }),
      params::NumberField<O>(
          "incremental_new_landmark_intensity",
          [](auto& o) -> auto& { return o.incremental_new_landmark_intensity; }, AtLeast(0.0)),
      params::NumberField<O>(
          "incremental_static_point_chi2",
          [](auto& o) -> auto& { return o.incremental_static_point_chi2; }, AtLeast(0.0)),
      params::NumberField<O>(
          "incremental_static_point_heading_std",
          [](auto& o) -> auto& { return o.incremental_static_point_heading_std; }, Above(0.0)),
      params::IntField<O>(
          "incremental_static_point_failures",
          [](auto& o) -> auto& { return o.incremental_static_point_failures; }, AtLeast(1)),
      params::NumberField<O>(
          "incremental_relocalisation_std",
          [](auto& o) -> auto& { return o.incremental_relocalisation_std; }, AtLeast(0.0)),
      params::IntField<O>(
          "incremental_relocalisation_scans",
          [](auto& o) -> auto& { return o.incremental_relocalisation_scans; }, AtLeast(2)),
      params::NumberField<O>(
          "incremental_relocalisation_inlier_distance",
          [](auto& o) -> auto& { return o.incremental_relocalisation_inlier_distance; },
          Above(0.0)),
      params::IntField<O>(
          "incremental_relocalisation_margin",
          [](auto& o) -> auto& { return o.incremental_relocalisation_margin; }, AtLeast(1)),
      params::NumberField<O>(
          "incremental_relocalisation_prior_weight",
          [](auto& o) -> auto& { return o.incremental_relocalisation_prior_weight; }, AtLeast(0.0)),
      params::BoolField<O>(
          "incremental_relocalisation_leave_ambiguous",
          [](auto& o) -> auto& { return o.incremental_relocalisation_leave_ambiguous; }),
      params::NumberField<O>(
          "known_outlier_chi2", [](auto& o) -> auto& { return o.known_outlier_chi2; },
          AtLeast(0.0)),
      params::IntField<O>(
          "max_iterations", [](auto& o) -> auto& { return o.max_iterations; }, AtLeast(1)),
      params::NumberField<O>(
          "function_tolerance", [](auto& o) -> auto& { return o.function_tolerance; }, Above(0.0)),
      params::NumberField<O>(
          "intermediate_function_tolerance",
          [](auto& o) -> auto& { return o.intermediate_function_tolerance; }, Above(0.0)),
      params::BoolField<O>(
          "compute_covariances", [](auto& o) -> auto& { return o.compute_covariances; }),
      params::EnumField<O, SparseLinearSolver>(
          "linear_solver", [](auto& o) -> auto& { return o.linear_solver; },
          {{SparseLinearSolver::kSparseNormalCholesky, "sparse_normal_cholesky"},
           {SparseLinearSolver::kSparseSchur, "sparse_schur"}}),
      params::IntField<O>(
          "num_threads", [](auto& o) -> auto& { return o.num_threads; }, AtLeast(1)),
      params::EnumField<O, OdometryResidual>("odometry_residual",
                                             [](auto& o) -> auto& { return o.odometry_residual; },
                                             {{OdometryResidual::kControlSpace, "control_space"},
                                              {OdometryResidual::kPoseSpace, "pose_space"}}),
      params::StructArrayField<O, F>(
          "odometry_floor", [](auto& o) -> auto& { return o.odometry_floor; }, FloorMembers(),
          Above(0.0)),
      params::StructArrayField<O, F>(
          "warm_start_floor", [](auto& o) -> auto& { return o.warm_start_floor; }, FloorMembers(),
          Above(0.0)),
      params::IntField<O>(
          "initial_pass_solve_steps", [](auto& o) -> auto& { return o.initial_pass_solve_steps; },
          AtLeast(0)),
      params::IntField<O>(
          "reassociation_rounds", [](auto& o) -> auto& { return o.reassociation_rounds; },
          AtLeast(0)),
      params::NumberField<O>(
          "gate_chi2", [](auto& o) -> auto& { return o.gate_chi2; }, Above(0.0)),
      params::IntField<O>(
          "min_observations", [](auto& o) -> auto& { return o.min_observations; }, AtLeast(1)),
      params::NumberField<O>(
          "merge_position_std", [](auto& o) -> auto& { return o.merge_position_std; },
          AtLeast(0.0)),
      params::NumberField<O>(
          "min_detection_ratio", [](auto& o) -> auto& { return o.min_detection_ratio; },
          params::Probability()),
      // "cauchy", "huber" or "none": checked by SmootherOptions::Validate().
      params::StringField<O>(
          "robust_loss", [](auto& o) -> auto& { return o.robust_loss; }),
      params::NumberField<O>(
          "robust_scale", [](auto& o) -> auto& { return o.robust_scale; }, Above(0.0)),
      params::NumberField<O>(
          "filter_label_distance", [](auto& o) -> auto& { return o.filter_label_distance; },
          Above(0.0)),
      params::EnumField<O, StartTrajectory>(
          "start_from", [](auto& o) -> auto& { return o.start_from; },
          {{StartTrajectory::kDeadReckoning, "dead-reckoning"}, {StartTrajectory::kPhd3, "phd3"}}),
      params::IntField<O>(
          "start_particles", [](auto& o) -> auto& { return o.start_particles; }, AtLeast(1)),
      params::EnumField<O, StartPath>("start_path", [](auto& o) -> auto& { return o.start_path; },
                                      {{StartPath::kEstimate, "estimate"},
                                       {StartPath::kBestParticlePath, "best-particle-path"}}),
  });
  return table;
}

nlohmann::json ToJson(const SmootherOptions& options) {
  return SmootherOptionsTable().ToJson(options);
}

void ApplyJson(const nlohmann::json& overrides, SmootherOptions& options) {
  SmootherOptions o = options;
  SmootherOptionsTable().Apply(overrides, o);
  o.Validate();
  options = std::move(o);
}

}  // namespace phdslam::reference
