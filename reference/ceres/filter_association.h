// The smoother on a filter's data association ("smoother-filter"): the filter runs over the
// scenario, its per-scan association becomes landmark labels, and the smoother solves in
// AssociationMode::kFilter.
#pragma once

#include <memory>
#include <vector>

#include "datasets/batch_estimator.h"
#include "reference/ceres/batch_smoother.h"
#include "src/filters/estimator.h"

namespace phdslam::reference {

/// Turns a filter's association into labels for SmootherOptions::filter_association.
/// `means[k][j]` is StepOutput::association of scan k: the mean of the map landmark measurement j
/// was associated with, or NaN for clutter / a new landmark (label -1). The filter's landmarks
/// carry no identity, so one is tracked here: scan by scan, associated means are matched to the
/// labels' latest means, closest pairs first, each label at most once per scan, when closer than
/// `same_landmark_distance` (m); an unmatched mean starts a new label.
/// `birth_points` (empty, or shaped like `means`) may give a NaN entry a point, e.g. the
/// measurement's inverse-model point: it then starts a new label there (never continues one),
/// which later associated means can continue. Labels are numbered in order of creation. Throws
/// std::invalid_argument when the distance is not positive or the shapes differ.
std::vector<std::vector<int>> LabelsFromAssociatedMeans(
    const std::vector<std::vector<Landmark>>& means, double same_landmark_distance,
    const std::vector<std::vector<Landmark>>& birth_points = {});

/// Runs the filter and then the smoother on its association.
class FilterThenSmooth final : public datasets::BatchEstimator {
 public:
  /// `filter` must be built for the scenario Solve will receive; options.association is set to
  /// kFilter, unless it is kUnknown with front_end kWindow (the labels are then the own
  /// association's first association), and options.filter_association is filled by Solve.
  FilterThenSmooth(std::unique_ptr<filters::OnlineEstimator> filter, SmootherOptions options);

  /// Runs the filter over every scan (once: a second call throws std::logic_error), converts its
  /// association with options.filter_label_distance and solves, starting from the filter's
  /// trajectory unless options.initial_poses is set. A measurement the filter left unassociated
  /// (clutter or a birth) enters the conversion as its inverse-model point at the filter's pose,
  /// so that the landmark it gives birth to keeps its first detection: without it the first
  /// scan, taken from the exactly known initial pose, would be lost, and with it most of what
  /// fixes the map's global position and heading (dropping the first scan of the known
  /// association doubles the position RMSE of seed 1). A clutter point stays a single detection,
  /// below min_observations. BatchResult.solve_seconds
  /// includes the filter's run; filter_seconds() gives that part alone. Throws
  /// std::runtime_error when the filter reports no association for a scan with measurements.
  datasets::BatchResult Solve(const datasets::Scenario& scenario) override;

  [[nodiscard]] const BatchSmoother& smoother() const { return *smoother_; }
  [[nodiscard]] double filter_seconds() const { return filter_seconds_; }
  /// The labels the smoother received.
  [[nodiscard]] const std::vector<std::vector<int>>& labels() const { return labels_; }

 private:
  std::unique_ptr<filters::OnlineEstimator> filter_;
  SmootherOptions options_;
  std::unique_ptr<BatchSmoother> smoother_;
  std::vector<std::vector<int>> labels_;
  double filter_seconds_ = 0.0;
};

}  // namespace phdslam::reference
