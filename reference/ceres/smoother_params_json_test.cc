#include "reference/ceres/smoother_params_json.h"

#include <gtest/gtest.h>

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
  ExpectRejected(R"({"max_iterations": 50, "gate": 3})", "'gate': unknown parameter (known: ");
  ExpectRejected(R"({"association": "unknown"})", "fixed by the estimator's name");
  ExpectRejected(R"({"max_iterations": 2.5})", "max_iterations': expected an integer");
  ExpectRejected(R"({"compute_covariances": 1})", "expected true or false");
  ExpectRejected(R"({"odometry_floor": [0.001]})", "expected [position_std, heading_std]");
  ExpectRejected(R"({"linear_solver": "dense_qr"})", "sparse_normal_cholesky");
  ExpectRejected(R"({"robust_loss": "tukey"})", "robust_loss");
  ExpectRejected(R"({"min_observations": 0})", "min_observations");
  ExpectRejected(R"([1, 2])", "expected a JSON object");
}

}  // namespace
}  // namespace phdslam::reference
