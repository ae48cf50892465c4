#include "reference/mrpt/mrpt_baseline_params_json.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

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

// The resolved configuration stored with results (config.json): every key, value and number type.
TEST(MrptBaselineParamsJson, WritesEveryOptionWithItsType) {
  EXPECT_EQ(ToJson(MrptEkfSlamOptions{}).dump(),
            nlohmann::json::parse(R"({"association": "jcbb", "ic_chi2_quantile": 0.999,
      "metric": "mahalanobis", "min_associations": 3, "mrpt_kdtree_candidates": false,
      "prune_after_steps": 0, "prune_min_associations": 2, "symmetrize_covariance": true})")
                .dump());
  EXPECT_EQ(ToJson(FastSlamOptions{}).dump(),
            nlohmann::json::parse(R"({"association": "nn", "confirm_associations": 2,
      "ess_threshold_fraction": 0.2, "ic_chi2_quantile": 0.999, "metric": "ml",
      "new_landmark_log_likelihood": null, "pose_regularisation": [1e-09, 1e-09, 1e-18],
      "proposal": "measurement-conditioned", "resampling": "systematic",
      "tentative_steps": 4})")
                .dump());
}

template <class Options>
std::string ErrorOf(const nlohmann::json& overrides) {
  Options o;
  const nlohmann::json before = ToJson(o);
  std::string error;
  try {
    ApplyJson(overrides, o);
  } catch (const std::invalid_argument& e) {
    error = e.what();
  }
  EXPECT_EQ(ToJson(o), before) << "options changed by " << overrides.dump();
  return error;
}

TEST(MrptBaselineParamsJson, ErrorsNameTheKey) {
  EXPECT_EQ(ErrorOf<MrptEkfSlamOptions>({{"prune_after", 5}}),
            "unknown parameter 'prune_after' (known: association, metric, ic_chi2_quantile, "
            "min_associations, mrpt_kdtree_candidates, prune_after_steps, "
            "prune_min_associations, symmetrize_covariance)");
  EXPECT_EQ(ErrorOf<MrptEkfSlamOptions>({{"association", "x"}}),
            "parameter 'association': expected one of \"jcbb\", \"nn\", got \"x\"");
  EXPECT_EQ(ErrorOf<MrptEkfSlamOptions>({{"ic_chi2_quantile", 1.0}}),
            "parameter 'ic_chi2_quantile': must be > 0 and < 1, got 1.0");
  EXPECT_EQ(ErrorOf<MrptEkfSlamOptions>({{"prune_min_associations", 0}}),
            "parameter 'prune_min_associations': must be >= 1, got 0");
  EXPECT_EQ(ErrorOf<FastSlamOptions>({{"proposal", "optimal"}}),
            "parameter 'proposal': expected one of \"motion-model\", "
            "\"measurement-conditioned\", got \"optimal\"");
  EXPECT_EQ(ErrorOf<FastSlamOptions>({{"new_landmark_log_likelihood", "fov"}}),
            "parameter 'new_landmark_log_likelihood': expected a number, got \"fov\"");
  EXPECT_EQ(ErrorOf<FastSlamOptions>({{"tentative_steps", 0}}),
            "parameter 'tentative_steps': must be >= 1, got 0");
  EXPECT_EQ(ErrorOf<FastSlamOptions>({{"pose_regularisation", {1e-9, 1e-9}}}),
            "parameter 'pose_regularisation': expected an array of 3 numbers, got "
            "[1e-09,1e-09]");
  EXPECT_EQ(ErrorOf<FastSlamOptions>({{"pose_regularisation", {1e-9, -1e-9, 0}}}),
            "parameter 'pose_regularisation': must be >= 0, got -1e-09");
  EXPECT_EQ(ErrorOf<FastSlamOptions>({{"resampling", "sys"}}),
            "parameter 'resampling': expected one of \"multinomial\", \"residual\", "
            "\"stratified\", \"systematic\", got \"sys\"");
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
