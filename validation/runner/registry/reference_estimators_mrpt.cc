// Registry entries of the MRPT baselines (built only when phdslam_reference_mrpt exists). Names,
// descriptions and parameters need no MRPT; only make_online constructs an estimator, through the
// plugin (reference/mrpt/mrpt_baselines_loader.h), so MRPT is loaded by the first such call only.
#include <memory>
#include <stdexcept>

#include "reference/mrpt/fastslam_options.h"
#include "reference/mrpt/mrpt_baseline_params_json.h"
#include "reference/mrpt/mrpt_baselines_loader.h"
#include "reference/mrpt/mrpt_ekf_slam_options.h"
#include "src/core/parameter_table.h"
#include "validation/runner/registry/estimator_registry.h"

namespace phdslam::validation {
namespace {

// The options' own checks (Validate) after the table's, naming the estimator.
template <class Options>
Options Validated(const EstimatorRequest& r, Options o) {
  try {
    o.Validate();
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("estimator '" + r.name + "': " + e.what());
  }
  return o;
}

// Track deletion is on by default here: stock MRPT (prune_after_steps = 0) keeps every clutter
// point as a landmark and cannot run 4000 cluttered scans (reference/mrpt/README.md).
reference::MrptEkfSlamOptions ResolveMrptEkf(const EstimatorRequest& r) {
  RequireSingleParticle(r);
  reference::MrptEkfSlamOptions defaults;
  defaults.prune_after_steps = 5;
  return Validated(r, ResolveParameters(r, reference::MrptEkfSlamOptionsTable(), defaults));
}

EstimatorEntry MrptEkfEntry() {
  EstimatorEntry e;
  e.name = "mrpt-ekf";
  e.description =
      "MRPT CRangeBearingKFSLAM2D EKF-SLAM, unknown association (JCBB, Mahalanobis, chi2 0.999) "
      "with track deletion and covariance symmetrisation added; raw map; one particle";
  e.parameters = reference::MrptEkfSlamOptionsTable().Descriptions();
  e.resolved_parameters = [](const EstimatorRequest& r) {
    return reference::ToJson(ResolveMrptEkf(r));
  };
  e.make_online = [](const EstimatorRequest& r) -> std::unique_ptr<filters::OnlineEstimator> {
    return reference::MakeMrptEkfSlam(RequireContext(r), ResolveMrptEkf(r),
                                      /*post_processed_map=*/false);
  };
  return e;
}

// The same EKF-SLAM run, reporting PostProcessedMap() (landmarks MRPT associated at least
// min_associations times) as its map: a post-processing step that is not part of MRPT's filter,
// under its own name so that no table mistakes it for the raw filter.

EstimatorEntry MrptEkfPostProcessedEntry() {
  EstimatorEntry e = MrptEkfEntry();
  e.name = "mrpt-ekf-postprocessed";
  e.description =
      "mrpt-ekf with a POST-PROCESSED map: only landmarks associated at least min_associations "
      "times (not part of MRPT's filter; trajectory identical to mrpt-ekf)";
  e.make_online = [](const EstimatorRequest& r) -> std::unique_ptr<filters::OnlineEstimator> {
    return reference::MakeMrptEkfSlam(RequireContext(r), ResolveMrptEkf(r),
                                      /*post_processed_map=*/true);
  };
  return e;
}

reference::FastSlamOptions ResolveFastSlam(const EstimatorRequest& r,
                                           reference::FastSlamProposal proposal) {
  if (r.particles < 1) {
    throw std::invalid_argument("estimator '" + r.name + "': --particles must be >= 1");
  }
  reference::FastSlamOptions defaults;
  defaults.proposal = proposal;
  reference::FastSlamOptions o =
      Validated(r, ResolveParameters(r, reference::FastSlamOptionsTable(), defaults));
  if (o.proposal != proposal) {
    throw std::invalid_argument(
        "estimator '" + r.name + "': parameter 'proposal': fixed by the estimator's name " +
        "(fastslam1, fastslam2): expected " + reference::ToJson(defaults)["proposal"].dump() +
        ", got " + params::Shown(reference::ToJson(o)["proposal"]));
  }
  return o;
}

EstimatorEntry FastSlamEntry(const std::string& name, reference::FastSlamProposal proposal,
                             const std::string& description) {
  EstimatorEntry e;
  e.name = name;
  e.description = description;
  e.parameters = reference::FastSlamOptionsTable().Descriptions();
  e.resolved_parameters = [proposal](const EstimatorRequest& r) {
    nlohmann::json j = reference::ToJson(ResolveFastSlam(r, proposal));
    j["particles"] = r.particles;
    return j;
  };
  e.make_online =
      [proposal](const EstimatorRequest& r) -> std::unique_ptr<filters::OnlineEstimator> {
    return reference::MakeFastSlam(RequireContext(r), r.particles, r.stream_seed,
                                   ResolveFastSlam(r, proposal));
  };
  return e;
}

}  // namespace

std::vector<EstimatorEntry> MrptEstimators() {
  return {MrptEkfEntry(), MrptEkfPostProcessedEntry(),
          FastSlamEntry("fastslam1", reference::FastSlamProposal::kMotionModel,
                        "FastSLAM 1.0 built on MRPT's particle filter: motion-model proposal, "
                        "per-particle ML association, landmark existence counter"),
          FastSlamEntry("fastslam2", reference::FastSlamProposal::kMeasurementConditioned,
                        "FastSLAM 2.0 built on MRPT's particle filter: EKF-conditioned pose "
                        "proposal, per-particle ML association, landmark existence counter")};
}

}  // namespace phdslam::validation
