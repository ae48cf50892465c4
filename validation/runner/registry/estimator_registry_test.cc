#include "validation/runner/registry/estimator_registry.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "datasets/scenario_generator.h"
#include "src/core/random.h"
#include "validation/runner/registry/scenario_defaults.h"

namespace phdslam::validation {
namespace {

datasets::Scenario TwoStepScenario() {
  datasets::Scenario s;
  s.name = "tiny";
  s.initial_pose = Pose(1.0, 2.0, 0.0);
  s.control_noise_cov = Vec2(0.01, 0.0001).asDiagonal();
  datasets::ScenarioStep first;
  first.data.times = {0.0};
  datasets::ScenarioStep second;
  second.data.times = {0.0, 1.0};
  second.data.controls = {Control(2.0, 1e-12)};
  second.data.measurements = {Measurement(5.0, 0.0)};
  s.steps = {first, second};
  return s;
}

TEST(EstimatorTable, HasOdometryAndUniqueNames) {
  const auto& table = EstimatorTable();
  ASSERT_FALSE(table.empty());
  std::set<std::string> names;
  for (const EstimatorEntry& e : table) {
    EXPECT_TRUE(names.insert(e.name).second) << e.name << " twice";
    EXPECT_FALSE(e.description.empty()) << e.name;
    EXPECT_TRUE(e.resolved_parameters) << e.name;
    EXPECT_TRUE(e.HasFactory()) << e.name;
  }
  EXPECT_EQ(FindEstimator("odometry").name, "odometry");
}

TEST(FindEstimator, UnknownNameListsTheKnownOnes) {
  try {
    FindEstimator("phd9");
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("'phd9'"), std::string::npos) << what;
    EXPECT_NE(what.find("odometry"), std::string::npos) << what;
  }
}

TEST(OdometryEntry, DeadReckonsTheScenario) {
  const datasets::Scenario scenario = TwoStepScenario();
  const filters::EstimatorContext context = scenario.PublicContext();
  EstimatorRequest request;
  request.name = "odometry";
  request.context = &context;
  const EstimatorEntry& entry = FindEstimator("odometry");
  EXPECT_EQ(entry.resolved_parameters(request), nlohmann::json::object());
  auto estimator = entry.make_online(request);
  const filters::StepOutput first = estimator->Step(scenario.steps[0].data);
  EXPECT_TRUE(first.pose.isApprox(scenario.initial_pose));
  const filters::StepOutput second = estimator->Step(scenario.steps[1].data);
  // Straight ahead at 2 m/s for 1 s from heading 0.
  EXPECT_NEAR(second.pose(0), 3.0, 1e-9);
  EXPECT_NEAR(second.pose(1), 2.0, 1e-9);
  ASSERT_EQ(estimator->Map().size(), 1u);
  EXPECT_NEAR(estimator->Map().means[0](0), 8.0, 1e-9);
}

TEST(OdometryEntry, RejectsParticlesAndParameters) {
  const datasets::Scenario scenario = TwoStepScenario();
  const filters::EstimatorContext context = scenario.PublicContext();
  EstimatorRequest request;
  request.name = "odometry";
  request.context = &context;
  request.particles = 10;
  const EstimatorEntry& entry = FindEstimator("odometry");
  EXPECT_THROW(entry.resolved_parameters(request), std::invalid_argument);
  request.particles = 1;
  request.overrides = {{"hypotheses", 3}};
  EXPECT_THROW(entry.resolved_parameters(request), std::invalid_argument);
  request.overrides = nlohmann::json::object();
  request.context = nullptr;
  EXPECT_THROW(entry.make_online(request), std::invalid_argument);
}

// The posterior Cramer-Rao bounds: batch entries that read the truth and are marked as bounds,
// one particle, refused when the run is planned on a scenario without a true map.
TEST(BoundEntries, AreTruthReadingDeterministicBoundsRefusedOnVictoriaPark) {
  for (const std::string name : {"pcrb", "pcrb-smoother"}) {
    const EstimatorEntry& entry = FindEstimator(name);
    EXPECT_TRUE(entry.bound && entry.batch && entry.reads_truth) << name;
    EstimatorRequest request;
    request.name = name;
    request.scenario_name = "paper-synthetic";
    EXPECT_EQ(entry.resolved_parameters(request).at("detection_model"), "conditioned");
    request.particles = 2;
    EXPECT_THROW(entry.resolved_parameters(request), SingleParticleOnly) << name;
    request.particles = 1;
    request.overrides = {{"detection_model", "enumerated"}};
    EXPECT_THROW(entry.resolved_parameters(request), std::invalid_argument) << name;
    request.overrides = nlohmann::json::object();
    request.scenario_name = "victoria-park";
    try {
      entry.resolved_parameters(request);
      ADD_FAILURE() << name << " accepted victoria-park";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("victoria-park"), std::string::npos) << e.what();
    }
  }
}

