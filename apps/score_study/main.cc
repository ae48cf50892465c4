// phdslam_score_study: how well the smoother's solution score (reference/ceres/
// association_posterior.h) ranks associations by their error. For each seed of a scenario the
// true association and graded corruptions of it (landmarks split, merged, dropped to clutter,
// clutter kept, detections moved to a neighbour) are each solved by the Ceres smoother in filter
// mode, started from the true trajectory with the squared loss, and printed as one CSV row with
// the solution's position RMSE and its score with the Poisson birth term and with the flat map
// prior (docs/algorithms/ceres-smoother.md, "The score of a solution").
//
//   phdslam_score_study SCENARIO FIRST_SEED LAST_SEED [steps=N] [key=value ...]  (scenario options)
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <exception>
#include <iostream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "datasets/scenario.h"
#include "reference/ceres/batch_smoother.h"
#include "src/models/range_bearing_model.h"
#include "validation/runner/registry/scenario_registry.h"

namespace {

using phdslam::Landmark;
using phdslam::datasets::Scenario;
using Labels = std::vector<std::vector<int>>;

// The hidden origins as labels, every unknown origin as clutter (-1). A label whose squared
// whitened residual at the true pose and landmark exceeds the known mode's known_outlier_chi2
// (a misread barcode on real data) is clutter too, as smoother-known screens it.
Labels TrueLabels(const Scenario& s) {
  const double chi2 = phdslam::reference::SmootherOptions{}.known_outlier_chi2;
  const Eigen::Matrix2d r_inv = s.sensor.noise_cov.inverse();
  Labels labels(s.steps.size());
  for (std::size_t k = 0; k < s.steps.size(); ++k) {
    for (std::size_t j = 0; j < s.steps[k].origin.size(); ++j) {
      int l = std::max(s.steps[k].origin[j], -1);
      if (l >= 0 && static_cast<std::size_t>(l) < s.truth.landmarks.size()) {
        Eigen::Vector2d v = s.steps[k].data.measurements[j] -
                            phdslam::models::PredictMeasurement(
                                s.truth.poses[k], s.truth.landmarks[static_cast<std::size_t>(l)]);
        v(1) = std::remainder(v(1), 2.0 * std::numbers::pi);
        if (v.dot(r_inv * v) > chi2) l = -1;
      }
      labels[k].push_back(l);
    }
  }
  return labels;
}

// The labels that occur in `labels`, sorted.
std::vector<int> UsedLabels(const Labels& labels) {
  std::set<int> used;
  for (const auto& step : labels) {
    for (int l : step) {
      if (l >= 0) used.insert(l);
    }
  }
  return {used.begin(), used.end()};
}

// Each used label with probability `fraction`.
std::vector<int> Choose(const Labels& labels, double fraction, std::mt19937_64& rng) {
  std::vector<int> chosen;
  std::bernoulli_distribution pick(fraction);
  for (int l : UsedLabels(labels)) {
    if (pick(rng)) chosen.push_back(l);
  }
  return chosen;
}

// Each landmark's mean measurement position in the world, from the true poses.
std::map<int, Landmark> LabelPositions(const Scenario& s, const Labels& labels) {
  std::map<int, Landmark> sum;
  std::map<int, int> count;
  for (std::size_t k = 0; k < labels.size(); ++k) {
    for (std::size_t j = 0; j < labels[k].size(); ++j) {
      const int l = labels[k][j];
      if (l < 0) continue;
      const Landmark m =
          phdslam::models::InverseMeasurement(s.truth.poses[k], s.steps[k].data.measurements[j]);
      sum.try_emplace(l, Landmark::Zero()).first->second += m;
      ++count[l];
    }
  }
  for (auto& [l, m] : sum) m /= count[l];
  return sum;
}

// The label nearest to `point` other than `except`.
int Nearest(const std::map<int, Landmark>& positions, const Landmark& point, int except) {
  int best = -1;
  double best_d = std::numeric_limits<double>::infinity();
  for (const auto& [l, m] : positions) {
    const double d = (m - point).squaredNorm();
    if (l != except && d < best_d) {
      best = l;
      best_d = d;
    }
  }
  return best;
}

int FreshLabel(const Labels& labels) {
  const std::vector<int> used = UsedLabels(labels);
  return used.empty() ? 0 : used.back() + 1;
}

// The chosen landmarks' detections after their median detection get a new label each.
Labels SplitInTime(const Labels& truth, double fraction, std::mt19937_64& rng) {
  Labels out = truth;
  int fresh = FreshLabel(truth);
  for (int l : Choose(truth, fraction, rng)) {
    std::vector<std::pair<std::size_t, std::size_t>> hits;
    for (std::size_t k = 0; k < truth.size(); ++k) {
      for (std::size_t j = 0; j < truth[k].size(); ++j) {
        if (truth[k][j] == l) hits.emplace_back(k, j);
      }
    }
    for (std::size_t h = hits.size() / 2; h < hits.size(); ++h) {
      out[hits[h].first][hits[h].second] = fresh;
    }
    ++fresh;
  }
  return out;
}

// The chosen landmarks' detections, each with probability 1/2, get a new label each: two
// landmarks where there is one.
Labels SplitInPlace(const Labels& truth, double fraction, std::mt19937_64& rng) {
  Labels out = truth;
  int fresh = FreshLabel(truth);
  std::bernoulli_distribution half(0.5);
  for (int l : Choose(truth, fraction, rng)) {
    for (auto& step : out) {
      for (int& a : step) {
        if (a == l && half(rng)) a = fresh;
      }
    }
    ++fresh;
  }
  return out;
}

// The chosen landmarks' detections go to their nearest other landmark.
Labels Merge(const Scenario& s, const Labels& truth, double fraction, std::mt19937_64& rng) {
  const std::map<int, Landmark> positions = LabelPositions(s, truth);
  Labels out = truth;
  for (int l : Choose(truth, fraction, rng)) {
    const int into = Nearest(positions, positions.at(l), l);
    for (auto& step : out) {
      for (int& a : step) a = a == l ? into : a;
    }
  }
  return out;
}

// The chosen landmarks' detections are called clutter.
Labels Drop(const Labels& truth, double fraction, std::mt19937_64& rng) {
  Labels out = truth;
  for (int l : Choose(truth, fraction, rng)) {
    for (auto& step : out) {
      for (int& a : step) a = a == l ? -1 : a;
    }
  }
  return out;
}

// Each clutter detection with probability `fraction` goes to its nearest landmark.
Labels KeepClutter(const Scenario& s, const Labels& truth, double fraction, std::mt19937_64& rng) {
  const std::map<int, Landmark> positions = LabelPositions(s, truth);
  Labels out = truth;
  std::bernoulli_distribution pick(fraction);
  for (std::size_t k = 0; k < truth.size(); ++k) {
    for (std::size_t j = 0; j < truth[k].size(); ++j) {
      if (truth[k][j] >= 0 || !pick(rng)) continue;
      const Landmark m =
          phdslam::models::InverseMeasurement(s.truth.poses[k], s.steps[k].data.measurements[j]);
      out[k][j] = Nearest(positions, m, -1);
    }
  }
  return out;
}

// Each landmark detection with probability `fraction` goes to its landmark's nearest neighbour.
Labels Flip(const Scenario& s, const Labels& truth, double fraction, std::mt19937_64& rng) {
  const std::map<int, Landmark> positions = LabelPositions(s, truth);
  Labels out = truth;
  std::bernoulli_distribution pick(fraction);
  for (auto& step : out) {
    for (int& a : step) {
      if (a >= 0 && pick(rng)) a = Nearest(positions, positions.at(a), a);
    }
  }
  return out;
}

double PositionRmse(const Scenario& s, const std::vector<phdslam::Pose>& poses) {
  double sum = 0.0;
  int n = 0;
  for (std::size_t k = 0; k < poses.size(); ++k) {
    if (!s.truth.PoseScored(k)) continue;
    sum += (poses[k].head<2>() - s.truth.poses[k].head<2>()).squaredNorm();
    ++n;
  }
  return std::sqrt(sum / std::max(n, 1));
}

void SolveAndPrint(const Scenario& s, const std::string& variant, double level,
                   const Labels& labels) {
  phdslam::reference::SmootherOptions o;
  o.association = phdslam::reference::AssociationMode::kFilter;
  o.filter_association = labels;
  o.min_observations = 1;
  o.min_detection_ratio = 0.0;
  o.robust_loss = "none";
  o.compute_covariances = false;
  o.initial_poses = s.truth.poses;
  phdslam::reference::BatchSmoother smoother(o);
  const phdslam::datasets::BatchResult r = smoother.Solve(s);
  const phdslam::reference::PosteriorTerms& t = smoother.report().posterior;
  std::cout << s.seed << ',' << variant << ',' << level << ',' << PositionRmse(s, r.poses) << ','
            << r.map.means.size() << ',' << t.Total() - t.births << ',' << t.Total() << '\n'
            << std::flush;
}

void Study(const Scenario& s) {
  std::mt19937_64 rng(s.seed);
  const Labels truth = TrueLabels(s);
  SolveAndPrint(s, "truth", 0.0, truth);
  for (double f : {0.1, 0.3, 0.6}) SolveAndPrint(s, "split_time", f, SplitInTime(truth, f, rng));
  for (double f : {0.1, 0.3, 0.6}) SolveAndPrint(s, "split_place", f, SplitInPlace(truth, f, rng));
  for (double f : {0.1, 0.3}) SolveAndPrint(s, "merge", f, Merge(s, truth, f, rng));
  for (double f : {0.1, 0.3, 0.6}) SolveAndPrint(s, "drop", f, Drop(truth, f, rng));
  for (double f : {0.3, 1.0}) SolveAndPrint(s, "keep_clutter", f, KeepClutter(s, truth, f, rng));
  for (double f : {0.02, 0.05, 0.1}) SolveAndPrint(s, "flip", f, Flip(s, truth, f, rng));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::cerr
        << "usage: phdslam_score_study SCENARIO FIRST_SEED LAST_SEED [steps=N] [key=value ...]\n";
    return 2;
  }
  try {
    phdslam::validation::ScenarioOptions options;
    for (int i = 4; i < argc; ++i) {
      const std::string kv = argv[i];
      const std::size_t eq = kv.find('=');
      if (eq == std::string::npos) throw std::invalid_argument("expected key=value: " + kv);
      const std::string key = kv.substr(0, eq);
      if (key == "steps") {
        options.steps = std::stoi(kv.substr(eq + 1));
      } else {
        options.settings[key] = nlohmann::json::parse(kv.substr(eq + 1));
      }
    }
    std::cout << "seed,variant,level,pos_rmse_m,landmarks,score_flat,score_poisson_birth\n";
    for (std::uint64_t seed = std::stoull(argv[2]); seed <= std::stoull(argv[3]); ++seed) {
      Study(phdslam::validation::MakeScenario(argv[1], seed, options));
    }
  } catch (const std::exception& e) {
    std::cerr << "phdslam_score_study: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
