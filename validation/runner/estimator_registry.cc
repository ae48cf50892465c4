#include "validation/runner/estimator_registry.h"

#include <stdexcept>

#include "src/core/random.h"
#include "src/filters/odometry_estimator.h"
#include "validation/runner/parameter_overrides.h"

namespace phdslam::validation {
namespace {

const datasets::Scenario& RequireScenario(const EstimatorRequest& request) {
  if (request.scenario == nullptr) {
    throw std::invalid_argument("estimator '" + request.name + "': no scenario given");
  }
  return *request.scenario;
}

void RequireSingleParticle(const EstimatorRequest& request) {
  if (request.particles != 1) {
    throw std::invalid_argument("estimator '" + request.name +
                                "' is deterministic and takes --particles 1, got " +
                                std::to_string(request.particles));
  }
}

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
    return std::make_unique<filters::OdometryEstimator>(
        filters::EstimatorContext::FromScenario(RequireScenario(request)));
  };
  return e;
}

}  // namespace

const std::vector<EstimatorEntry>& EstimatorTable() {
  static const std::vector<EstimatorEntry> table = {
      OdometryEntry(),
  };
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
