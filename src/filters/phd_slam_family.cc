#include "src/filters/phd_slam_family.h"

#include <stdexcept>

#include "src/filters/gm_ipl_density.h"
#include "src/filters/phd2a_density.h"
#include "src/filters/phd2b_density.h"

namespace phdslam::filters {

const std::vector<PhdSlamVariant>& PhdSlamVariants() {
  static const std::vector<PhdSlamVariant> variants = {
      {"phd1", "PHD-SLAM 1.0: RB-PHD-SLAM with the transition density as importance density"},
      {"phd2a",
       "PHD-SLAM 2.0a: EKF conditionals on every gated (component, measurement) pair, "
       "moment-matched into one Gaussian"},
      {"phd2b",
       "PHD-SLAM 2.0b: joint IPL of the pose and the landmarks of the single best "
       "association, pose marginal as proposal"},
      {"phd3",
       "PHD-SLAM 3.0 (system under test): GM importance density over Murty-ranked "
       "associations with partitioned IPL"},
  };
  return variants;
}

std::unique_ptr<ImportanceDensity> MakeImportanceDensity(const std::string& variant,
                                                         const PhdSlamParams& params) {
  if (variant == "phd1") return std::make_unique<TransitionDensity>();
  if (variant == "phd2a") return std::make_unique<MergedEkfDensity>(params);
  if (variant == "phd2b") return std::make_unique<JointIplDensity>(params);
  if (variant == "phd3") return std::make_unique<GmIplDensity>(params);
  throw std::invalid_argument("unknown PHD-SLAM variant '" + variant + "'");
}

std::unique_ptr<RbPhdSlam> MakePhdSlam(const std::string& variant, EstimatorContext context,
                                       const PhdSlamParams& params, std::uint64_t stream_seed) {
  return MakeRbPhdSlam(std::move(context), params, MakeImportanceDensity(variant, params),
                       stream_seed);
}

}  // namespace phdslam::filters
