#include "reference/ceres/filter_association.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "reference/ceres/association_labels.h"
#include "src/models/range_bearing_model.h"

namespace phdslam::reference {

std::vector<std::vector<int>> LabelsFromAssociatedMeans(
    const std::vector<std::vector<Landmark>>& means, double same_landmark_distance,
    const std::vector<std::vector<Landmark>>& birth_points) {
  if (!(same_landmark_distance > 0.0)) {
    throw std::invalid_argument("LabelsFromAssociatedMeans: same_landmark_distance must be > 0");
  }
  if (!birth_points.empty()) {
    bool same = birth_points.size() == means.size();
    for (std::size_t k = 0; same && k < means.size(); ++k) {
      same = birth_points[k].size() == means[k].size();
    }
    if (!same) {
      throw std::invalid_argument(
          "LabelsFromAssociatedMeans: birth_points must have the shape of means");
    }
  }
  const double d2_max = same_landmark_distance * same_landmark_distance;
  std::vector<Landmark> latest;  // latest associated mean of each label
  std::vector<std::vector<int>> labels;
  labels.reserve(means.size());
  for (std::size_t k = 0; k < means.size(); ++k) {
    const std::vector<Landmark>& scan = means[k];
    std::vector<int> out(scan.size(), -1);
    struct Pair {
      double d2;
      std::size_t j;
      int label;
    };
    std::vector<Pair> pairs;
    for (std::size_t j = 0; j < scan.size(); ++j) {
      if (!scan[j].allFinite()) continue;
      for (std::size_t l = 0; l < latest.size(); ++l) {
        const double d2 = (scan[j] - latest[l]).squaredNorm();
        if (d2 < d2_max) pairs.push_back({d2, j, static_cast<int>(l)});
      }
    }
    std::sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) {
      if (a.d2 != b.d2) return a.d2 < b.d2;
      if (a.j != b.j) return a.j < b.j;
      return a.label < b.label;
    });
    std::vector<bool> used(latest.size(), false);
    for (const Pair& p : pairs) {
      if (out[p.j] >= 0 || used[static_cast<std::size_t>(p.label)]) continue;
      out[p.j] = p.label;
      used[static_cast<std::size_t>(p.label)] = true;
    }
    for (std::size_t j = 0; j < scan.size(); ++j) {
      if (!scan[j].allFinite()) {
        if (!birth_points.empty() && birth_points[k][j].allFinite()) {
          out[j] = static_cast<int>(latest.size());
          latest.push_back(birth_points[k][j]);
        }
        continue;
      }
      if (out[j] < 0) {
        out[j] = static_cast<int>(latest.size());
        latest.push_back(scan[j]);
      } else {
        latest[static_cast<std::size_t>(out[j])] = scan[j];
      }
    }
    labels.push_back(std::move(out));
  }
  return labels;
}

FilterThenSmooth::FilterThenSmooth(std::unique_ptr<filters::OnlineEstimator> filter,
                                   SmootherOptions options)
    : filter_(std::move(filter)), options_(std::move(options)) {
  if (!filter_) throw std::invalid_argument("FilterThenSmooth: no filter given");
  // The own association takes the labels as its first association (front_end window) and
  // re-associates; every other mode solves them as given.
  if (options_.association != AssociationMode::kUnknown ||
      options_.front_end != OwnFrontEnd::kWindow) {
    options_.association = AssociationMode::kFilter;
  }
  options_.Validate();
}

datasets::BatchResult FilterThenSmooth::Solve(const datasets::Scenario& scenario) {
  if (smoother_) throw std::logic_error("FilterThenSmooth::Solve: the filter has already run");
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::vector<Landmark>> means;
  means.reserve(scenario.steps.size());
  std::vector<std::vector<Landmark>> birth_points;
  birth_points.reserve(scenario.steps.size());
  std::vector<Pose> poses;
  poses.reserve(scenario.steps.size());
  for (std::size_t k = 0; k < scenario.steps.size(); ++k) {
    const datasets::StepData& step = scenario.steps[k].data;
    filters::StepOutput out = filter_->Step(step);
    if (out.association.empty() && !step.measurements.empty()) {
      throw std::runtime_error("FilterThenSmooth: the filter gave no association at step " +
                               std::to_string(k));
    }
    if (out.association.size() != step.measurements.size()) {
      throw std::runtime_error("FilterThenSmooth: the filter's association at step " +
                               std::to_string(k) + " has " +
                               std::to_string(out.association.size()) + " entries for " +
                               std::to_string(step.measurements.size()) + " measurements");
    }
    // A measurement the filter did not associate is clutter or the birth of a landmark; its
    // inverse-model point lets a later association with the born component continue it (a
    // clutter point stays a single detection and is dropped by the smoother).
    std::vector<Landmark> births(out.association.size(), Landmark::Constant(std::nan("")));
    for (std::size_t j = 0; j < out.association.size(); ++j) {
      if (!out.association[j].allFinite()) {
        births[j] = models::InverseMeasurement(out.pose, step.measurements[j]);
      }
    }
    birth_points.push_back(std::move(births));
    means.push_back(std::move(out.association));
    poses.push_back(out.pose);
  }
  filter_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const auto* named = dynamic_cast<const LabelledAssociation*>(filter_.get());
  labels_ = named != nullptr
                ? named->FinalLabels()
                : LabelsFromAssociatedMeans(means, options_.filter_label_distance, birth_points);
  SmootherOptions o = options_;
  o.filter_association = labels_;
  if (o.initial_poses.empty()) o.initial_poses = std::move(poses);
  smoother_ = std::make_unique<BatchSmoother>(std::move(o));
  datasets::BatchResult result = smoother_->Solve(scenario);
  result.solve_seconds += filter_seconds_;
  return result;
}

}  // namespace phdslam::reference
