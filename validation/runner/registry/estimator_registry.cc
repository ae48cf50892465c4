#include "validation/runner/registry/estimator_registry.h"

#include <stdexcept>

#include "oracle/oracle_params_json.h"
#include "oracle/oracle_rbpf.h"
#include "src/core/random.h"
#include "src/filters/odometry_estimator.h"
#include "src/filters/phd_slam_family.h"
#include "src/filters/phd_slam_params_json.h"
#include "src/filters/sc_phd_slam.h"
#include "src/glmb/glmb_slam.h"
#include "validation/runner/registry/parameter_overrides.h"

namespace phdslam::validation {

const filters::EstimatorContext& RequireContext(const EstimatorRequest& request) {
  if (request.context == nullptr) {
    throw std::invalid_argument("estimator '" + request.name + "': no scenario given");
  }
  return *request.context;
}

void RequireSingleParticle(const EstimatorRequest& request) {
  if (request.particles != 1) {
    throw SingleParticleOnly("estimator '" + request.name +
                             "' is deterministic and takes --particles 1, got " +
                             std::to_string(request.particles));
  }
}

bool IsSingleParticleEstimator(const EstimatorEntry& entry, const std::string& scenario_name,
                               const nlohmann::json& overrides) {
  if (!entry.resolved_parameters) return false;
  EstimatorRequest probe;
  probe.name = entry.name;
  probe.particles = 2;
  probe.scenario_name = scenario_name;
  probe.overrides = overrides;
  try {
    entry.resolved_parameters(probe);
  } catch (const SingleParticleOnly&) {
    return true;
  } catch (const std::exception&) {
    return false;  // another error, reported when the plan is checked
  }
  return false;
}

void RequireKnownOrigins(const EstimatorRequest& request) {
  if (request.scenario_name == "victoria-park") {
    throw std::invalid_argument("estimator '" + request.name +
                                "' needs the hidden landmark identities, which scenario '" +
                                request.scenario_name + "' does not have");
  }
}

namespace {

EstimatorEntry OdometryEntry() {
  EstimatorEntry e;
  e.name = "odometry";
  e.description =
      "dead reckoning: the odometry integrated from the initial pose, no map update "
      "(its map is the last scan's measurements); one particle";
  e.resolved_parameters = [](const EstimatorRequest& request) {
    RequireSingleParticle(request);
    return ApplyOverrides(nlohmann::json::object(), request.overrides,
                          "estimator '" + request.name + "'");
  };
  e.make_online = [](const EstimatorRequest& request) -> std::unique_ptr<filters::OnlineEstimator> {
    return std::make_unique<filters::OdometryEstimator>(RequireContext(request));
  };
  return e;
}

EstimatorEntry PhdSlamEntry(const filters::PhdSlamVariant& variant) {
  EstimatorEntry e;
  e.name = variant.name;
  e.description = variant.description;
  e.parameters = filters::PhdSlamParamsTable().Descriptions();
  e.resolved_parameters = [](const EstimatorRequest& request) {
    return filters::ToJson(ResolveParameters(request, filters::PhdSlamParamsTable()));
  };
  e.make_online = [](const EstimatorRequest& request) -> std::unique_ptr<filters::OnlineEstimator> {
    return filters::MakePhdSlam(request.name, RequireContext(request),
                                ResolveParameters(request, filters::PhdSlamParamsTable()),
                                request.stream_seed);
  };
  return e;
}

filters::PhdSlamParams RbPhdDefaults() {
  filters::PhdSlamParams p;
  p.weighting = filters::RbPhdWeighting::kSingleFeature;
  return p;
}

EstimatorEntry RbPhdEntry() {
  EstimatorEntry e;
  e.name = "rbphd";
  e.description =
      "RB-PHD-SLAM of Mullane, Vo, Adams & Vo (2011): PHD-SLAM 1.0's transition density with the "
      "single-feature map particle weight (the comparator of single-cluster PHD SLAM's paper); "
      "--set weighting=empty-map for the empty-map strategy";
  e.parameters = filters::PhdSlamParamsTable().Descriptions();
  e.resolved_parameters = [](const EstimatorRequest& r) {
    return filters::ToJson(ResolveParameters(r, filters::PhdSlamParamsTable(), RbPhdDefaults()));
  };
  e.make_online = [](const EstimatorRequest& r) -> std::unique_ptr<filters::OnlineEstimator> {
    return filters::MakePhdSlam(
        "phd1", RequireContext(r),
        ResolveParameters(r, filters::PhdSlamParamsTable(), RbPhdDefaults()), r.stream_seed);
  };
  return e;
}

oracle::OracleParams ResolveOracleParams(const EstimatorRequest& request) {
  RequireKnownOrigins(request);
  return ResolveParameters(request, oracle::OracleParamsTable());
}

EstimatorEntry OracleEntry() {
  EstimatorEntry e;
  e.name = "oracle";
  e.description =
      "oracle RBPF: FastSLAM 2.0 with the known data association (reads the hidden origin "
      "labels) and the partitioned IPL proposal; scenarios with origin labels (the simulated "
      "ones and MRCLAM, whose barcodes name the landmarks; not victoria-park)";
  e.reads_truth = true;
  e.parameters = oracle::OracleParamsTable().Descriptions();
  e.resolved_parameters = [](const EstimatorRequest& request) {
    return oracle::ToJson(ResolveOracleParams(request));
  };
  e.make_online_with_truth =
      [](const EstimatorRequest& request,
         const datasets::Scenario& with_truth) -> std::unique_ptr<filters::OnlineEstimator> {
    return oracle::MakeOracle(with_truth, ResolveOracleParams(request), request.stream_seed);
  };
  return e;
}

EstimatorEntry ScPhdSlamEntry() {
  EstimatorEntry e;
  e.name = "scphd";
  e.description =
      "single-cluster PHD SLAM (Lee, Clark & Salvi 2012): N pose parents shotgun-sampled into M "
      "children with GM-PHD maps, single-cluster likelihood weights, pruned to the N best; "
      "expected a posteriori pose";
  e.parameters = filters::ScPhdSlamParamsTable().Descriptions();
  e.resolved_parameters = [](const EstimatorRequest& r) {
    return filters::ToJson(ResolveParameters(r, filters::ScPhdSlamParamsTable()));
  };
  e.make_online = [](const EstimatorRequest& r) -> std::unique_ptr<filters::OnlineEstimator> {
    return std::make_unique<filters::ScPhdSlam>(
        RequireContext(r), ResolveParameters(r, filters::ScPhdSlamParamsTable()), r.stream_seed);
  };
  return e;
}

EstimatorEntry GlmbSlamEntry(const std::string& name, const std::string& description) {
  EstimatorEntry e;
  e.name = name;
  e.description = description;
  e.parameters = glmb::GlmbSlamParamsTable().Descriptions();
  e.resolved_parameters = [](const EstimatorRequest& r) {
    return glmb::ToJson(ResolveParameters(r, glmb::GlmbSlamParamsTable()));
  };
  e.make_online = [](const EstimatorRequest& r) -> std::unique_ptr<filters::OnlineEstimator> {
    const glmb::GlmbSlamParams params = ResolveParameters(r, glmb::GlmbSlamParamsTable());
    if (r.name == "lmb") return glmb::MakeLmbSlam(RequireContext(r), params, r.stream_seed);
    return glmb::MakeGlmbSlam(RequireContext(r), params, r.name == "glmb2", r.stream_seed);
  };
  return e;
}

}  // namespace

EstimatorEntry OracleFastSlam1Entry();  // oracle_fastslam1.cc: the worked example

namespace {

std::vector<EstimatorEntry> BuildTable() {
  std::vector<EstimatorEntry> table = {OdometryEntry()};
  for (const filters::PhdSlamVariant& v : filters::PhdSlamVariants()) {
    table.push_back(PhdSlamEntry(v));
  }
  table.push_back(RbPhdEntry());
  table.push_back(ScPhdSlamEntry());
  table.push_back(GlmbSlamEntry(
      "glmb2",
      "delta-GLMB-SLAM 2.0 (Moratuwage, Adams & Inostroza 2019): per-particle delta-GLMB maps "
      "updated by Gibbs sampling, the optimal-kernel pose proposal (--set kernel_weight=...)"));
  table.push_back(GlmbSlamEntry(
      "glmb1",
      "delta-GLMB-SLAM 1.0: per-particle delta-GLMB maps updated by Gibbs sampling, the motion "
      "model as pose proposal"));
  table.push_back(GlmbSlamEntry(
      "lmb",
      "LMB-SLAM as the delta-GLMB-SLAM paper ran it: per-particle LMB maps, one Gibbs-sampled "
      "delta-GLMB update per step, existence pruning 0.019, no clustering; motion-model proposal"));
  table.push_back(OracleEntry());
  table.push_back(OracleFastSlam1Entry());
  for (EstimatorEntry& e : MrptEstimators()) table.push_back(std::move(e));
  for (EstimatorEntry& e : CeresEstimators()) table.push_back(std::move(e));
  for (EstimatorEntry& e : BoundEstimators()) table.push_back(std::move(e));
  return table;
}

}  // namespace

const std::vector<EstimatorEntry>& EstimatorTable() {
  static const std::vector<EstimatorEntry> table = BuildTable();
  return table;
}

const EstimatorEntry& FindEstimator(const std::vector<EstimatorEntry>& table,
                                    const std::string& name) {
  std::string known;
  for (const EstimatorEntry& e : table) {
    if (e.name == name) return e;
    known += known.empty() ? e.name : ", " + e.name;
  }
  throw std::invalid_argument("unknown estimator '" + name + "' (known: " + known + ")");
}

const EstimatorEntry& FindEstimator(const std::string& name) {
  return FindEstimator(EstimatorTable(), name);
}

std::uint64_t RunStreamSeed(std::string_view experiment, std::uint64_t seed,
                            std::string_view estimator, int particles) {
  return DeriveSeed(HashName(experiment), seed,
                    DeriveSeed(HashName(estimator), static_cast<std::uint64_t>(particles)));
}

}  // namespace phdslam::validation
