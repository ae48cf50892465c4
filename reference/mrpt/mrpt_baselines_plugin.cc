// The entry point of the MRPT baselines' plugin (mrpt_baselines_plugin.h). The plugin is linked
// with hidden visibility and --exclude-libs, so this function is the only symbol it exports and
// its copies of phdslam's static libraries never interpose on the program's.
#include "reference/mrpt/mrpt_baselines_plugin.h"

#include <memory>
#include <utility>

#include "reference/mrpt/fastslam.h"
#include "reference/mrpt/mrpt_ekf_slam.h"

namespace phdslam::reference {
namespace {

// The same EKF-SLAM run, reporting PostProcessedMap() (landmarks MRPT associated at least
// min_associations times) as its map: a post-processing step that is not part of MRPT's filter.
class PostProcessedMrptEkf final : public filters::OnlineEstimator {
 public:
  explicit PostProcessedMrptEkf(std::unique_ptr<MrptEkfSlam> ekf) : ekf_(std::move(ekf)) {}
  filters::StepOutput Step(const datasets::StepData& step) override { return ekf_->Step(step); }
  [[nodiscard]] filters::MapEstimate Map() const override { return ekf_->PostProcessedMap(); }

 private:
  std::unique_ptr<MrptEkfSlam> ekf_;
};

std::unique_ptr<filters::OnlineEstimator> MakeMrptEkf(const filters::EstimatorContext& context,
                                                      const MrptEkfSlamOptions& options,
                                                      bool post_processed_map) {
  auto ekf = std::make_unique<MrptEkfSlam>(context, options);
  if (post_processed_map) return std::make_unique<PostProcessedMrptEkf>(std::move(ekf));
  return ekf;
}

std::unique_ptr<filters::OnlineEstimator> MakeFastSlam(const filters::EstimatorContext& context,
                                                       int particles, std::uint64_t stream_seed,
                                                       const FastSlamOptions& options) {
  return std::make_unique<FastSlam>(context, particles, stream_seed, options);
}

}  // namespace
}  // namespace phdslam::reference

extern "C" __attribute__((visibility("default"))) const phdslam::reference::MrptBaselineFactories*
phdslam_mrpt_baselines() {
  namespace r = phdslam::reference;
  static const r::MrptBaselineFactories factories{r::MrptBaselinesLayout(), &r::MakeMrptEkf,
                                                  &r::MakeFastSlam};
  return &factories;
}
