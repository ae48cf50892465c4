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
                         {AssociationMode::kUnknown, "unknown"}})
                        .Means("known labels (smoother-known), a PHD-SLAM 3.0 run's association "
                               "(smoother-filter) or its own (smoother-unknown)"),
                    "fixed by the estimator's name (smoother-known, smoother-filter, "
                    "smoother-unknown)"),
      params::EnumField<O, SmootherInitialisation>(
          "initialisation", [](auto& o) -> auto& { return o.initialisation; },
          {{SmootherInitialisation::kIncremental, "incremental"},
           {SmootherInitialisation::kBatch, "batch"}})
          .Means("solve the whole graph from the start trajectory (batch) or build it in time "
                 "order and solve as it grows (incremental)"),
      params::IntField<O>(
          "incremental_chunk_steps", [](auto& o) -> auto& { return o.incremental_chunk_steps; },
          AtLeast(1))
          .Means("incremental: steps added between two solves")
          .UsedOnlyWith("initialisation", {"incremental"}),
      params::IntField<O>(
          "incremental_active_steps", [](auto& o) -> auto& { return o.incremental_active_steps; },
          AtLeast(0))
          .Means("incremental: newest poses optimised in each chunk solve, older ones held (0: "
                 "every pose)")
          .UsedOnlyWith("initialisation", {"incremental"}),
      params::BoolField<O>(
          "incremental_held_prior", [](auto& o) -> auto& { return o.incremental_held_prior; })
          .Means("incremental: fold the measurements of held poses once into a fixed prior on "
                 "their landmarks")
          .UsedOnlyWith("initialisation", {"incremental"}),
      params::BoolField<O>(
          "incremental_squared_marginals",
          [](auto& o) -> auto& { return o.incremental_squared_marginals; })
          .Means("incremental, own association: gate covariances from the squared-loss graph "
                 "instead of the robust one")
          .UsedOnlyWith("initialisation", {"incremental"})
          .UsedOnlyWith("association", {"unknown"}),
      params::BoolField<O>(
          "incremental_delete_collapsed",
          [](auto& o) -> auto& { return o.incremental_delete_collapsed; })
          .Means("incremental, own association: delete landmarks collapsed onto a pose after every "
                 "chunk solve")
          .UsedOnlyWith("initialisation", {"incremental"})
          .UsedOnlyWith("association", {"unknown"}),
      params::BoolField<O>(
          "incremental_marginals_without_collapsed",
          [](auto& o) -> auto& { return o.incremental_marginals_without_collapsed; })
          .Means("incremental, own association: when the marginal covariances fail, compute them "
                 "again without collapsed landmarks")
          .UsedOnlyWith("initialisation", {"incremental"})
          .UsedOnlyWith("association", {"unknown"}),
      params::EnumField<O, ScanAssignment>(
          "incremental_assignment", [](auto& o) -> auto& { return o.incremental_assignment; },
          {{ScanAssignment::kNearestNeighbour, "nearest_neighbour"},
           {ScanAssignment::kJointCompatibility, "jcbb"}})
          .Means("incremental, own association: each scan's gated pairs by greedy nearest "
                 "neighbour or by joint compatibility branch and bound (jcbb)")
          .UsedOnlyWith("initialisation", {"incremental"})
          .UsedOnlyWith("association", {"unknown"}),
      params::IntField<O>(
          "incremental_jcbb_max_nodes",
          [](auto& o) -> auto& { return o.incremental_jcbb_max_nodes; }, AtLeast(1))
          .Means("incremental, jcbb: joint compatibility tests per scan before the search keeps "
                 "its best")
          .UsedOnlyWith("initialisation", {"incremental"})
          .UsedOnlyWith("incremental_assignment", {"jcbb"}),
      params::NumberField<O>(
          "incremental_jcbb_null_intensity",
          [](auto& o) -> auto& { return o.incremental_jcbb_null_intensity; }, AtLeast(0.0))
          .Means("incremental, jcbb: 0 takes the most jointly compatible pairs; > 0 the most "
                 "likely assignment, a measurement left out weighed by this intensity (per m per "
                 "rad)")
          .UsedOnlyWith("initialisation", {"incremental"})
          .UsedOnlyWith("incremental_assignment", {"jcbb"}),
      params::BoolField<O>(
          "incremental_skip_ambiguous",
          [](auto& o) -> auto& { return o.incremental_skip_ambiguous; })
          .Means("incremental, own association: a measurement inside two or more gates is left "
                 "unassociated and starts none")
          .UsedOnlyWith("initialisation", {"incremental"})
          .UsedOnlyWith("association", {"unknown"}),
      params::BoolField<O>(
          "incremental_birth_outside_gates",
          [](auto& o) -> auto& { return o.incremental_birth_outside_gates; })
          .Means(
              "incremental, own association: only measurements outside every gate start landmarks")
          .UsedOnlyWith("initialisation", {"incremental"}),
      params::BoolField<O>(
          "incremental_pose_landmark_cross",
          [](auto& o) -> auto& { return o.incremental_pose_landmark_cross; })
          .Means("incremental, own association: the gate uses each landmark's cross-covariance "
                 "with the pose")
          .UsedOnlyWith("initialisation", {"incremental"})
          .UsedOnlyWith("association", {"unknown"}),
      params::NumberField<O>(
          "incremental_new_landmark_intensity",
          [](auto& o) -> auto& { return o.incremental_new_landmark_intensity; }, AtLeast(0.0))
          .Means("incremental, own association: a gated pair is admissible only when pD N(nu; 0, "
                 "S) reaches this intensity (0: off)")
          .UsedOnlyWith("initialisation", {"incremental"})
          .UsedOnlyWith("association", {"unknown"}),
      params::NumberField<O>(
          "incremental_static_point_chi2",
          [](auto& o) -> auto& { return o.incremental_static_point_chi2; }, AtLeast(0.0))
          .Means("incremental, own association: a landmark whose detection moved farther than this "
                 "chi-square from its first one is deleted (0: off)")
          .UsedOnlyWith("initialisation", {"incremental"})
          .UsedOnlyWith("association", {"unknown"}),
      params::NumberField<O>(
          "incremental_static_point_heading_std",
          [](auto& o) -> auto& { return o.incremental_static_point_heading_std; }, Above(0.0))
          .Means("the static-point check compares with the first detection only while the odometry "
                 "heading std stays below this (rad)")
          .UsedOnlyWith("initialisation", {"incremental"})
          .UsedOnlyWith("association", {"unknown"}),
      params::IntField<O>(
          "incremental_static_point_failures",
          [](auto& o) -> auto& { return o.incremental_static_point_failures; }, AtLeast(1))
          .Means("consecutive moving detections before the static-point check deletes the landmark")
          .UsedOnlyWith("initialisation", {"incremental"})
          .UsedOnlyWith("association", {"unknown"}),
      params::NumberField<O>(
          "incremental_relocalisation_std",
          [](auto& o) -> auto& { return o.incremental_relocalisation_std; }, AtLeast(0.0))
          .Means("incremental, own association: above this marginal position std (m) scans are "
                 "matched with the map together (0: off)")
          .UsedOnlyWith("initialisation", {"incremental"})
          .UsedOnlyWith("association", {"unknown"}),
      params::IntField<O>(
          "incremental_relocalisation_scans",
          [](auto& o) -> auto& { return o.incremental_relocalisation_scans; }, AtLeast(2))
          .Means("scans with detections matched together in a re-localisation")
          .UsedOnlyWith("initialisation", {"incremental"})
          .UsedOnlyWith("association", {"unknown"}),
      params::NumberField<O>(
          "incremental_relocalisation_inlier_distance",
          [](auto& o) -> auto& { return o.incremental_relocalisation_inlier_distance; }, Above(0.0))
          .Means("a detection within this distance (m) of a landmark after the candidate "
                 "correction is an inlier")
          .UsedOnlyWith("initialisation", {"incremental"})
          .UsedOnlyWith("association", {"unknown"}),
      params::IntField<O>(
          "incremental_relocalisation_margin",
          [](auto& o) -> auto& { return o.incremental_relocalisation_margin; }, AtLeast(1))
          .Means("inliers by which the best re-localisation correction must beat every rival")
          .UsedOnlyWith("initialisation", {"incremental"})
          .UsedOnlyWith("association", {"unknown"}),
      params::NumberField<O>(
          "incremental_relocalisation_prior_weight",
          [](auto& o) -> auto& { return o.incremental_relocalisation_prior_weight; }, AtLeast(0.0))
          .Means("a correction scores its inliers less this times half its squared Mahalanobis "
                 "distance from dead reckoning")
          .UsedOnlyWith("initialisation", {"incremental"})
          .UsedOnlyWith("association", {"unknown"}),
      params::BoolField<O>(
          "incremental_relocalisation_leave_ambiguous",
          [](auto& o) -> auto& { return o.incremental_relocalisation_leave_ambiguous; })
          .Means("an ambiguous re-localisation match ends it without a correction (false: keep "
                 "matching)")
          .UsedOnlyWith("initialisation", {"incremental"})
          .UsedOnlyWith("association", {"unknown"}),
      params::NumberField<O>(
          "known_outlier_chi2", [](auto& o) -> auto& { return o.known_outlier_chi2; }, AtLeast(0.0))
          .Means("known association: labelled measurements above this squared whitened residual "
                 "are left out as mislabelled (0: keep all)"),
      params::IntField<O>(
          "max_iterations", [](auto& o) -> auto& { return o.max_iterations; }, AtLeast(1))
          .Means("most Levenberg-Marquardt iterations per solve"),
      params::NumberField<O>(
          "function_tolerance", [](auto& o) -> auto& { return o.function_tolerance; }, Above(0.0))
          .Means("relative cost decrease that ends the final solve"),
      params::NumberField<O>(
          "intermediate_function_tolerance",
          [](auto& o) -> auto& { return o.intermediate_function_tolerance; }, Above(0.0))
          .Means("relative cost decrease that ends the solves before the final one"),
      params::BoolField<O>(
          "compute_covariances", [](auto& o) -> auto& { return o.compute_covariances; })
          .Means("compute the marginal pose and landmark covariances after the final solve"),
      params::EnumField<O, SparseLinearSolver>(
          "linear_solver", [](auto& o) -> auto& { return o.linear_solver; },
          {{SparseLinearSolver::kSparseNormalCholesky, "sparse_normal_cholesky"},
           {SparseLinearSolver::kSparseSchur, "sparse_schur"}})
          .Means("Ceres sparse linear solver of the normal equations"),
      params::IntField<O>(
          "num_threads", [](auto& o) -> auto& { return o.num_threads; }, AtLeast(1))
          .Means("threads Ceres uses per solve"),
      params::EnumField<O, OdometryResidual>("odometry_residual",
                                             [](auto& o) -> auto& { return o.odometry_residual; },
                                             {{OdometryResidual::kControlSpace, "control_space"},
                                              {OdometryResidual::kPoseSpace, "pose_space"}})
          .Means("odometry residual in the space of the controls (control_space) or of the pose "
                 "increments (pose_space)"),
      params::StructArrayField<O, F>(
          "odometry_floor", [](auto& o) -> auto& { return o.odometry_floor; }, FloorMembers(),
          Above(0.0))
          .Means(
              "floor on the odometry noise [position_std m, heading_std rad] of the final solve"),
      params::StructArrayField<O, F>(
          "warm_start_floor", [](auto& o) -> auto& { return o.warm_start_floor; }, FloorMembers(),
          Above(0.0))
          .Means("looser odometry noise floor of every solve but the last, to bring the trajectory "
                 "close quickly"),
      params::IntField<O>(
          "initial_pass_solve_steps", [](auto& o) -> auto& { return o.initial_pass_solve_steps; },
          AtLeast(0))
          .Means("batch, own association: the initial association pass solves the steps so far "
                 "every this many steps (0: never)"),
      params::IntField<O>(
          "reassociation_rounds", [](auto& o) -> auto& { return o.reassociation_rounds; },
          AtLeast(0))
          .Means("own association: most solve and re-associate rounds"),
      params::NumberField<O>(
          "gate_chi2", [](auto& o) -> auto& { return o.gate_chi2; }, Above(0.0))
          .Means("chi-square (2 dof) gate for associating a measurement and for merging landmarks"),
      params::IntField<O>(
          "min_observations", [](auto& o) -> auto& { return o.min_observations; }, AtLeast(1))
          .Means("landmarks seen fewer times are dropped"),
      params::NumberField<O>(
          "merge_position_std", [](auto& o) -> auto& { return o.merge_position_std; }, AtLeast(0.0))
          .Means(
              "standard deviation (m) added to both landmarks' covariances when testing a merge"),
      params::NumberField<O>(
          "min_detection_ratio", [](auto& o) -> auto& { return o.min_detection_ratio; },
          params::Probability())
          .Means("landmarks detected in fewer than this fraction of the scans expected to see them "
                 "are dropped"),
      // "cauchy", "huber" or "none": checked by SmootherOptions::Validate().
      params::StringField<O>(
          "robust_loss", [](auto& o) -> auto& { return o.robust_loss; })
          .Means("robust loss on the measurements: cauchy, huber or none"),
      params::NumberField<O>(
          "robust_scale", [](auto& o) -> auto& { return o.robust_scale; }, Above(0.0))
          .Means("scale of the robust loss, in standard deviations"),
      params::NumberField<O>(
          "filter_label_distance", [](auto& o) -> auto& { return o.filter_label_distance; },
          Above(0.0))
          .Means("smoother-filter: associated landmark means of consecutive scans closer than this "
                 "(m) are one landmark"),
      params::EnumField<O, FilterFrontEnd>(
          "filter_front_end", [](auto& o) -> auto& { return o.filter_front_end; },
          {{FilterFrontEnd::kPhd3, "phd3"}, {FilterFrontEnd::kWindow, "window"}})
          .Means("smoother-filter: the association of a PHD-SLAM 3.0 run (phd3) or of the "
                 "fixed-lag smoother's own association (window, with its defaults on the scenario, "
                 "its labels as they are)")
          .UsedOnlyWith("association", {"filter"}),
      params::EnumField<O, OwnFrontEnd>(
          "front_end", [](auto& o) -> auto& { return o.front_end; },
          {{OwnFrontEnd::kPass, "pass"}, {OwnFrontEnd::kWindow, "window"}})
          .Means("smoother-unknown's first association: its own pass (pass) or the fixed-lag "
                 "smoother's own association (window, with its defaults on the scenario), then "
                 "the re-association rounds")
          .UsedOnlyWith("association", {"unknown"}),
      params::EnumField<O, StartTrajectory>("start_from",
                                            [](auto& o) -> auto& { return o.start_from; },
                                            {{StartTrajectory::kDeadReckoning, "dead-reckoning"},
                                             {StartTrajectory::kPhd3, "phd3"},
                                             {StartTrajectory::kWindow, "window"}})
          .Means("start trajectory: dead reckoning, a PHD-SLAM 3.0 run on the same seed (phd3) or "
                 "the fixed-lag smoother's own-association run (window, with its defaults on the "
                 "scenario)"),
      params::IntField<O>(
          "start_particles", [](auto& o) -> auto& { return o.start_particles; }, AtLeast(1))
          .Means("particles of the PHD-SLAM 3.0 run of start_from phd3")
          .UsedOnlyWith("start_from", {"phd3"}),
      params::EnumField<O, StartPath>("start_path", [](auto& o) -> auto& { return o.start_path; },
                                      {{StartPath::kEstimate, "estimate"},
                                       {StartPath::kBestParticlePath, "best-particle-path"}})
          .Means("with start_from phd3: that run's per-step estimates or its best final particle's "
                 "path"),
      params::EnumField<O, PosteriorMapPrior>(
          "posterior_map_prior", [](auto& o) -> auto& { return o.posterior.map_prior; },
          {{PosteriorMapPrior::kPoissonBirth, "poisson_birth"}, {PosteriorMapPrior::kFlat, "flat"}})
          .Means("map prior of the reported neg_log_posterior: a Poisson birth term per landmark "
                 "(poisson_birth) or none (flat, the score of earlier versions)"),
      params::NumberField<O>(
          "posterior_birth_log_weight",
          [](auto& o) -> auto& { return o.posterior.birth_log_weight; })
          .Means("poisson_birth: log of the birth intensity each landmark pays in "
                 "neg_log_posterior (the RFS filters' birth log-weight, ln 1e-6)"),
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
