// The interface between the program and the MRPT baselines' plugin (libphdslam_mrpt_baselines.so,
// a CMake MODULE library built from this folder). The plugin holds MrptEkfSlam and FastSlam with
// MRPT and its shared libraries; the program holds the options, their parameter tables and the
// loader (mrpt_baselines_loader.h), so that a process that constructs no MRPT estimator never
// loads MRPT. This header includes no MRPT header.
#pragma once

#include <cstdint>
#include <memory>

#include "datasets/scenario.h"
#include "reference/mrpt/fastslam_options.h"
#include "reference/mrpt/mrpt_ekf_slam_options.h"
#include "src/filters/estimator.h"

namespace phdslam::reference {

/// The factories the plugin exports. Program and plugin are built from one source tree; `layout`
/// lets the loader reject a plugin of another build whose exchanged types differ.
struct MrptBaselineFactories {
  std::uint64_t layout = 0;  ///< MrptBaselinesLayout() of the plugin's build
  /// MrptEkfSlam; with post_processed_map, an estimator whose Map() is PostProcessedMap().
  std::unique_ptr<filters::OnlineEstimator> (*make_mrpt_ekf)(
      const filters::EstimatorContext& context, const MrptEkfSlamOptions& options,
      bool post_processed_map) = nullptr;
  std::unique_ptr<filters::OnlineEstimator> (*make_fastslam)(
      const filters::EstimatorContext& context, int particles, std::uint64_t stream_seed,
      const FastSlamOptions& options) = nullptr;
};

/// A fingerprint of the types the factories exchange: their sizes, so that a plugin built with
/// other definitions of them is refused instead of corrupting memory.
constexpr std::uint64_t MrptBaselinesLayout() {
  std::uint64_t h = 1;
  for (std::uint64_t size :
       {sizeof(MrptBaselineFactories), sizeof(MrptEkfSlamOptions), sizeof(FastSlamOptions),
        sizeof(filters::EstimatorContext), sizeof(datasets::StepData), sizeof(filters::StepOutput),
        sizeof(filters::MapEstimate)}) {
    h = h * 1000003U + size;
  }
  return h;
}

/// The name of the plugin's entry point, a function with C linkage returning the factories:
///   const MrptBaselineFactories* phdslam_mrpt_baselines();
inline constexpr const char* kMrptBaselinesEntryPoint = "phdslam_mrpt_baselines";
using MrptBaselinesEntryPoint = const MrptBaselineFactories* (*)();

}  // namespace phdslam::reference