TEST(PhdSlamEntries, VictoriaParkResamplingThresholdDependsOnTheVariant) {
  EstimatorRequest request;
  request.scenario_name = "victoria-park";
  request.particles = 5;
  const auto threshold = [&](const std::string& name) {
    request.name = name;
    const nlohmann::json p = FindEstimator(name).resolved_parameters(request);
    EXPECT_EQ(p.at("ess_threshold_kind"), "absolute") << name;
    return p.at("ess_threshold").get<double>();
  };
  EXPECT_EQ(threshold("phd1"), 2.5);
  EXPECT_EQ(threshold("phd2a"), 2.5);
  EXPECT_EQ(threshold("phd2b"), 1.0);
  EXPECT_EQ(threshold("phd3"), 1.0);
  EXPECT_EQ(threshold("rbphd"), 2.5);
  // The synthetic scenario: 0.2 N for every variant.
  request.scenario_name = "paper-synthetic";
  request.name = "phd1";
  EXPECT_EQ(FindEstimator("phd1").resolved_parameters(request).at("ess_threshold"), 0.2);
}

TEST(LabelledFilterSurvival, KeepsThePapersRatioOfDeathToMissedDetection) {
  // (1 - p_S) / (1 - pD) = 0.05 / 0.3 at every pD.
  EXPECT_NEAR(SurvivalProbabilityForDetection(0.95), 1.0 - 0.05 / 0.3 * 0.05, 1e-15);
  EXPECT_NEAR(SurvivalProbabilityForDetection(0.4), 1.0 - 0.05 / 0.3 * 0.6, 1e-15);
  EXPECT_EQ(SurvivalProbabilityForDetection(0.7), 0.95);  // the paper's point, exactly
  EXPECT_NEAR(SurvivalProbabilityForDetection(0.98), 1.0 - 0.05 / 0.3 * 0.02, 1e-15);
  // Near pD = 1 the death hypothesis keeps a weight of at least 0.002.
  EXPECT_EQ(SurvivalProbabilityForDetection(0.99), 0.998);
  EXPECT_EQ(SurvivalProbabilityForDetection(1.0), 0.998);
  for (const double bad : {0.0, -0.1, 1.01, std::nan("")}) {
    EXPECT_THROW(SurvivalProbabilityForDetection(bad), std::invalid_argument) << bad;
  }
}

TEST(LabelledFilterSurvival, NominalDetectionProbabilityOfResolvedScenarioOptions) {
  EXPECT_EQ(NominalDetectionProbability({{"detection_probability", 0.95}, {"steps", 10}}), 0.95);
  // A range-dependent pD (Victoria Park): the nominal value, not the maximum.
  EXPECT_EQ(NominalDetectionProbability(
                {{"detection_probability_max", 0.8}, {"detection_probability_nominal", 0.6}}),
            0.6);
  EXPECT_FALSE(NominalDetectionProbability({{"steps", 10}}).has_value());
}

