#include "reference/ceres/landmark_association.h"

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <unordered_set>

#include "reference/ceres/pose_covariance_propagation.h"
#include "src/core/angles.h"
#include "src/core/gaussian.h"
#include "src/models/range_bearing_model.h"

namespace phdslam::reference {
namespace {

/// Side of the grid cells used to find gating candidates (m). A query visits the 3 x 3 cells
/// around a point, so every landmark within one cell side of it is a candidate: the gates here
/// are a few metres wide (0.8 m range noise, 0.3-1 deg bearing noise at <= 150 m).
constexpr double kGridCell = 10.0;

/// Covariance given to a landmark without observations in the previous association (m^2).
constexpr double kUnobservedLandmarkVariance = 1e6;

/// Gauss-Newton iterations of the initial pass' pose correction (iterated EKF).
constexpr int kPoseCorrectionIterations = 3;

/// Two landmarks seen together in more than this fraction of the steps of the less-seen one are
/// distinct and never merged. Duplicates of one landmark share a step only when clutter or a
/// neighbour's detection fell into the other's gate, which is rare but does happen.
constexpr double kMaxMergeOverlap = 0.1;

/// Spatial hash of landmark positions.
class LandmarkGrid {
 public:
  void Insert(int id, const Vec2& p) { cells_[Key(p)].push_back(id); }

  void Move(int id, const Vec2& from, const Vec2& to) {
    const std::int64_t a = Key(from);
    const std::int64_t b = Key(to);
    if (a == b) return;
    std::vector<int>& cell = cells_[a];
    const auto it = std::find(cell.begin(), cell.end(), id);
    if (it != cell.end()) {
      *it = cell.back();
      cell.pop_back();
    }
    cells_[b].push_back(id);
  }

  void Remove(int id, const Vec2& p) {
    std::vector<int>& cell = cells_[Key(p)];
    const auto it = std::find(cell.begin(), cell.end(), id);
    if (it != cell.end()) {
      *it = cell.back();
      cell.pop_back();
    }
  }

  /// Appends the ids stored in the cells that overlap the disc of the given radius around p.
  void NearRadius(const Vec2& p, double radius, std::vector<int>* out) const {
    const std::int64_t x0 = Cell(p(0) - radius);
    const std::int64_t x1 = Cell(p(0) + radius);
    const std::int64_t y0 = Cell(p(1) - radius);
    const std::int64_t y1 = Cell(p(1) + radius);
    for (std::int64_t cx = x0; cx <= x1; ++cx) {
      for (std::int64_t cy = y0; cy <= y1; ++cy) {
        const auto it = cells_.find(Key(cx, cy));
        if (it != cells_.end()) out->insert(out->end(), it->second.begin(), it->second.end());
      }
    }
  }

  /// Appends the ids stored in the 3 x 3 cells around p.
  void Near(const Vec2& p, std::vector<int>* out) const {
    const std::int64_t cx = Cell(p(0));
    const std::int64_t cy = Cell(p(1));
    for (std::int64_t dx = -1; dx <= 1; ++dx) {
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        const auto it = cells_.find(Key(cx + dx, cy + dy));
        if (it != cells_.end()) out->insert(out->end(), it->second.begin(), it->second.end());
      }
    }
  }

 private:
  static std::int64_t Cell(double v) {
    return static_cast<std::int64_t>(std::floor(v / kGridCell));
  }
  static std::int64_t Key(std::int64_t cx, std::int64_t cy) {
    return cx * 4294967296LL + (cy & 0xffffffffLL);
  }
  static std::int64_t Key(const Vec2& p) { return Key(Cell(p(0)), Cell(p(1))); }

