#include "validation/runner/evaluation/offline_evaluation.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

#include "validation/metrics/gospa.h"
#include "validation/metrics/trajectory_error.h"
#include "validation/runner/evaluation/error_moments.h"

namespace phdslam::validation {
namespace {

constexpr double kDegreesPerRadian = 180.0 / std::numbers::pi;

void RequireFiniteTimes(const std::vector<datasets::StampedPose>& poses, const char* what) {
  for (std::size_t i = 0; i < poses.size(); ++i) {
    if (!std::isfinite(poses[i].t)) {
      throw std::invalid_argument(std::string(what) + " pose " + std::to_string(i) +
                                  ": time stamp is not finite");
    }
  }
}

std::vector<Landmark> Positions(const std::vector<datasets::MapPoint>& points) {
  std::vector<Landmark> out;
  out.reserve(points.size());
  for (const datasets::MapPoint& p : points) out.push_back(p.position);
  return out;
}

std::pair<std::string, std::string> TimeSpan(const std::vector<datasets::StampedPose>& poses) {
  const auto [lo, hi] = std::minmax_element(poses.begin(), poses.end(),
                                            [](const auto& a, const auto& b) { return a.t < b.t; });
  return {std::to_string(lo->t), std::to_string(hi->t)};
}

nlohmann::json ValueOrNull(const std::optional<double>& v) {
  return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
}

}  // namespace

TimeMatchedPoses MatchByTime(const std::vector<datasets::StampedPose>& truth,
                             const std::vector<datasets::StampedPose>& estimate, double tolerance) {
  if (!(tolerance >= 0.0)) {
    throw std::invalid_argument("time tolerance must be >= 0, got " + std::to_string(tolerance));
  }
  RequireFiniteTimes(truth, "truth");
  RequireFiniteTimes(estimate, "estimate");
  std::vector<datasets::StampedPose> sorted = estimate;
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](const auto& a, const auto& b) { return a.t < b.t; });
  TimeMatchedPoses out;
  for (const datasets::StampedPose& p : truth) {
    const auto after = std::lower_bound(sorted.begin(), sorted.end(), p.t,
                                        [](const auto& e, double t) { return e.t < t; });
    const datasets::StampedPose* best = nullptr;
    if (after != sorted.begin()) best = &*(after - 1);
    if (after != sorted.end() && (best == nullptr || after->t - p.t < p.t - best->t)) {
      best = &*after;
    }
    if (best == nullptr || std::abs(best->t - p.t) > tolerance) continue;
    out.times.push_back(p.t);
    out.truth.push_back(p.pose);
    out.estimate.push_back(best->pose);
  }
  return out;
}

nlohmann::json CompareMaps(const std::vector<datasets::MapPoint>& truth,
                           const std::vector<datasets::MapPoint>& estimate, double c, double p) {
  const std::vector<Landmark> x = Positions(truth);
  const std::vector<Landmark> y = Positions(estimate);
  if (!std::isfinite(std::pow(c, p))) {
    throw std::invalid_argument("c^p overflows for c = " + std::to_string(c) +
                                " and p = " + std::to_string(p) + ": choose a smaller c or p");
  }
  const GospaResult g = Gospa(x, y, c, p);
  const OspaResult o = Ospa(x, y, c, p);
  for (double v :
       {g.gospa, g.localisation, g.missed, g.false_, o.ospa, o.localisation, o.cardinality}) {
    if (!std::isfinite(v)) {
      throw std::invalid_argument("GOSPA/OSPA overflow for c = " + std::to_string(c) +
                                  " and p = " + std::to_string(p) + ": choose a smaller c or p");
    }
  }
  return {{"gospa", g.gospa},
          {"localisation", g.localisation},
          {"missed", g.missed},
          {"false", g.false_},
          {"n_missed", g.n_missed},
          {"n_false", g.n_false},
          {"ospa", o.ospa},
          {"ospa_localisation", o.localisation},
          {"ospa_cardinality", o.cardinality},
          {"truth_size", truth.size()},
          {"estimate_size", estimate.size()},
          {"c", c},
          {"p", p}};
}

nlohmann::json CompareTrajectories(const std::vector<datasets::StampedPose>& truth,
                                   const std::vector<datasets::StampedPose>& estimate,
                                   double tolerance) {
  if (truth.empty() || estimate.empty()) {
    throw std::invalid_argument(std::string(truth.empty() ? "the true" : "the estimated") +
                                " trajectory holds no poses");
  }
  const TimeMatchedPoses matched = MatchByTime(truth, estimate, tolerance);
  if (matched.truth.empty()) {
    const auto [t0, t1] = TimeSpan(truth);
    const auto [e0, e1] = TimeSpan(estimate);
    throw std::invalid_argument("no true pose has an estimate within " + std::to_string(tolerance) +
                                " s (truth spans " + t0 + ".." + t1 + " s, the estimate " + e0 +
                                ".." + e1 + " s): the trajectories do not overlap in time");
  }
  ErrorMoments position;
  ErrorMoments heading;
  if (!matched.truth.empty()) {
    const PoseErrors errors = ComputePoseErrors(matched.truth, matched.estimate);
    for (double e : errors.position_m) position.Add(e);
    for (double e : errors.heading_rad) heading.Add(e * kDegreesPerRadian);
  }
  return {{"pos_rmse_m", ValueOrNull(position.Rms())},
          {"pos_err_std_m", ValueOrNull(position.Std())},
          {"heading_rmse_deg", ValueOrNull(heading.Rms())},
          {"heading_err_std_deg", ValueOrNull(heading.Std())},
          {"matched", matched.truth.size()},
          {"truth_poses", truth.size()},
          {"estimate_poses", estimate.size()},
          {"time_tolerance_s", tolerance}};
}

}  // namespace phdslam::validation
