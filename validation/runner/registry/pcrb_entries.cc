// The posterior Cramer-Rao bounds as registry entries (docs/algorithms/pcrb.md): batch entries
// that read the truth and are marked as bounds, deterministic (one particle).
#include <memory>

#include "reference/pcrb/pcrb_estimator.h"
#include "reference/pcrb/pcrb_params.h"
#include "validation/runner/registry/estimator_registry.h"

namespace phdslam::validation {
namespace {

reference::pcrb::PcrbParams ResolvePcrbParams(const EstimatorRequest& request) {
  RequireSingleParticle(request);
  if (request.scenario_name == "victoria-park") {
    throw std::invalid_argument("estimator '" + request.name + "': scenario '" +
                                request.scenario_name +
                                "' has no true map or trajectory, which a bound needs");
  }
  return ResolveParameters(request, reference::pcrb::PcrbParamsTable());
}

EstimatorEntry BoundEntry(const std::string& name, reference::pcrb::BoundKind kind,
                          const std::string& description) {
  EstimatorEntry e;
  e.name = name;
  e.description = description;
  e.batch = true;
  e.reads_truth = true;
  e.bound = true;
  e.parameters = reference::pcrb::PcrbParamsTable().Descriptions();
  e.resolved_parameters = [](const EstimatorRequest& r) {
    return reference::pcrb::PcrbParamsTable().ToJson(ResolvePcrbParams(r));
  };
  e.make_batch = [kind](const EstimatorRequest& r) -> std::unique_ptr<datasets::BatchEstimator> {
    return std::make_unique<reference::pcrb::PcrbEstimator>(r.name, kind, ResolvePcrbParams(r),
                                                            r.stream_seed);
  };
  return e;
}

}  // namespace

std::vector<EstimatorEntry> BoundEstimators() {
  using reference::pcrb::BoundKind;
  return {BoundEntry("pcrb", BoundKind::kFiltering,
                     "BOUND, not an estimator: posterior Cramer-Rao bound of the filtering "
                     "problem at the truth (pose given the data up to each step, map "
                     "marginalised); --set detection_model=conditioned|irf (default "
                     "conditioned); synthetic scenarios and MRCLAM"),
          BoundEntry("pcrb-smoother", BoundKind::kSmoothing,
                     "BOUND, not an estimator: posterior Cramer-Rao bound of the smoothing "
                     "problem (the marginals of the whole graph's inverse Fisher information at "
                     "the truth); options as pcrb")};
}

}  // namespace phdslam::validation