  std::unordered_map<std::int64_t, std::vector<int>> cells_;
};

struct Candidate {
  int measurement;
  int landmark;
  double d2;
};

/// Innovation z - h(m, x) with the bearing difference wrapped.
Vec2 Innovation(const Pose& x, const Landmark& m, const Measurement& z) {
  const Measurement h = models::PredictMeasurement(x, m);
  return {z(0) - h(0), WrapAngle(z(1) - h(1))};
}

/// Squared Mahalanobis distance of z to landmark (m, pm) seen from x (pose covariance px, or
/// none for a pose taken as known); nullopt outside the gate or when S is singular.
std::optional<double> GateDistance(const Pose& x, const Mat3* px, const Landmark& m, const Mat2& pm,
                                   const Measurement& z, const Mat2& r, double gate) {
  if ((m - x.head<2>()).squaredNorm() < 1e-18) return std::nullopt;
  const models::RangeBearingJacobians j = models::MeasurementJacobians(x, m);
  Mat2 s = j.hm * pm * j.hm.transpose() + r;
  if (px != nullptr) s += j.hx * (*px) * j.hx.transpose();
  const Gaussian2Eval e = EvalGaussian2(Innovation(x, m, z), s);
  if (!std::isfinite(e.mahalanobis2) || !(e.mahalanobis2 < gate)) return std::nullopt;
  return e.mahalanobis2;
}

/// Greedy global nearest neighbour: pairs in increasing distance (ties by indices, so the result
/// does not depend on the order candidates were found in), each measurement and landmark once.
std::vector<int> AssignGreedy(std::vector<Candidate> candidates, std::size_t measurement_count) {
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    if (a.d2 != b.d2) return a.d2 < b.d2;
    if (a.measurement != b.measurement) return a.measurement < b.measurement;
    return a.landmark < b.landmark;
  });
  std::vector<int> assigned(measurement_count, kUnassociated);
  std::unordered_set<int> used;
  for (const Candidate& c : candidates) {
    if (assigned[static_cast<std::size_t>(c.measurement)] != kUnassociated) continue;
    if (used.count(c.landmark) > 0) continue;
    assigned[static_cast<std::size_t>(c.measurement)] = c.landmark;
    used.insert(c.landmark);
  }
  return assigned;
}

/// A landmark estimated with the poses taken as known.
struct Track {
  Landmark m;
  Mat2 p;
  int count = 0;
  double expected = 0.0;  ///< sum of pD over the steps so far (initial pass only)
  bool dead = false;      ///< can no longer gain support: out of the grid (initial pass only)
};

/// EKF update of a track with z taken at the known pose x.
void UpdateTrack(const Pose& x, const Measurement& z, const Mat2& r, Track* t) {
  const Mat2 hm = models::MeasurementJacobians(x, t->m).hm;
  const Mat2 s = hm * t->p * hm.transpose() + r;
  const Mat2 k = t->p * hm.transpose() * s.inverse();
  t->m += k * Innovation(x, t->m, z);
  t->p = (Mat2::Identity() - k * hm) * t->p;
  Symmetrize(t->p);
  ++t->count;
}

Track BirthTrack(const Pose& x, const Measurement& z, const Mat2& r) {
  return {models::InverseMeasurement(x, z), models::BirthCovariance(x, z, r), 1};
}

/// Iterated EKF correction of the pose (x, px) with measurements of landmarks taken as known up to
/// their covariance, which is added to R.
void CorrectPose(const std::vector<std::pair<Measurement, const Track*>>& obs, const Mat2& r,
                 Pose* x, Mat3* px) {
  if (obs.empty()) return;
  const int n = 2 * static_cast<int>(obs.size());
  const Pose x0 = *x;
  Pose xi = x0;
  Eigen::MatrixXd h(n, 3);
  Eigen::MatrixXd k;
  for (int it = 0; it < kPoseCorrectionIterations; ++it) {
    Eigen::VectorXd nu(n);
    Eigen::MatrixXd rb = Eigen::MatrixXd::Zero(n, n);
    for (std::size_t i = 0; i < obs.size(); ++i) {
      const int row = 2 * static_cast<int>(i);
      const Track& t = *obs[i].second;
      const models::RangeBearingJacobians j = models::MeasurementJacobians(xi, t.m);
      h.block<2, 3>(row, 0) = j.hx;
      nu.segment<2>(row) = Innovation(xi, t.m, obs[i].first);
      rb.block<2, 2>(row, row) = j.hm * t.p * j.hm.transpose() + r;
    }
    const Eigen::MatrixXd s = h * (*px) * h.transpose() + rb;
    const Eigen::LDLT<Eigen::MatrixXd> ldlt(s);
    if (ldlt.info() != Eigen::Success) return;
    k = (*px) * h.transpose() * ldlt.solve(Eigen::MatrixXd::Identity(n, n));
    xi = x0 + k * (nu + h * (xi - x0));
  }
  *x = xi;
  *px = (Mat3::Identity() - k * h) * (*px);
  Symmetrize(*px);
}

