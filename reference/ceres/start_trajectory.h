// The smoother's own association started from another estimator's trajectory (README.md, "Start
// from another estimator's trajectory"). The sequential association pass predicts each pose by
// the start trajectory's relative motion between consecutive steps instead of the odometry, so
// that its gates open around a trajectory that has already closed its loops, while the pass, its
// intermediate solves and the final re-association rounds make the smoother's own association:
// nothing of the other estimator's association is read.
#pragma once

#include <memory>
#include <vector>

#include "datasets/batch_estimator.h"
#include "datasets/scenario.h"
#include "reference/ceres/batch_smoother.h"
#include "reference/ceres/particle_lineage.h"
#include "src/filters/estimator.h"
#include "src/filters/particle_filter.h"

namespace phdslam::reference {

/// Runs an online estimator over the scenario for its trajectory alone and then the smoother
/// with `options` (any association mode but kFilter), started from that trajectory
/// (SmootherOptions::initial_poses): the estimator's pose estimate of every step, or with
/// options.start_path = kBestParticlePath the path of a particle filter's best particle at the
/// last step (particle_lineage.h). The estimator's association is never read.
class SmoothFromEstimatorStart final : public datasets::BatchEstimator {
 public:
  /// `estimator` must be built for the scenario Solve will receive. Throws std::invalid_argument
  /// when it is null, options.association is kFilter, options.initial_poses is already set, or
  /// options.start_path is kBestParticlePath (which needs the particle filter constructor).
  SmoothFromEstimatorStart(std::unique_ptr<filters::OnlineEstimator> estimator,
                           SmootherOptions options);

  /// As above for a particle filter, whose particles' ancestry is recorded (SetObserver: the
  /// filter must not have another observer) when options.start_path is kBestParticlePath.
  template <class Model>
  SmoothFromEstimatorStart(std::unique_ptr<filters::ParticleFilter<Model>> filter,
                           const SmootherOptions& options)
      : SmoothFromEstimatorStart(WithLineage(std::move(filter), options.start_path), options) {}

  /// Runs the estimator over every scan (once: a second call throws std::logic_error), then the
  /// smoother. BatchResult.solve_seconds includes the estimator's run; estimator_seconds() gives
  /// that part alone.
  datasets::BatchResult Solve(const datasets::Scenario& scenario) override;

  [[nodiscard]] const BatchSmoother& smoother() const { return *smoother_; }
  [[nodiscard]] double estimator_seconds() const { return estimator_seconds_; }
  /// The trajectory the smoother started from.
  [[nodiscard]] const std::vector<Pose>& start() const { return start_; }

 private:
  struct Started {
    std::unique_ptr<filters::OnlineEstimator> estimator;
    std::unique_ptr<LineageSource> lineage;  ///< null unless the start is a particle's path
  };
  template <class Model>
  static Started WithLineage(std::unique_ptr<filters::ParticleFilter<Model>> filter,
                             StartPath path) {
    Started s;
    if (filter && path == StartPath::kBestParticlePath) {
      auto observer = std::make_unique<
          LineageObserver<typename filters::ParticleFilter<Model>::ParticleType>>();
      filter->SetObserver(observer.get());
      s.lineage = std::move(observer);
    }
    s.estimator = std::move(filter);
    return s;
  }
  SmoothFromEstimatorStart(Started started, SmootherOptions options);

  std::unique_ptr<LineageSource> lineage_;
  std::unique_ptr<filters::OnlineEstimator> estimator_;
  SmootherOptions options_;
  std::unique_ptr<BatchSmoother> smoother_;
  std::vector<Pose> start_;
  double estimator_seconds_ = 0.0;
};

}  // namespace phdslam::reference