TEST(LabelledFilterSurvival, FollowsTheScenarioDetectionProbabilityUnlessGivenOrSetPerScenario) {
  EstimatorRequest request;
  request.particles = 10;
  const auto survival = [&](const std::string& name) {
    request.name = name;
    return FindEstimator(name)
        .resolved_parameters(request)
        .at("survival_probability")
        .get<double>();
  };
  request.scenario_name = "paper-synthetic";
  request.detection_probability = 0.95;
  for (const char* name : {"glmb2", "glmb1", "lmb"}) {
    EXPECT_NEAR(survival(name), 1.0 - 0.05 / 0.3 * 0.05, 1e-15) << name;
  }
  // The delta-GLMB paper's simulation keeps the paper's 0.95 whatever its pD.
  request.scenario_name = "glmb-sim";
  for (const char* name : {"glmb2", "glmb1", "lmb"}) {
    EXPECT_EQ(survival(name), 0.95) << name;
  }
  // Victoria Park's range-dependent pD: the measured 0.998, not the rule's 0.95 at its nominal 0.7.
  request.scenario_name = "victoria-park";
  request.detection_probability = 0.7;
  for (const char* name : {"glmb2", "glmb1", "lmb"}) {
    EXPECT_EQ(survival(name), 0.998) << name;
  }
  // An explicit value always wins, on Victoria Park as elsewhere.
  request.overrides = {{"survival_probability", 0.95}};
  EXPECT_EQ(survival("lmb"), 0.95);
  request.scenario_name = "paper-synthetic";
  request.detection_probability = 0.95;
  request.overrides = {{"survival_probability", 0.97}};
  EXPECT_EQ(survival("glmb2"), 0.97);
  // No known pD: the estimator's own default.
  request.overrides = nlohmann::json::object();
  request.detection_probability.reset();
  EXPECT_EQ(survival("glmb2"), 0.95);
  // Estimators without a survival probability are unchanged by the scenario's pD.
  request.name = "phd3";
  const nlohmann::json without = FindEstimator("phd3").resolved_parameters(request);
  request.detection_probability = 0.95;
  EXPECT_EQ(FindEstimator("phd3").resolved_parameters(request), without);
}

TEST(RbPhdEntry, IsPhd1WithTheSingleFeatureWeight) {
  EstimatorRequest request;
  request.scenario_name = "paper-synthetic";
  request.particles = 10;
  request.name = "rbphd";
  nlohmann::json rb = FindEstimator("rbphd").resolved_parameters(request);
  EXPECT_EQ(rb.at("weighting"), "single-feature");
  request.name = "phd1";
  nlohmann::json phd1 = FindEstimator("phd1").resolved_parameters(request);
  EXPECT_EQ(phd1.at("weighting"), "paper-46");
  rb.erase("weighting");
  phd1.erase("weighting");
  EXPECT_EQ(rb, phd1);  // every other parameter is phd1's
  request.name = "rbphd";
  request.overrides = {{"weighting", "empty-map"}};
  EXPECT_EQ(FindEstimator("rbphd").resolved_parameters(request).at("weighting"), "empty-map");
}

TEST(MrptEkfPostProcessed, RunsTheSameFilterAndReportsASubsetOfItsMap) {
  bool built = false;
  for (const EstimatorEntry& e : EstimatorTable()) built = built || e.name == "mrpt-ekf";
  if (!built) GTEST_SKIP() << "built without MRPT";
  datasets::GeneratorOptions o;
  o.steps = 60;
  o.landmarks = 40;
  o.corridor_half_width = 60.0;
  const datasets::Scenario scenario = datasets::GenerateScenario(o, 3);
  const filters::EstimatorContext context = scenario.PublicContext();
  EstimatorRequest request;
  request.context = &context;
  // Nearest-neighbour association: the property holds for either method, and MRPT's JCBB on this
  // cluttered corridor takes about 25 s (MRPT's own tests and the contract tests run JCBB).
  request.overrides = {{"association", "nn"}};
  request.name = "mrpt-ekf";
  auto raw = FindEstimator("mrpt-ekf").make_online(request);
  request.name = "mrpt-ekf-postprocessed";
  auto post = FindEstimator("mrpt-ekf-postprocessed").make_online(request);
  for (const datasets::ScenarioStep& step : scenario.steps) {
    const filters::StepOutput a = raw->Step(step.data);
    const filters::StepOutput b = post->Step(step.data);
    ASSERT_EQ(a.pose, b.pose);
  }
  const filters::MapEstimate raw_map = raw->Map();
  const filters::MapEstimate post_map = post->Map();
  EXPECT_GT(post_map.size(), 0u);
  EXPECT_LT(post_map.size(), raw_map.size());  // the clutter landmarks are dropped
  for (const Landmark& m : post_map.means) {
    bool found = false;
    for (const Landmark& r : raw_map.means) found = found || r == m;
    EXPECT_TRUE(found) << m.transpose();
  }
}