/// Pose-known information sum_obs Hm^T R^-1 Hm of every landmark under `association`.
std::vector<Mat2> LandmarkInformation(const std::vector<Pose>& poses,
                                      const std::vector<Landmark>& landmarks,
                                      const Association& association, const Mat2& r) {
  const Mat2 r_inv = r.inverse();
  std::vector<Mat2> info(landmarks.size(), Mat2::Zero());
  for (std::size_t k = 0; k < association.size(); ++k) {
    for (std::size_t j = 0; j < association[k].size(); ++j) {
      const int i = association[k][j];
      if (i == kUnassociated) continue;
      const auto li = static_cast<std::size_t>(i);
      if ((landmarks[li] - poses[k].head<2>()).squaredNorm() < 1e-18) continue;
      const Mat2 hm = models::MeasurementJacobians(poses[k], landmarks[li]).hm;
      info[li] += hm.transpose() * r_inv * hm;
    }
  }
  return info;
}

Mat2 CovarianceFromInformation(const Mat2& info) {
  if (std::abs(info.determinant()) < 1e-300) {
    return kUnobservedLandmarkVariance * Mat2::Identity();
  }
  Mat2 p = info.inverse();
  Symmetrize(p);
  return p;
}

/// Removes landmarks with too little support (see the header) and renumbers the rest in order.
void DropUnsupportedLandmarks(const AssociationOptions& options, const std::vector<Pose>& poses,
                              AssociatedMap* map) {
  const std::vector<int> counts = CountObservations(map->association, map->landmarks.size());
  const std::vector<bool> keep =
      SupportedLandmarks(map->association, map->landmarks, poses, options);
  std::vector<int> new_index(map->landmarks.size(), kUnassociated);
  std::vector<Landmark> kept;
  for (std::size_t i = 0; i < map->landmarks.size(); ++i) {
    if (keep[i]) {
      new_index[i] = static_cast<int>(kept.size());
      kept.push_back(map->landmarks[i]);
    } else if (counts[i] > 0) {
      ++map->dropped;
    }
  }
  for (auto& step : map->association) {
    for (int& a : step) {
      if (a != kUnassociated) a = new_index[static_cast<std::size_t>(a)];
    }
  }
  map->landmarks = std::move(kept);
}

void CheckSizes(const datasets::Scenario& scenario, std::size_t poses, const char* what) {
  if (poses != scenario.steps.size()) {
    throw std::invalid_argument(std::string(what) + ": expected one pose per step (" +
                                std::to_string(scenario.steps.size()) + "), got " +
                                std::to_string(poses));
  }
}

}  // namespace

std::vector<bool> SupportedLandmarks(const Association& association,
                                     const std::vector<Landmark>& landmarks,
                                     const std::vector<Pose>& poses,
                                     const AssociationOptions& options) {
  const std::vector<int> counts = CountObservations(association, landmarks.size());
  std::vector<bool> keep(landmarks.size(), false);
  for (std::size_t i = 0; i < landmarks.size(); ++i) {
    keep[i] = counts[i] >= options.min_observations;
    if (keep[i] && options.min_detection_ratio > 0.0) {
      double expected = 0.0;
      for (const Pose& x : poses) expected += options.sensor.DetectionProbability(x, landmarks[i]);
      keep[i] = counts[i] >= options.min_detection_ratio * expected;
    }
  }
  return keep;
}

