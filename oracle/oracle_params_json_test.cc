#include "oracle/oracle_params_json.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace phdslam::oracle {
namespace {

TEST(OracleParamsJson, DefaultsAreThePapersAndRoundTrip) {
  const nlohmann::json j = ToJson(OracleParams{});
  EXPECT_EQ(j.at("particles"), 1);
  EXPECT_EQ(j.at("resampling"), true);
  EXPECT_DOUBLE_EQ(j.at("ess_threshold").get<double>(), 0.2);
  EXPECT_EQ(j.at("ipl_iterations"), 5);
  EXPECT_DOUBLE_EQ(j.at("ipl_kl_tolerance").get<double>(), 1e-3);
  EXPECT_DOUBLE_EQ(j.at("pose_regularisation")[2].get<double>(), 1e-18);

  OracleParams p;
  ApplyJson({{"particles", 10},
             {"resampling", false},
             {"ess_threshold", 0.5},
             {"ipl_iterations", 2},
             {"ipl_kl_tolerance", 1e-6},
             {"pose_regularisation", {1e-4, 2e-4, 3e-6}}},
            p);
  EXPECT_EQ(p.particles, 10);
  EXPECT_FALSE(p.resampling);
  EXPECT_EQ(p.ess_threshold, 0.5);
  EXPECT_EQ(p.ipl_iterations, 2);
  EXPECT_EQ(p.ipl_kl_tolerance, 1e-6);
  EXPECT_EQ(p.pose_regularisation, Mat3(Vec3(1e-4, 2e-4, 3e-6).asDiagonal()));
  OracleParams q;
  ApplyJson(ToJson(p), q);
  EXPECT_EQ(ToJson(q), ToJson(p));
}

TEST(OracleParamsJson, RejectsUnknownKeysWrongTypesAndBadValuesWithoutChangingParams) {
  OracleParams p;
  EXPECT_THROW(ApplyJson({{"hypotheses", 3}}, p), std::invalid_argument);
  EXPECT_THROW(ApplyJson({{"particles", 2.5}}, p), std::invalid_argument);
  EXPECT_THROW(ApplyJson({{"resampling", 1}}, p), std::invalid_argument);
  EXPECT_THROW(ApplyJson({{"ess_threshold", "high"}}, p), std::invalid_argument);
  EXPECT_THROW(ApplyJson({{"pose_regularisation", {1e-9, 1e-9}}}, p), std::invalid_argument);
  EXPECT_THROW(ApplyJson({{"pose_regularisation", {1e-9, -1.0, 0.0}}}, p), std::invalid_argument);
  EXPECT_THROW(ApplyJson({{"ipl_iterations", 3}, {"particles", 0}}, p), std::invalid_argument);
  EXPECT_THROW(ApplyJson(nlohmann::json::array(), p), std::invalid_argument);
  EXPECT_EQ(ToJson(p), ToJson(OracleParams{}));
}

}  // namespace
}  // namespace phdslam::oracle
