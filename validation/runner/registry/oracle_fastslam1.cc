// `oracle-fs1`: FastSLAM 1.0 with the known data association. It is the worked example of adding
// an estimator (validation/README.md, "Adding an estimator"): a filter on the particle-filter
// skeleton is a map model and an importance density, so this one is the oracle's known-association
// landmark EKFs (oracle::OracleMapModel) with PHD-SLAM 1.0's transition density as proposal, the
// oracle's parameters, and this file's one table entry. Beside the oracle (the same map with the
// IPL proposal) it shows what the optimal-kernel proposal buys when the association is known.
#include <memory>

#include "oracle/oracle_params_json.h"
#include "oracle/oracle_rbpf.h"
#include "src/filters/importance_density.h"
#include "validation/runner/registry/estimator_registry.h"

namespace phdslam::validation {

EstimatorEntry OracleFastSlam1Entry() {
  EstimatorEntry e;
  e.name = "oracle-fs1";
  e.description =
      "FastSLAM 1.0 with the known data association (reads the hidden origin labels): the "
      "oracle's landmark EKFs with the transition density as proposal; scenarios with origin "
      "labels (the simulated ones and MRCLAM; not victoria-park)";
  e.reads_truth = true;
  e.parameters = oracle::OracleParamsTable().Descriptions();
  e.resolved_parameters = [](const EstimatorRequest& r) {
    RequireKnownOrigins(r);
    return oracle::ToJson(ResolveParameters(r, oracle::OracleParamsTable()));
  };
  e.make_online_with_truth =
      [](const EstimatorRequest& r,
         const datasets::Scenario& with_truth) -> std::unique_ptr<filters::OnlineEstimator> {
    return oracle::MakeKnownAssociationFilter(
        with_truth.PublicContext(), oracle::ScenarioOrigins(with_truth),
        ResolveParameters(r, oracle::OracleParamsTable()),
        std::make_unique<filters::TransitionDensity>(), r.stream_seed);
  };
  return e;
}

}  // namespace phdslam::validation
