#include "reference/ceres/smoother_params_json.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace phdslam::reference {
namespace {

TEST(SmootherParamsJson, DefaultsRoundTrip) {
  const SmootherOptions defaults;
  nlohmann::json j = ToJson(defaults);
  EXPECT_EQ(j["association"], "known");
  EXPECT_EQ(j["robust_loss"], "cauchy");
  EXPECT_EQ(j["odometry_floor"][0], 1e-4);
  j.erase("association");
  SmootherOptions o;
  ApplyJson(j, o);
  EXPECT_EQ(ToJson(o), ToJson(defaults));
}

TEST(SmootherParamsJson, AppliesOverrides) {
  SmootherOptions o;
  ApplyJson(nlohmann::json::parse(R"({"robust_loss": "huber", "robust_scale": 2,
      "odometry_floor": [0.001, 1e-6], "linear_solver": "sparse_schur",
      "odometry_residual": "pose_space", "compute_covariances": false,
      "min_observations": 5})"),
            o);
  EXPECT_EQ(o.robust_loss, "huber");
  EXPECT_EQ(o.robust_scale, 2.0);
  EXPECT_EQ(o.odometry_floor.position_std, 1e-3);
  EXPECT_EQ(o.odometry_floor.heading_std, 1e-6);
  EXPECT_EQ(o.linear_solver, SparseLinearSolver::kSparseSchur);
  EXPECT_EQ(o.odometry_residual, OdometryResidual::kPoseSpace);
  EXPECT_FALSE(o.compute_covariances);
  EXPECT_EQ(o.min_observations, 5);
}

TEST(SmootherParamsJson, AcceptsTheCurrentAssociationModeAsANoOp) {
  SmootherOptions o;
  o.association = AssociationMode::kFilter;
  const nlohmann::json resolved = ToJson(o);
  ApplyJson(nlohmann::json{{"association", "filter"}}, o);
  EXPECT_EQ(o.association, AssociationMode::kFilter);
  SmootherOptions back;
  back.association = AssociationMode::kFilter;
  ApplyJson(resolved, back);
  EXPECT_EQ(ToJson(back), resolved);
}

// The resolved configuration stored with results (config.json): every key, value and number type.
TEST(SmootherParamsJson, WritesEveryOptionWithItsType) {
  EXPECT_EQ(ToJson(SmootherOptions{}).dump(),
            nlohmann::json::parse(R"({"association": "known", "compute_covariances": true,
      "filter_front_end": "phd3", "filter_label_distance": 2.0, "front_end": "pass",
      "function_tolerance": 1e-09,
      "gate_chi2": 13.8,
      "incremental_active_steps": 500, "incremental_chunk_steps": 25,
      "incremental_assignment": "nearest_neighbour", "incremental_jcbb_max_nodes": 20000,
      "incremental_jcbb_null_intensity": 0.0,
      "incremental_birth_outside_gates": false, "incremental_delete_collapsed": false,
      "incremental_held_prior": true, "incremental_marginals_without_collapsed": true,
      "incremental_new_landmark_intensity": 0.0, "incremental_pose_landmark_cross": false,
      "incremental_skip_ambiguous": false,
      "incremental_squared_marginals": false, "incremental_static_point_chi2": 0.0,
      "incremental_static_point_heading_std": 0.2, "incremental_static_point_failures": 1,
      "incremental_relocalisation_std": 0.0, "incremental_relocalisation_scans": 5,
      "incremental_relocalisation_inlier_distance": 0.5, "incremental_relocalisation_margin": 2,
      "incremental_relocalisation_prior_weight": 0.0,
      "incremental_relocalisation_leave_ambiguous": false,
      "initial_pass_solve_steps": 200, "initialisation": "batch",
      "intermediate_function_tolerance": 1e-06, "known_outlier_chi2": 1000.0,
      "linear_solver": "sparse_normal_cholesky", "max_iterations": 100,
      "merge_position_std": 1.0, "min_detection_ratio": 0.3, "min_observations": 3,
      "num_threads": 1, "odometry_floor": [0.0001, 1e-05], "odometry_residual": "control_space",
      "posterior_birth_log_weight": -13.815510557964274, "posterior_map_prior": "poisson_birth",
      "reassociation_rounds": 5, "robust_loss": "cauchy", "robust_scale": 1.0,
      "start_from": "dead-reckoning", "start_particles": 5, "start_path": "estimate",
      "warm_start_floor": [0.05, 1e-05]})")
                .dump());
}