bool Registered(const std::string& name) {
  for (const EstimatorEntry& e : EstimatorTable()) {
    if (e.name == name) return true;
  }
  return false;
}

std::string ResolveError(const std::string& name, const nlohmann::json& overrides) {
  EstimatorRequest request;
  request.name = name;
  request.scenario_name = "generated";
  request.overrides = overrides;
  try {
    FindEstimator(name).resolved_parameters(request);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

// A key fixed by the estimator's name accepts that value (a no-op) and rejects any other.
TEST(ReferenceEstimators, KeysFixedByTheNameAcceptOnlyTheirOwnValue) {
  if (!Registered("smoother-filter")) GTEST_SKIP() << "built without Ceres";
  for (const auto& [name, mode] : {std::pair<std::string, std::string>{"smoother-known", "known"},
                                   {"smoother-filter", "filter"},
                                   {"smoother-unknown", "unknown"}}) {
    EstimatorRequest request;
    request.name = name;
    request.scenario_name = "generated";
    request.overrides = {{"association", mode}};
    EXPECT_EQ(FindEstimator(name).resolved_parameters(request).at("association"), mode);
  }
  EXPECT_EQ(ResolveError("smoother-filter", {{"association", "known"}}),
            "estimator 'smoother-filter': parameter 'association': fixed by the estimator's name "
            "(smoother-known, smoother-filter, smoother-unknown): expected \"filter\", got "
            "\"known\"");
  EXPECT_EQ(ResolveError("smoother-known", {{"robust_loss", "tukey"}}),
            "estimator 'smoother-known': SmootherOptions.robust_loss: expected \"cauchy\", "
            "\"huber\" or \"none\", got \"tukey\"");
}

// The incremental solve's settings are refused without initialisation=incremental (they would
// change nothing), accepted with it and at their default value.
TEST(ReferenceEstimators, IncrementalSettingsNeedTheIncrementalInitialisation) {
  if (!Registered("smoother-known")) GTEST_SKIP() << "built without Ceres";
  for (const char* key : {"incremental_chunk_steps", "incremental_relocalisation_scans",
                          "incremental_static_point_failures"}) {
    const std::string error = ResolveError("smoother-unknown", {{key, 7}});
    EXPECT_NE(error.find(std::string("parameter '") + key +
                         "' has no effect with "
                         "initialisation=batch; it is used only with initialisation=incremental"),
              std::string::npos)
        << error;
    EXPECT_EQ(ResolveError("smoother-unknown", {{key, 7}, {"initialisation", "incremental"}}), "");
  }
  EXPECT_EQ(ResolveError("smoother-unknown", {{"incremental_chunk_steps", 25}}), "");
  EXPECT_NE(ResolveError("smoother-known", {{"incremental_relocalisation_std", 2.0}}), "");
  EXPECT_NE(ResolveError("smoother-known", {{"start_particles", 10}}).find("start_from=phd3"),
            std::string::npos);
  EXPECT_EQ(ResolveError("smoother-known", {{"start_particles", 10}, {"start_from", "phd3"}}), "");
}

// One rule for every estimator: a parameter that has no effect in the chosen mode is refused,
// naming the mode that would use it; at its default, or with that mode, it is accepted.
TEST(EstimatorRegistry, ParametersWithoutEffectInTheChosenModeAreRefused) {
  struct Case {
    std::string estimator;
    nlohmann::json overrides;
    std::string mode;  // the mode the error names
    nlohmann::json with_mode;
  };
  const std::vector<Case> cases = {
      {"phd3",
       {{"resampling", false}, {"ess_threshold", 0.5}},
       "resampling=true",
       {{"resampling", true}, {"ess_threshold", 0.5}}},
      {"phd1",
       {{"resampling", false}, {"ess_threshold_kind", "absolute"}},
       "resampling=true",
       {{"ess_threshold_kind", "absolute"}}},
      {"oracle",
       {{"resampling", false}, {"ess_threshold", 0.9}},
       "resampling=true",
       {{"ess_threshold", 0.9}}},
      {"glmb2",
       {{"resampling", "every-step"}, {"ess_threshold", 0.4}},
       "resampling=ess",
       {{"resampling", "ess"}, {"ess_threshold", 0.4}}},
      {"glmb2",
       {{"birth_rule", "continuous"}, {"birth_assigned_threshold", 0.6}},
       "birth_rule=thresholded",
       {{"birth_rule", "thresholded"}, {"birth_assigned_threshold", 0.6}}},
      {"pcrb",
       {{"gate_sigma", 4.0}},
       "detection_model=irf",
       {{"detection_model", "irf"}, {"gate_sigma", 4.0}}},
      {"pcrb-smoother",
       {{"irf_samples", 5000}},
       "detection_model=irf",
       {{"detection_model", "irf"}, {"irf_samples", 5000}}},
  };
  for (const Case& c : cases) {
    const std::string error = ResolveError(c.estimator, c.overrides);
    EXPECT_NE(error.find("has no effect with"), std::string::npos) << c.estimator << ": " << error;
    EXPECT_NE(error.find("it is used only with " + c.mode), std::string::npos)
        << c.estimator << ": " << error;
    EXPECT_EQ(ResolveError(c.estimator, c.with_mode), "") << c.estimator;
  }
  // The resolved parameters read back as overrides change nothing, so they are accepted.
  EstimatorRequest request;
  request.name = "phd3";
  request.scenario_name = "generated";
  request.overrides = {{"resampling", false}};
  request.overrides = FindEstimator("phd3").resolved_parameters(request);
  request.overrides.erase("particles");
  EXPECT_NO_THROW(FindEstimator("phd3").resolved_parameters(request));
  if (Registered("mrpt-ekf")) {
    EXPECT_NE(ResolveError("mrpt-ekf", {{"prune_after_steps", 0}, {"prune_min_associations", 3}})
                  .find("used only with prune_after_steps other than 0"),
              std::string::npos);
    EXPECT_EQ(ResolveError("mrpt-ekf", {{"prune_min_associations", 3}}), "");
  }
}

// The fixed-lag smoother's run-length bounds are checked when the plan knows the run's length.
TEST(ReferenceEstimators, WindowBoundsAreCheckedWithThePlannedSteps) {
  if (!Registered("window")) GTEST_SKIP() << "built without Ceres";
  EstimatorRequest request;
  request.name = "window";
  request.scenario_name = "generated";
  request.steps = 200;
  request.overrides = {{"solve_every", 1000}};
  try {
    FindEstimator("window").resolved_parameters(request);
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("solve_every: 1000 is longer than the run (200 steps)"),
              std::string::npos)
        << e.what();
  }
  request.overrides = {{"solve_every", 200}};
  EXPECT_EQ(FindEstimator("window").resolved_parameters(request).at("solve_every"), 200);
  request.overrides = nlohmann::json::object();
  request.steps = 5;  // the default window (20) is shortened only when the run is built
  EXPECT_EQ(FindEstimator("window").resolved_parameters(request).at("window_length"), 20);
}

// The start from a PHD-SLAM 3.0 trajectory: for the known and own associations, not for the
// filter's, which starts from its own filter's trajectory.
TEST(ReferenceEstimators, StartFromPhd3) {
  if (!Registered("smoother-unknown")) GTEST_SKIP() << "built without Ceres";
  EXPECT_EQ(ResolveError("smoother-unknown", {{"start_from", "phd3"}, {"start_particles", 1}}), "");
  EXPECT_EQ(ResolveError("smoother-known", {{"start_from", "phd3"}}), "");
  EXPECT_EQ(ResolveError("smoother-filter", {{"start_from", "phd3"}}),
            "estimator 'smoother-filter': SmootherOptions.start_from: the filter association "
            "starts from its own filter's trajectory");
  EXPECT_NE(ResolveError("smoother-unknown", {{"start_particles", 0}}), "");
}

// On Victoria Park the own association takes the window's labels and trajectory by default, from
// dead reckoning, and the window joint compatibility (scenario_defaults.cc); a start trajectory
// given without front_end takes the pass, an explicit front_end with it is refused, and a path
// asked for with the dead-reckoning start is refused, naming start_path.
TEST(ReferenceEstimators, VictoriaParkTakesTheWindowAsTheOwnFrontEnd) {
  if (!Registered("smoother-unknown")) GTEST_SKIP() << "built without Ceres";
  EstimatorRequest request;
  request.name = "smoother-unknown";
  request.scenario_name = "victoria-park";
  const auto start = [&](const nlohmann::json& overrides) {
    request.overrides = overrides;
    const nlohmann::json p = FindEstimator("smoother-unknown").resolved_parameters(request);
    return p.at("front_end").get<std::string>() + " " + p.at("start_from").get<std::string>() +
           " " + p.at("start_path").get<std::string>();
  };
  EXPECT_EQ(start(nlohmann::json::object()), "window dead-reckoning estimate");
  EXPECT_EQ(start({{"start_from", "phd3"}}), "pass phd3 estimate");
  EXPECT_EQ(start({{"start_from", "phd3"}, {"start_path", "best-particle-path"}}),
            "pass phd3 best-particle-path");
  EXPECT_EQ(start({{"front_end", "pass"}}), "pass dead-reckoning estimate");
  const auto refused = [&](const nlohmann::json& overrides, const std::string& field) {
    request.overrides = overrides;
    try {
      FindEstimator("smoother-unknown").resolved_parameters(request);
      ADD_FAILURE() << overrides.dump() << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  };
  refused({{"start_from", "phd3"}, {"front_end", "window"}}, "start_from");
  refused({{"start_path", "best-particle-path"}}, "start_path");
  const auto window = [&](const std::string& scenario) {
    return FindEstimator("window").resolved_parameters(
        {.name = "window", .scenario_name = scenario});
  };
  EXPECT_EQ(window("victoria-park").at("assignment"), "jcbb");
  EXPECT_DOUBLE_EQ(window("victoria-park").at("jcbb_null_intensity").get<double>(), 0.035);
  EXPECT_EQ(window("victoria-park").at("landmark_keep_steps"), 200);
  EXPECT_EQ(window("paper-synthetic").at("landmark_keep_steps"), 0);
  // Elsewhere the own association keeps its pass; smoother-filter keeps PHD-SLAM 3.0's
  // association on Victoria Park.
  request.scenario_name = "paper-synthetic";
  EXPECT_EQ(start(nlohmann::json::object()), "pass dead-reckoning estimate");
  EXPECT_EQ(FindEstimator("smoother-filter")
                .resolved_parameters({.name = "smoother-filter", .scenario_name = "victoria-park"})
                .at("filter_front_end")
                .get<std::string>(),
            "phd3");
  EXPECT_EQ(ScenarioParameterDefaults("victoria-park", "smoother-known"), nlohmann::json::object());
}

// On MRCLAM the known and own associations build their graph incrementally by default
// (scenario_defaults.cc); an explicit value wins; elsewhere, and for smoother-filter, the default
// stays the solve from dead reckoning.
TEST(ReferenceEstimators, MrclamSolvesTheSmoothersIncrementallyByDefault) {
  if (!Registered("smoother-known")) GTEST_SKIP() << "built without Ceres";
  const auto initialisation = [](const std::string& name, const std::string& scenario,
                                 const nlohmann::json& overrides) {
    EstimatorRequest request;
    request.name = name;
    request.scenario_name = scenario;
    request.overrides = overrides;
    return FindEstimator(name).resolved_parameters(request).at("initialisation").get<std::string>();
  };
  const nlohmann::json none = nlohmann::json::object();
  EXPECT_EQ(initialisation("smoother-known", "mrclam", none), "incremental");
  EXPECT_EQ(initialisation("smoother-unknown", "mrclam", none), "incremental");
  EXPECT_EQ(initialisation("smoother-known", "mrclam", {{"initialisation", "batch"}}), "batch");
  EXPECT_EQ(initialisation("smoother-filter", "mrclam", none), "batch");
  EXPECT_EQ(initialisation("smoother-known", "paper-synthetic", none), "batch");
}

// On MRCLAM the window has joint compatibility and the moving-object test, and its labels are
// both batch smoothers' front end; on the synthetic scenario neither.
TEST(ReferenceEstimators, TheWindowAndItsLabelsAreTheFrontEndsOnMrclam) {
  if (!Registered("window")) GTEST_SKIP() << "built without Ceres";
  const auto resolved = [](const std::string& scenario, const nlohmann::json& overrides) {
    EstimatorRequest request;
    request.name = "window";
    request.scenario_name = scenario;
    request.overrides = overrides;
    return FindEstimator("window").resolved_parameters(request);
  };
  const nlohmann::json none = nlohmann::json::object();
  const nlohmann::json mrclam = resolved("mrclam", none);
  EXPECT_EQ(mrclam.at("assignment"), "jcbb");
  EXPECT_DOUBLE_EQ(mrclam.at("static_point_chi2").get<double>(), 9.21);
  EXPECT_EQ(mrclam.at("static_point_failures"), 3);
  const nlohmann::json synthetic = resolved("paper-synthetic", none);
  EXPECT_EQ(synthetic.at("assignment"), "nearest_neighbour");
  EXPECT_DOUBLE_EQ(synthetic.at("static_point_chi2").get<double>(), 0.0);
  EXPECT_EQ(FindEstimator("smoother-filter")
                .resolved_parameters({.name = "smoother-filter", .scenario_name = "mrclam"})
                .at("filter_front_end"),
            "window");
  const nlohmann::json unknown =
      FindEstimator("smoother-unknown")
          .resolved_parameters({.name = "smoother-unknown", .scenario_name = "mrclam"});
  EXPECT_EQ(unknown.at("front_end"), "window");
  EXPECT_DOUBLE_EQ(unknown.at("merge_position_std").get<double>(), 0.0);
  EXPECT_EQ(
      FindEstimator("smoother-unknown")
          .resolved_parameters({.name = "smoother-unknown", .scenario_name = "paper-synthetic"})
          .at("front_end"),
      "pass");
  // A value given by the user wins over the scenario's default.
  EXPECT_DOUBLE_EQ(
      resolved("mrclam", {{"static_point_chi2", 0.0}}).at("static_point_chi2").get<double>(), 0.0);
}

TEST(ReferenceEstimators, FastSlamProposalIsFixedByTheName) {
  if (!Registered("fastslam1")) GTEST_SKIP() << "built without MRPT";
  EXPECT_EQ(ResolveError("fastslam1", {{"proposal", "motion-model"}}), "");
  EXPECT_EQ(ResolveError("fastslam1", {{"proposal", "measurement-conditioned"}}),
            "estimator 'fastslam1': parameter 'proposal': fixed by the estimator's name "
            "(fastslam1, fastslam2): expected \"motion-model\", got "
            "\"measurement-conditioned\"");
  EXPECT_EQ(ResolveError("mrpt-ekf", {{"prune_after_steps", -1}}),
            "estimator 'mrpt-ekf': parameter 'prune_after_steps': must be >= 0, got -1");
}

TEST(RunStreamSeed, FollowsTheDocumentedDerivation) {
  EXPECT_EQ(RunStreamSeed("exp", 7, "phd3", 10),
            DeriveSeed(HashName("exp"), 7, DeriveSeed(HashName("phd3"), 10)));
  // Every part matters.
  const std::uint64_t base = RunStreamSeed("exp", 7, "phd3", 10);
  EXPECT_NE(base, RunStreamSeed("exp2", 7, "phd3", 10));
  EXPECT_NE(base, RunStreamSeed("exp", 8, "phd3", 10));
  EXPECT_NE(base, RunStreamSeed("exp", 7, "phd1", 10));
  EXPECT_NE(base, RunStreamSeed("exp", 7, "phd3", 100));
}

}  // namespace
}  // namespace phdslam::validation