std::vector<int> CountObservations(const Association& association, std::size_t landmark_count) {
  std::vector<int> counts(landmark_count, 0);
  for (const auto& step : association) {
    for (int a : step) {
      if (a == kUnassociated) continue;
      if (a < 0 || static_cast<std::size_t>(a) >= landmark_count) {
        throw std::invalid_argument("CountObservations: landmark index " + std::to_string(a) +
                                    " outside [0, " + std::to_string(landmark_count) + ")");
      }
      ++counts[static_cast<std::size_t>(a)];
    }
  }
  return counts;
}

struct SequentialAssociator::State {
  const datasets::Scenario* scenario;
  std::vector<OdometryIncrement> increments;
  AssociationOptions options;
  std::vector<Track> tracks;
  LandmarkGrid grid;
  Pose x;
  Mat3 px = Mat3::Zero();
  Association association;
  std::vector<Pose> poses;
  int born = 0;

  void Step(std::size_t k);
  /// Seen often enough, in absolute terms and relative to the detections the sensor model
  /// expected so far: the tracks that correct the pose and enter the intermediate solves.
  [[nodiscard]] bool Supported(const Track& t) const {
    return !t.dead && t.count >= options.min_observations &&
           t.count >= options.min_detection_ratio * t.expected;
  }
};

void SequentialAssociator::State::Step(std::size_t k) {
  const Mat2& r = options.measurement_cov;
  const OdometryIncrement& inc = increments[k];
  if (inc.propagated) {
    px = PropagatePoseCovariance(x, inc, px);
    x = ComposeRelative(x, inc.delta);
  }
  const std::vector<Measurement>& zs = scenario->steps[k].data.measurements;
  std::vector<Candidate> candidates;
  std::vector<int> near;
  for (std::size_t j = 0; j < zs.size(); ++j) {
    near.clear();
    grid.Near(models::InverseMeasurement(x, zs[j]), &near);
    for (int i : near) {
      const Track& t = tracks[static_cast<std::size_t>(i)];
      const auto d2 = GateDistance(x, &px, t.m, t.p, zs[j], r, options.gate_chi2);
      if (d2) candidates.push_back({static_cast<int>(j), i, *d2});
    }
  }
  std::vector<int> assigned = AssignGreedy(std::move(candidates), zs.size());

  std::vector<std::pair<Measurement, const Track*>> confirmed;
  for (std::size_t j = 0; j < zs.size(); ++j) {
    const int i = assigned[j];
    if (i == kUnassociated) continue;
    const Track& t = tracks[static_cast<std::size_t>(i)];
    if (Supported(t)) confirmed.emplace_back(zs[j], &t);
  }
  CorrectPose(confirmed, r, &x, &px);

  for (std::size_t j = 0; j < zs.size(); ++j) {
    if (assigned[j] == kUnassociated) {
      assigned[j] = static_cast<int>(tracks.size());
      tracks.push_back(BirthTrack(x, zs[j], r));
      grid.Insert(assigned[j], tracks.back().m);
      ++born;
    } else {
      Track& t = tracks[static_cast<std::size_t>(assigned[j])];
      const Landmark before = t.m;
      UpdateTrack(x, zs[j], r, &t);
      grid.Move(assigned[j], before, t.m);
    }
  }
  // Expected detections of every live track around the pose. A track detected in fewer than
  // min_detection_ratio of the scans expected to see it is dead: it would fail the final support
  // test anyway, and leaving the grid keeps clutter tracks from piling up.
  near.clear();
  grid.NearRadius(x.head<2>(), options.sensor.fov_range, &near);
  for (int i : near) {
    Track& t = tracks[static_cast<std::size_t>(i)];
    t.expected += options.sensor.DetectionProbability(x, t.m);
    if (static_cast<double>(t.count) < options.min_detection_ratio * t.expected) {
      t.dead = true;
      grid.Remove(i, t.m);
    }
  }
  association.push_back(std::move(assigned));
  poses.push_back(x);
}

