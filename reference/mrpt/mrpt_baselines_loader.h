// The MRPT baselines, constructed through their plugin (mrpt_baselines_plugin.h). The plugin file,
// libphdslam_mrpt_baselines.so, is opened with dlopen the first time one of these functions is
// called, once per process, and never closed; a process that calls neither never loads MRPT and
// its shared libraries (about 290, half a second of CPU per process start).
//
// The file is the first that exists of:
//   $PHDSLAM_MRPT_PLUGIN when it is set (the file itself; nothing else is tried),
//   the running program's folder (build/release/apps/ holds phdslam and the plugin),
//   <program's folder>/<relative path of the install lib dir> (installed: PREFIX/bin/phdslam and
//   PREFIX/lib/libphdslam_mrpt_baselines.so),
//   the folder the build wrote it to (the tests and other programs of the build tree).
// A missing or broken plugin throws std::runtime_error naming the file (or the folders searched)
// and the loader's message (dlerror()).
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>

#include "reference/mrpt/fastslam_options.h"
#include "reference/mrpt/mrpt_baselines_plugin.h"
#include "reference/mrpt/mrpt_ekf_slam_options.h"
#include "src/filters/estimator.h"

namespace phdslam::reference {

/// MrptEkfSlam(context, options); with post_processed_map, its Map() is PostProcessedMap().
std::unique_ptr<filters::OnlineEstimator> MakeMrptEkfSlam(const filters::EstimatorContext& context,
                                                          const MrptEkfSlamOptions& options,
                                                          bool post_processed_map);

/// FastSlam(context, particles, stream_seed, options).
std::unique_ptr<filters::OnlineEstimator> MakeFastSlam(const filters::EstimatorContext& context,
                                                       int particles, std::uint64_t stream_seed,
                                                       const FastSlamOptions& options);

/// Opens `file` (a path, or a bare name for the system's search) and returns its factories,
/// without the search and the once-per-process cache of the functions above (which call it).
/// Throws std::runtime_error naming the file and the loader's message when it cannot be opened,
/// has no entry point or was built with other type definitions.
const MrptBaselineFactories& LoadMrptBaselinesPlugin(const std::filesystem::path& file);

}  // namespace phdslam::reference
