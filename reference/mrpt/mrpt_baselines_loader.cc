#include "reference/mrpt/mrpt_baselines_loader.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include "reference/mrpt/shared_object_check.h"

// Set by reference/mrpt/CMakeLists.txt for this file.
#ifndef PHDSLAM_MRPT_PLUGIN_FILE_NAME
#error "PHDSLAM_MRPT_PLUGIN_FILE_NAME is not defined"
#endif

namespace phdslam::reference {
namespace {

namespace fs = std::filesystem;

fs::path ProgramFolder() {
  std::error_code error;
  const fs::path program = fs::read_symlink("/proc/self/exe", error);
  return error ? fs::path() : program.parent_path();
}

// The places of mrpt_baselines_loader.h, in order.
std::vector<fs::path> Candidates() {
  const fs::path file = PHDSLAM_MRPT_PLUGIN_FILE_NAME;
  std::vector<fs::path> candidates;
  if (const fs::path folder = ProgramFolder(); !folder.empty()) {
    candidates.push_back(folder / file);
    candidates.push_back((folder / PHDSLAM_MRPT_PLUGIN_INSTALL_RELDIR / file).lexically_normal());
  }
  candidates.push_back(fs::path(PHDSLAM_MRPT_PLUGIN_BUILD_DIR) / file);
  return candidates;
}

fs::path FindPlugin() {
  if (const char* chosen = std::getenv("PHDSLAM_MRPT_PLUGIN"); chosen != nullptr && *chosen != 0) {
    return chosen;
  }
  std::string searched;
  for (const fs::path& candidate : Candidates()) {
    std::error_code error;
    if (fs::exists(candidate, error)) return candidate;
    searched += (searched.empty() ? "" : ", ") + candidate.string();
  }
  throw std::runtime_error(
      "the MRPT baselines' plugin " + std::string(PHDSLAM_MRPT_PLUGIN_FILE_NAME) +
      " was not found (searched " + searched + "; PHDSLAM_MRPT_PLUGIN names the file)");
}

std::string LoaderMessage() {
  const char* message = dlerror();
  return message != nullptr ? message : "no message";
}

}  // namespace

const MrptBaselineFactories& LoadMrptBaselinesPlugin(const std::filesystem::path& path) {
  const std::string failure = "cannot load the MRPT baselines' plugin " + path.string() + ": ";
  // A bare name (no '/') is dlopen's own library search, which finds the file itself; a path is
  // checked before it is mapped.
  if (path.string().find('/') != std::string::npos) RequireCompleteSharedObject(path);
  // RTLD_LOCAL: the plugin's symbols stay its own. Never closed: the estimators it made run its
  // code until the process ends.
  void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (handle == nullptr) throw std::runtime_error(failure + LoaderMessage());
  void* symbol = dlsym(handle, kMrptBaselinesEntryPoint);
  if (symbol == nullptr) throw std::runtime_error(failure + LoaderMessage());
  const MrptBaselineFactories* factories = reinterpret_cast<MrptBaselinesEntryPoint>(symbol)();
  if (factories == nullptr || factories->layout != MrptBaselinesLayout() ||
      factories->make_mrpt_ekf == nullptr || factories->make_fastslam == nullptr) {
    throw std::runtime_error(failure +
                             "it was built with other definitions of the estimator types (a "
                             "plugin of another build): rebuild or reinstall phdslam");
  }
  return *factories;
}

namespace {

// Loaded on first use, once per process (a failed load is retried at the next call).
const MrptBaselineFactories& Plugin() {
  static const MrptBaselineFactories& factories = LoadMrptBaselinesPlugin(FindPlugin());
  return factories;
}

}  // namespace

std::unique_ptr<filters::OnlineEstimator> MakeMrptEkfSlam(const filters::EstimatorContext& context,
                                                          const MrptEkfSlamOptions& options,
                                                          bool post_processed_map) {
  return Plugin().make_mrpt_ekf(context, options, post_processed_map);
}

std::unique_ptr<filters::OnlineEstimator> MakeFastSlam(const filters::EstimatorContext& context,
                                                       int particles, std::uint64_t stream_seed,
                                                       const FastSlamOptions& options) {
  return Plugin().make_fastslam(context, particles, stream_seed, options);
}

}  // namespace phdslam::reference