SequentialAssociator::SequentialAssociator(const datasets::Scenario& scenario,
                                           std::vector<OdometryIncrement> increments,
                                           AssociationOptions options)
    : state_(std::make_unique<State>()) {
  CheckSizes(scenario, increments.size(), "SequentialAssociator");
  state_->scenario = &scenario;
  state_->increments = std::move(increments);
  state_->options = std::move(options);
  state_->x = scenario.initial_pose;
}

SequentialAssociator::~SequentialAssociator() = default;

std::size_t SequentialAssociator::steps_done() const { return state_->poses.size(); }

void SequentialAssociator::AdvanceTo(std::size_t end) {
  end = std::min(end, state_->scenario->steps.size());
  for (std::size_t k = steps_done(); k < end; ++k) state_->Step(k);
}

AssociatedMap SequentialAssociator::Confirmed(std::vector<int>* track_ids) const {
  const State& st = *state_;
  std::vector<int> index(st.tracks.size(), kUnassociated);
  track_ids->clear();
  AssociatedMap out;
  for (std::size_t i = 0; i < st.tracks.size(); ++i) {
    if (!st.Supported(st.tracks[i])) continue;
    index[i] = static_cast<int>(track_ids->size());
    track_ids->push_back(static_cast<int>(i));
    out.landmarks.push_back(st.tracks[i].m);
  }
  out.association = st.association;
  for (auto& step : out.association) {
    for (int& a : step) {
      if (a != kUnassociated) a = index[static_cast<std::size_t>(a)];
    }
  }
  out.poses = st.poses;
  out.born = st.born;
  return out;
}

void SequentialAssociator::Correct(const std::vector<Pose>& poses,
                                   const std::vector<int>& track_ids,
                                   const std::vector<Landmark>& means) {
  State& st = *state_;
  if (poses.size() != st.poses.size() || track_ids.size() != means.size()) {
    throw std::invalid_argument("SequentialAssociator::Correct: expected " +
                                std::to_string(st.poses.size()) + " poses and one mean per track");
  }
  st.poses = poses;
  if (!poses.empty()) st.x = poses.back();
  for (std::size_t n = 0; n < track_ids.size(); ++n) {
    const int id = track_ids[n];
    Track& t = st.tracks.at(static_cast<std::size_t>(id));
    st.grid.Move(id, t.m, means[n]);
    t.m = means[n];
  }
}

AssociatedMap SequentialAssociator::Finish() const {
  const State& st = *state_;
  AssociatedMap out;
  out.association = st.association;
  out.poses = st.poses;
  out.born = st.born;
  for (const Track& t : st.tracks) out.landmarks.push_back(t.m);
  DropUnsupportedLandmarks(st.options, out.poses, &out);
  return out;
}

AssociatedMap SequentialAssociation(const datasets::Scenario& scenario,
                                    const std::vector<OdometryIncrement>& increments,
                                    const AssociationOptions& options) {
  SequentialAssociator associator(scenario, increments, options);
  associator.AdvanceTo(scenario.steps.size());
  return associator.Finish();
}

namespace {

/// Whether measurement j of step k is left out of the re-association (options.excluded).
bool Excluded(const AssociationOptions& options, std::size_t k, std::size_t j) {
  if (options.excluded == nullptr || k >= options.excluded->size()) return false;
  const std::vector<bool>& step = (*options.excluded)[k];
  return j < step.size() && step[j];
}

}  // namespace