void ExpectRejected(const std::string& overrides, const std::string& message_part) {
  SmootherOptions o;
  const nlohmann::json before = ToJson(o);
  try {
    ApplyJson(nlohmann::json::parse(overrides), o);
    ADD_FAILURE() << "accepted " << overrides;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(message_part), std::string::npos) << e.what();
  }
  EXPECT_EQ(ToJson(o), before) << "options changed by a rejected override";
}

TEST(SmootherParamsJson, RejectsBadOverridesAndLeavesTheOptionsUnchanged) {
  ExpectRejected(R"({"incremental_new_landmark_intensity": -0.5})",
                 "incremental_new_landmark_intensity");
  ExpectRejected(R"({"incremental_pose_landmark_cross": 1})", "incremental_pose_landmark_cross");
  ExpectRejected(R"({"incremental_static_point_chi2": -1})", "incremental_static_point_chi2");
  ExpectRejected(R"({"incremental_static_point_heading_std": 0})",
                 "incremental_static_point_heading_std");
  ExpectRejected(R"({"incremental_static_point_failures": 0})",
                 "incremental_static_point_failures");
  ExpectRejected(R"({"incremental_relocalisation_leave_ambiguous": 1})",
                 "incremental_relocalisation_leave_ambiguous");
  ExpectRejected(R"({"incremental_relocalisation_std": -1})", "incremental_relocalisation_std");
  ExpectRejected(R"({"incremental_relocalisation_scans": 1})", "incremental_relocalisation_scans");
  ExpectRejected(R"({"incremental_relocalisation_inlier_distance": 0})",
                 "incremental_relocalisation_inlier_distance");
  ExpectRejected(R"({"incremental_relocalisation_margin": 0})",
                 "incremental_relocalisation_margin");
  ExpectRejected(R"({"incremental_relocalisation_prior_weight": -1})",
                 "incremental_relocalisation_prior_weight");
  ExpectRejected(R"({"max_iterations": 50, "gate": 3})",
                 "unknown parameter 'gate' (known: association, initialisation, ");
  ExpectRejected(R"({"association": "unknown"})",
                 "parameter 'association': fixed by the estimator's name (smoother-known, "
                 "smoother-filter, smoother-unknown): expected \"known\", got \"unknown\"");
  ExpectRejected(R"({"association": "none"})", "parameter 'association': expected one of");
  ExpectRejected(R"({"max_iterations": 2.5})", "max_iterations': expected an integer");
  ExpectRejected(R"({"compute_covariances": 1})", "expected true or false");
  ExpectRejected(R"({"odometry_floor": [0.001]})",
                 "parameter 'odometry_floor': expected [position_std, heading_std], got [0.001]");
  ExpectRejected(R"({"warm_start_floor": [0.001, 0]})",
                 "parameter 'warm_start_floor': must be > 0, got 0");
  ExpectRejected(R"({"linear_solver": "dense_qr"})", "sparse_normal_cholesky");
  ExpectRejected(R"({"robust_loss": "tukey"})", "robust_loss");
  ExpectRejected(R"({"start_path": "lineage"})", "parameter 'start_path': expected one of");
  ExpectRejected(R"({"min_observations": 0})", "min_observations");
  ExpectRejected(R"({"initialisation": "dead_reckoning"})",
                 "parameter 'initialisation': expected one of");
  ExpectRejected(R"({"incremental_chunk_steps": 0})", "incremental_chunk_steps");
  ExpectRejected(R"({"incremental_active_steps": -1})", "incremental_active_steps");
  ExpectRejected(R"({"known_outlier_chi2": -1})",
                 "parameter 'known_outlier_chi2': must be >= 0, got -1");
  ExpectRejected(R"({"robust_scale": 0})", "parameter 'robust_scale': must be > 0, got 0");
  ExpectRejected(R"({"incremental_assignment": "hungarian"})",
                 "parameter 'incremental_assignment': expected one of");
  ExpectRejected(R"({"incremental_jcbb_max_nodes": 0})", "incremental_jcbb_max_nodes");
  ExpectRejected(R"({"posterior_map_prior": "uniform"})",
                 "parameter 'posterior_map_prior': expected one of");
  ExpectRejected(R"({"posterior_birth_log_weight": "ln"})", "posterior_birth_log_weight");
  ExpectRejected(R"([1, 2])", "expected an object, got [1,2]");
}

}  // namespace
}  // namespace phdslam::reference
