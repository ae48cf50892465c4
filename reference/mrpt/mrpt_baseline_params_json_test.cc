#include "reference/mrpt/mrpt_baseline_params_json.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace phdslam::reference {
namespace {

TEST(MrptBaselineParamsJson, EkfRoundTripsAndOverrides) {
  MrptEkfSlamOptions o;
  ApplyJson(nlohmann::json{{"association", "nn"},
                           {"metric", "ml"},
                           {"ic_chi2_quantile", 0.99},
                           {"min_associations", 4},
                           {"mrpt_kdtree_candidates", true},
                           {"prune_after_steps", 5},
                           {"prune_min_associations", 3},
                           {"symmetrize_covariance", false}},
            o);
  EXPECT_EQ(o.association, AssociationMethod::kNearestNeighbour);
  EXPECT_EQ(o.metric, AssociationMetric::kMatchingLikelihood);
  EXPECT_DOUBLE_EQ(o.ic_chi2_quantile, 0.99);
  EXPECT_EQ(o.min_associations, 4);
  EXPECT_TRUE(o.mrpt_kdtree_candidates);
  EXPECT_EQ(o.prune_after_steps, 5);
  EXPECT_EQ(o.prune_min_associations, 3);
  EXPECT_FALSE(o.symmetrize_covariance);
  MrptEkfSlamOptions back;
  ApplyJson(ToJson(o), back);
  EXPECT_EQ(ToJson(back), ToJson(o));
}

TEST(MrptBaselineParamsJson, FastSlamRoundTripsAndOverrides) {
  FastSlamOptions o;
  ApplyJson(nlohmann::json{{"proposal", "motion-model"},
                           {"association", "jcbb"},
                           {"new_landmark_log_likelihood", -7.5},
                           {"confirm_associations", 3},
                           {"tentative_steps", 6},
                           {"ess_threshold_fraction", 0.5},
                           {"resampling", "stratified"},
                           {"pose_regularisation", {1e-8, 2e-8, 0.0}}},
            o);
  EXPECT_EQ(o.proposal, FastSlamProposal::kMotionModel);
  EXPECT_EQ(o.association, AssociationMethod::kJcbb);
  ASSERT_TRUE(o.new_landmark_log_likelihood.has_value());
  EXPECT_DOUBLE_EQ(*o.new_landmark_log_likelihood, -7.5);
  EXPECT_EQ(o.confirm_associations, 3);
  EXPECT_EQ(o.tentative_steps, 6);
  EXPECT_DOUBLE_EQ(o.ess_threshold_fraction, 0.5);
  EXPECT_EQ(o.resampling, ResamplingScheme::kStratified);
  EXPECT_DOUBLE_EQ(o.pose_regulariser_diag(1), 2e-8);
  FastSlamOptions back;
  ApplyJson(ToJson(o), back);
  EXPECT_EQ(ToJson(back), ToJson(o));
  ApplyJson(nlohmann::json{{"new_landmark_log_likelihood", nullptr}}, back);
  EXPECT_FALSE(back.new_landmark_log_likelihood.has_value());
}

TEST(MrptBaselineParamsJson, RejectsBadOverridesAndLeavesOptionsUnchanged) {
  MrptEkfSlamOptions ekf;
  EXPECT_THROW(ApplyJson(nlohmann::json{{"prune_after", 5}}, ekf), std::invalid_argument);
  EXPECT_THROW(ApplyJson(nlohmann::json{{"prune_after_steps", 2.5}}, ekf), std::invalid_argument);
  EXPECT_THROW(ApplyJson(nlohmann::json{{"min_associations", 5}, {"association", "x"}}, ekf),
               std::invalid_argument);
  EXPECT_EQ(ekf.min_associations, MrptEkfSlamOptions{}.min_associations);
  FastSlamOptions fs;
  EXPECT_THROW(ApplyJson(nlohmann::json{{"ess_threshold_fraction", 2.0}}, fs),
               std::invalid_argument);
  EXPECT_THROW(ApplyJson(nlohmann::json{{"resampling", 1}}, fs), std::invalid_argument);
  EXPECT_THROW(ApplyJson(nlohmann::json::array(), fs), std::invalid_argument);
  EXPECT_DOUBLE_EQ(fs.ess_threshold_fraction, 0.2);
}

}  // namespace
}  // namespace phdslam::reference