AssociatedMap Reassociate(const datasets::Scenario& scenario, const std::vector<Pose>& poses,
                          const std::vector<Landmark>& landmarks, const Association& previous,
                          const AssociationOptions& options) {
  CheckSizes(scenario, poses.size(), "Reassociate");
  CheckSizes(scenario, previous.size(), "Reassociate (previous association)");
  const Mat2& r = options.measurement_cov;

  // 1. Gate every measurement against the current map.
  std::vector<Mat2> covs;
  for (const Mat2& info : LandmarkInformation(poses, landmarks, previous, r)) {
    covs.push_back(CovarianceFromInformation(info));
  }
  LandmarkGrid grid;
  for (std::size_t i = 0; i < landmarks.size(); ++i) grid.Insert(static_cast<int>(i), landmarks[i]);
  AssociatedMap out;
  out.poses = poses;
  out.landmarks = landmarks;
  std::vector<int> near;
  for (std::size_t k = 0; k < scenario.steps.size(); ++k) {
    const std::vector<Measurement>& zs = scenario.steps[k].data.measurements;
    std::vector<Candidate> candidates;
    for (std::size_t j = 0; j < zs.size(); ++j) {
      if (Excluded(options, k, j)) continue;
      near.clear();
      grid.Near(models::InverseMeasurement(poses[k], zs[j]), &near);
      for (int i : near) {
        const auto li = static_cast<std::size_t>(i);
        const auto d2 =
            GateDistance(poses[k], nullptr, landmarks[li], covs[li], zs[j], r, options.gate_chi2);
        if (d2) candidates.push_back({static_cast<int>(j), i, *d2});
      }
    }
    out.association.push_back(AssignGreedy(std::move(candidates), zs.size()));
  }

  // 2. Unassociated measurements, in step order, create landmarks or join those created so far.
  std::vector<Track> born;
  LandmarkGrid born_grid;
  const int first_born = static_cast<int>(landmarks.size());
  for (std::size_t k = 0; k < scenario.steps.size(); ++k) {
    const std::vector<Measurement>& zs = scenario.steps[k].data.measurements;
    std::vector<int>& assigned = out.association[k];
    std::vector<Candidate> candidates;
    for (std::size_t j = 0; j < zs.size(); ++j) {
      if (assigned[j] != kUnassociated || Excluded(options, k, j)) continue;
      near.clear();
      born_grid.Near(models::InverseMeasurement(poses[k], zs[j]), &near);
      for (int b : near) {
        const Track& t = born[static_cast<std::size_t>(b)];
        const auto d2 = GateDistance(poses[k], nullptr, t.m, t.p, zs[j], r, options.gate_chi2);
        if (d2) candidates.push_back({static_cast<int>(j), b, *d2});
      }
    }
    const std::vector<int> joined = AssignGreedy(std::move(candidates), zs.size());
    for (std::size_t j = 0; j < zs.size(); ++j) {
      if (assigned[j] != kUnassociated || Excluded(options, k, j)) continue;
      int b = joined[j];
      if (b == kUnassociated) {
        b = static_cast<int>(born.size());
        born.push_back(BirthTrack(poses[k], zs[j], r));
        born_grid.Insert(b, born.back().m);
        ++out.born;
      } else {
        Track& t = born[static_cast<std::size_t>(b)];
        const Landmark before = t.m;
        UpdateTrack(poses[k], zs[j], r, &t);
        born_grid.Move(b, before, t.m);
      }
      assigned[j] = first_born + b;
    }
  }
  for (const Track& t : born) out.landmarks.push_back(t.m);

  // 3. Drop landmarks without support, so that merging sees only real candidates (a single
  // clutter detection near a landmark would otherwise be merged into it).
  DropUnsupportedLandmarks(options, poses, &out);

  // 4. Merge landmarks that are within the gate of each other and (almost) never seen at the
  // same step, closest pairs first; a merged landmark is the information-weighted mean of its
  // parts. A step where both were seen then holds two measurements of one landmark; the next
  // re-association keeps the better one.
  const std::size_t n = out.landmarks.size();
  std::vector<Mat2> info = LandmarkInformation(poses, out.landmarks, out.association, r);
  std::vector<std::vector<int>> steps_seen(n);
  for (std::size_t k = 0; k < out.association.size(); ++k) {
    for (int a : out.association[k]) {
      if (a != kUnassociated)
        steps_seen[static_cast<std::size_t>(a)].push_back(static_cast<int>(k));
    }
  }
  LandmarkGrid all_grid;
  for (std::size_t i = 0; i < n; ++i) all_grid.Insert(static_cast<int>(i), out.landmarks[i]);
  const double s2 = options.merge_position_std * options.merge_position_std;
  std::vector<Candidate> pairs;
  for (std::size_t i = 0; i < n; ++i) {
    near.clear();
    all_grid.Near(out.landmarks[i], &near);
    const Mat2 pi = CovarianceFromInformation(info[i]);
    for (int jn : near) {
      const auto j = static_cast<std::size_t>(jn);
      if (j <= i) continue;
      const Mat2 s = pi + CovarianceFromInformation(info[j]) + s2 * Mat2::Identity();
      const double d2 = EvalGaussian2(out.landmarks[i] - out.landmarks[j], s).mahalanobis2;
      if (d2 < options.gate_chi2) pairs.push_back({static_cast<int>(i), jn, d2});
    }
  }
  std::sort(pairs.begin(), pairs.end(), [](const Candidate& a, const Candidate& b) {
    if (a.d2 != b.d2) return a.d2 < b.d2;
    if (a.measurement != b.measurement) return a.measurement < b.measurement;
    return a.landmark < b.landmark;
  });
  std::vector<int> root(n);
  std::iota(root.begin(), root.end(), 0);
  const auto find = [&root](int i) {
    while (root[static_cast<std::size_t>(i)] != i) i = root[static_cast<std::size_t>(i)];
    return i;
  };
  std::vector<Vec2> weighted(n);
  for (std::size_t i = 0; i < n; ++i) weighted[i] = info[i] * out.landmarks[i];
  for (const Candidate& p : pairs) {
    const int a = find(p.measurement);
    const int b = find(p.landmark);
    if (a == b) continue;
    std::vector<int>& sa = steps_seen[static_cast<std::size_t>(a)];
    std::vector<int>& sb = steps_seen[static_cast<std::size_t>(b)];
    std::vector<int> common;
    std::set_intersection(sa.begin(), sa.end(), sb.begin(), sb.end(), std::back_inserter(common));
    const double smaller = static_cast<double>(std::min(sa.size(), sb.size()));
    if (static_cast<double>(common.size()) > kMaxMergeOverlap * smaller) continue;
    std::vector<int> merged;
    std::set_union(sa.begin(), sa.end(), sb.begin(), sb.end(), std::back_inserter(merged));
    const int keep = std::min(a, b);
    const int gone = std::max(a, b);
    root[static_cast<std::size_t>(gone)] = keep;
    steps_seen[static_cast<std::size_t>(keep)] = std::move(merged);
    steps_seen[static_cast<std::size_t>(gone)].clear();
    info[static_cast<std::size_t>(keep)] += info[static_cast<std::size_t>(gone)];
    weighted[static_cast<std::size_t>(keep)] += weighted[static_cast<std::size_t>(gone)];
    const Mat2& ik = info[static_cast<std::size_t>(keep)];
    if (std::abs(ik.determinant()) > 1e-300) {
      out.landmarks[static_cast<std::size_t>(keep)] =
          ik.inverse() * weighted[static_cast<std::size_t>(keep)];
    }
    ++out.merged;
  }
  if (out.merged > 0) {
    for (auto& step : out.association) {
      for (int& a : step) {
        if (a != kUnassociated) a = find(a);
      }
    }
  }
  // Merged-away landmarks now have no observations; renumber.
  if (out.merged > 0) DropUnsupportedLandmarks(options, poses, &out);
  return out;
}

}  // namespace phdslam::reference
