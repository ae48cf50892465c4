// Parameters of delta-GLMB-SLAM 2.0 (glmb2), 1.0 (glmb1) and LMB-SLAM (lmb), one struct for the
// three filters (glmb_slam.h) with its parameter table. Defaults are the source paper's values
// (Moratuwage, Adams & Inostroza, Sensors 2019) and, where it is silent, the readings
// of docs/algorithms/glmb-slam.md section 12; each such reading is named here.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>

#include "src/core/parameter_table.h"
#include "src/core/types.h"
#include "src/filters/particle_filter_params.h"
#include "src/glmb/birth.h"
#include "src/glmb/lmb.h"
#include "src/models/sensor_model.h"

namespace phdslam::glmb {

/// The 2.0 particle weight, docs/algorithms/glmb-slam.md section 6.3.
enum class KernelWeight {
  kMarginal,    ///< (a) literal eq. 33: w * sum of the proposal pass's unnormalised weights
  kNormaliser,  ///< (b) w * Z-hat(x_k) at the sampled pose, no proposal correction
  kImportance,  ///< (c) w * Z-hat(x_k) N(x_k; x-hat, Sigma_0) / q(x_k) (default)
};

/// Which sampled associations enter the 2.0 pose mixture, docs/algorithms/glmb-slam.md section 6.3.
enum class KernelAssociations {
  kAll,   ///< (i) every distinct Gibbs sample of every hypothesis (default)
  kBest,  ///< (ii) only the highest-weight (hypothesis, association)
};

/// Collapse the 2.0 pose mixture or sample it, docs/algorithms/glmb-slam.md section 6.3.
enum class KernelForm {
  kCollapse,  ///< one moment-matched Gaussian ("a single Gaussian", default)
  kMixture,   ///< sample the mixture itself
};

/// When particles are resampled.
enum class ResamplingRule {
  kEveryStep,  ///< the source paper: every step (the suite's stratified scheme), default
  kEss,        ///< the suite's ESS threshold (ess_threshold_kind, ess_threshold)
};

struct GlmbSlamParams {
  int particles = 1;
  double survival_probability = 0.95;        ///< p_S inside the FOV (1 outside)
  double gate_probability = 0.9999999;       ///< [V]'s P_G: chi2_2 threshold -2 ln(1 - P_G) = 32.24
  int gibbs_samples = 1000;                  ///< H_upd per particle and update ([V] gms: 1000)
  int max_hypotheses = 1000;                 ///< H_max ([V]: = H_upd)
  double hypothesis_prune_threshold = 1e-5;  ///< the source paper's 1e-5
  bool optimal_start = true;  ///< optimal Gibbs start, docs/algorithms/glmb-slam.md section 4.3
  /// The space of the clutter density kappa(z) = Lambda pdf_c(z), docs/algorithms/glmb-slam.md
  /// section 2.3: unset ("sensor", default) the scenario's SensorModel::clutter_space (what its
  /// clutter generation and the other filters use); kRangeBearingBox ("range-bearing") [V]'s
  /// uniform density over the (r, b) box, 1 / (R_fov 2 half-angle).
  std::optional<models::ClutterSpace> clutter_space;
  BirthSettings birth;  ///< rule (a), 1e-4 new, 5e-5 existing, threshold 0.5
  // delta-GLMB-SLAM 2.0's optimal-kernel proposal.
  KernelWeight kernel_weight = KernelWeight::kImportance;
  KernelAssociations kernel_associations = KernelAssociations::kAll;
  KernelForm kernel_form = KernelForm::kCollapse;
  // LMB-SLAM.
  double existence_prune_threshold = 0.019;  ///< the source paper's value ([V]: 1e-3)
  int max_tracks = 100;                      ///< [V]'s T_max, here actually truncating
  MixtureReduction mixture;                  ///< per-track GM reduction ([V]: 1e-5, 4, 10)
  // The particle filter.
  ResamplingRule resampling = ResamplingRule::kEveryStep;
  filters::EssThresholdKind ess_threshold_kind = filters::EssThresholdKind::kRelative;
  double ess_threshold = 0.2;
  /// Q_n, the regulariser of the rank-2 predicted pose covariance (P_{x,k-1} = 0,
  /// docs/algorithms/glmb-slam.md section 6.1).
  Mat3 pose_regularisation = Vec3(1e-9, 1e-9, 1e-18).asDiagonal();
};

const params::ParameterTable<GlmbSlamParams>& GlmbSlamParamsTable();
nlohmann::json ToJson(const GlmbSlamParams& params);
void ApplyJson(const nlohmann::json& overrides, GlmbSlamParams& params);

/// The skeleton parameters (resampling every step = an infinite absolute ESS threshold).
filters::ParticleFilterParams SkeletonParams(const GlmbSlamParams& params);

}  // namespace phdslam::glmb
