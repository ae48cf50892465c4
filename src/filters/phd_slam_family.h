// The RB-PHD-SLAM family by name: each member is RbPhdSlam with its own importance density.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "src/filters/importance_density.h"
#include "src/filters/rb_phd_slam.h"

namespace phdslam::filters {

struct PhdSlamVariant {
  std::string name;         ///< estimator name, e.g. "phd3"
  std::string description;  ///< one line for `phdslam list`
};

/// The members of the family, in the paper's order.
const std::vector<PhdSlamVariant>& PhdSlamVariants();

/// The importance density of a family member; throws std::invalid_argument for an unknown name.
std::unique_ptr<ImportanceDensity> MakeImportanceDensity(const std::string& variant,
                                                         const PhdSlamParams& params);

/// A ready filter of the named member.
std::unique_ptr<RbPhdSlam> MakePhdSlam(const std::string& variant, EstimatorContext context,
                                       const PhdSlamParams& params, std::uint64_t stream_seed);

}  // namespace phdslam::filters
