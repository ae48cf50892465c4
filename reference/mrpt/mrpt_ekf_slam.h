// "mrpt-ekf": MRPT's EKF-SLAM for 2-D range-bearing landmarks, mrpt::slam::CRangeBearingKFSLAM2D,
// run with unknown data association behind phdslam's OnlineEstimator interface.
//
// What is MRPT's: the whole filter (prediction with a robot-frame odometry increment, EKF update,
// landmark initialisation, data association by mrpt::slam::data_association_full_covariance with
// JCBB or nearest neighbour). What is built here: the conversion of each StepData into an MRPT
// odometry action (the motion model's increment over the step's sub-intervals, covariance
// Fu Q_u Fu^T propagated and rotated into the robot frame) and a bearing-range observation, the
// initial pose, the unwrapped heading of the output, the count of associations per landmark and
// the post-processed map built from it, and documented deviations from stock MRPT, each an option
// (MrptEkfSlamOptions: mrpt_kdtree_candidates, prune_after_steps, symmetrize_covariance; and the
// note on Step()).
#pragma once

#include <memory>
#include <vector>

#include "datasets/scenario.h"
#include "reference/mrpt/mrpt_ekf_slam_options.h"
#include "src/filters/estimator.h"

namespace phdslam::reference {

class MrptEkfSlam final : public filters::OnlineEstimator {
 public:
  /// Throws std::invalid_argument for invalid options, a missing motion model or a measurement
  /// noise covariance that is not diagonal (CRangeBearingKFSLAM2D models R as diagonal).
  explicit MrptEkfSlam(filters::EstimatorContext context, MrptEkfSlamOptions options = {});
  ~MrptEkfSlam() override;
  MrptEkfSlam(const MrptEkfSlam&) = delete;
  MrptEkfSlam& operator=(const MrptEkfSlam&) = delete;

  /// Feeds one step to MRPT. Note: CRangeBearingKFSLAM2D skips its prediction while its map is
  /// empty (it assumes the first pose is the map origin); the pose is known here, so while the map
  /// is empty the odometry is applied by this wrapper with the same composition and covariance
  /// formula MRPT uses, and MRPT receives a zero increment.
  filters::StepOutput Step(const datasets::StepData& step) override;

  /// The raw map: every landmark in the filter state, clutter included (MRPT never removes one;
  /// only the optional track deletion of prune_after_steps does).
  /// Covariances are the marginal 2x2 blocks; log-weights are 0.
  [[nodiscard]] filters::MapEstimate Map() const override;

  /// POST-PROCESSING, not part of MRPT's filter: the landmarks of Map() that were associated with
  /// a measurement at least options.min_associations times after their creation.
  [[nodiscard]] filters::MapEstimate PostProcessedMap() const;

  /// For each landmark of Map(), how many measurements MRPT associated with it (creation excluded).
  [[nodiscard]] const std::vector<int>& AssociationCounts() const { return association_counts_; }

  /// For each measurement of the last step: the index in Map() of the landmark MRPT associated it
  /// with, or -1 when it created a landmark.
  [[nodiscard]] const std::vector<int>& LastAssociations() const { return last_associations_; }

  [[nodiscard]] const MrptEkfSlamOptions& options() const { return options_; }

 private:
  class Filter;  // CRangeBearingKFSLAM2D with the association hook (mrpt_ekf_slam.cc)

  filters::EstimatorContext context_;
  MrptEkfSlamOptions options_;
  std::unique_ptr<Filter> filter_;
  double heading_ = 0.0;  ///< unwrapped heading; MRPT keeps its own wrapped into [-pi, pi]
  std::vector<int> association_counts_;
  std::vector<int> birth_steps_;
  std::vector<int> last_associations_;  ///< step index at which each landmark was created
  int step_index_ = 0;
};

}  // namespace phdslam::reference
