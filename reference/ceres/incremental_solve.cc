#include "reference/ceres/incremental_solve.h"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <utility>

#include "reference/ceres/held_measurement_prior.h"
#include "reference/ceres/pose_covariance_propagation.h"
#include "reference/ceres/static_point_check.h"
#include "src/core/gaussian.h"
#include "src/models/range_bearing_model.h"

namespace phdslam::reference {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// Pose k predicted from pose k-1 (or the initial pose) by step k's odometry.
Pose PredictPose(const datasets::Scenario& scenario, const std::vector<OdometryIncrement>& inc,
                 const std::vector<Pose>& poses, std::size_t k) {
  const Pose base = k == 0 ? scenario.initial_pose : poses[k - 1];
  return inc[k].propagated ? ComposeRelative(base, inc[k].delta) : base;
}

/// The steps [0, end) of the graph, chunk by chunk: held_before for the chunk ending at `end`.
std::size_t HeldBefore(const IncrementalSettings& settings, std::size_t end) {
  return settings.active_steps > 0 && end > settings.active_steps ? end - settings.active_steps : 0;
}

void Validate(const IncrementalSettings& settings) {
  if (settings.chunk_steps == 0) {
    throw std::invalid_argument("IncrementalSettings.chunk_steps: expected >= 1");
  }
}

using Mat23 = Eigen::Matrix<double, 2, 3>;

/// A landmark of the own-association pass.
struct PassLandmark {
  Mat2 cov;
  LandmarkSupport support;
  LandmarkStatus status = LandmarkStatus::kTentative;
  Mat23 cross = Mat23::Zero();  ///< Cov(m, x) with the pass's current pose (pose_landmark_cross)
  /// Its first and its latest detection, each with the odometry since (static_point_chi2).
  StaticPointTrack static_point = {};
  bool moving = false;  ///< deleted by the static-point check
};

/// Landmark started at the inverse model of z from (x, px): covariance from R and the pose.
Mat2 StartCovariance(const Pose& x, const Mat3& px, const Measurement& z, const Mat2& r) {
  const Mat23 jx = InverseModelPoseJacobian(x, z);
  Mat2 p = models::BirthCovariance(x, z, r) + jx * px * jx.transpose();
  Symmetrize(p);
  return p;
}

/// Update of a tentative landmark (m, p) with cross-covariance c = Cov(m, x) by z taken at
/// (x, px), the pose not updated (a Schmidt update: the pose keeps its estimate and covariance,
/// the landmark's gain and its cross-covariance account for their correlation).
void UpdateTentativeCorrelated(const Pose& x, const Mat3& px, const Measurement& z, const Mat2& r,
                               Landmark* m, Mat2* p, Mat23* c) {
  if ((*m - x.head<2>()).squaredNorm() < 1e-18) return;
  const models::PredictionWithJacobians h = models::PredictWithJacobians(x, *m);
  const Mat2 u = (*p) * h.j.hm.transpose() + (*c) * h.j.hx.transpose();  // Cov(m, z)
  Mat2 s =
      h.j.hm * u + h.j.hx * (c->transpose() * h.j.hm.transpose() + px * h.j.hx.transpose()) + r;
  Symmetrize(s);
  const Mat2 k = u * s.inverse();
  *m += k * Vec2(z(0) - h.z_hat(0), WrapAngle(z(1) - h.z_hat(1)));
  *p -= k * u.transpose();
  Symmetrize(*p);
  *c -= k * (h.j.hm * (*c) + h.j.hx * px);
}

/// EKF update of a tentative landmark (m, p) by z taken at (x, px), the pose not updated.
void UpdateTentative(const Pose& x, const Mat3& px, const Measurement& z, const Mat2& r,
                     Landmark* m, Mat2* p) {
  if ((*m - x.head<2>()).squaredNorm() < 1e-18) return;
  const models::PredictionWithJacobians h = models::PredictWithJacobians(x, *m);
  const Mat2 s = h.j.hm * (*p) * h.j.hm.transpose() + h.j.hx * px * h.j.hx.transpose() + r;
  const Mat2 k = (*p) * h.j.hm.transpose() * s.inverse();
  *m += k * Vec2(z(0) - h.z_hat(0), WrapAngle(z(1) - h.z_hat(1)));
  *p = (Mat2::Identity() - k * h.j.hm) * (*p);
  Symmetrize(*p);
}

/// State of the own-association pass.
class AssociationPass {
 public:
  AssociationPass(const datasets::Scenario& scenario, const OdometrySpec& odometry,
                  const IncrementalAssociationOptions& options)
      : scenario_(scenario), increments_(*odometry.increments), options_(options) {
    if (options.static_point_chi2 > 0.0 &&
        (options.model_increments == nullptr ||
         options.model_increments->size() != scenario.steps.size())) {
      throw std::invalid_argument(
          "IncrementalAssociationOptions.model_increments: one per step needed for the "
          "static-point check");
    }
    poses_.assign(scenario.steps.size(), Pose::Zero());
    for (const auto& step : scenario.steps) {
      association_.emplace_back(step.data.measurements.size(), kUnassociated);
    }
  }

  /// Predicts, associates and starts landmarks for step k.
  void Step(std::size_t k) {
    const Pose& base = k == 0 ? scenario_.initial_pose : poses_[k - 1];
    if (options_.pose_landmark_cross) PropagateCross(base, increments_[k]);
    if (options_.static_point_chi2 > 0.0) AdvanceAnchors((*options_.model_increments)[k]);
    px_ = PropagatePoseCovariance(base, increments_[k], px_);
    Symmetrize(px_);
    poses_[k] = PredictPose(scenario_, increments_, poses_, k);
    const bool relocalising = RelocalisationUnderWay(k);
    const Pose& x = poses_[k];
    std::vector<int> ids;
    std::vector<MapLandmark> view;
    NearLandmarks(x, &ids);
    if (relocalising) {  // the map before the mode is left to the multi-scan match
      ids.erase(std::remove_if(ids.begin(), ids.end(),
                               [&](int i) { return i < relocalisation_first_landmark_; }),
                ids.end());
    }
    view.reserve(ids.size());
    const bool with_pd =
        options_.gate.new_landmark_intensity > 0.0 || options_.gate.jcbb_null_intensity > 0.0;
    for (int i : ids) {
      const auto li = static_cast<std::size_t>(i);
      MapLandmark v{landmarks_[li], state_[li].cov};
      if (options_.pose_landmark_cross) v.pose_cross = state_[li].cross;
      if (with_pd)
        v.detection_probability = options_.sensor.DetectionProbability(x, landmarks_[li]);
      view.push_back(v);
    }
    const std::vector<Measurement>& zs = scenario_.steps[k].data.measurements;
    const ScanAssociation a =
        AssociateScan(x, px_, view, zs, options_.measurement_cov, options_.gate);
    const Mat2& r = options_.measurement_cov;
    for (std::size_t j = 0; j < zs.size(); ++j) {
      if (options_.skip_ambiguous && a.gated[j] > 1) continue;
      int id = a.landmark[j] == kUnassociated ? kUnassociated
                                              : ids[static_cast<std::size_t>(a.landmark[j])];
      if (id != kUnassociated && DeletedAsMoving(id, zs[j])) id = kUnassociated;
      if (id != kUnassociated) {
        PassLandmark& l = state_[static_cast<std::size_t>(id)];
        ++l.support.detections;
        if (l.status == LandmarkStatus::kTentative) {
          Landmark* m = &landmarks_[static_cast<std::size_t>(id)];
          if (options_.pose_landmark_cross) {
            UpdateTentativeCorrelated(x, px_, zs[j], r, m, &l.cov, &l.cross);
          } else {
            UpdateTentative(x, px_, zs[j], r, m, &l.cov);
          }
        }
        association_[k][j] = id;
      } else if (!options_.birth_outside_gates || a.gated[j] == 0) {
        association_[k][j] = static_cast<int>(landmarks_.size());
        ids.push_back(association_[k][j]);
        landmarks_.push_back(models::InverseMeasurement(x, zs[j]));
        state_.push_back({StartCovariance(x, px_, zs[j], r), {1, 0.0}});
        if (options_.static_point_chi2 > 0.0) {
          state_.back().static_point.first = AnchorAt(zs[j], r);
          state_.back().static_point.latest = state_.back().static_point.first;
        }
        if (options_.pose_landmark_cross) {
          state_.back().cross = InverseModelPoseJacobian(x, zs[j]) * px_;
        }
        ++born_;
      }
    }
    for (int i : ids) {
      PassLandmark& l = state_[static_cast<std::size_t>(i)];
      if (l.status == LandmarkStatus::kDeleted) continue;  // a moving object, deleted above
      l.support.expected +=
          options_.sensor.DetectionProbability(x, landmarks_[static_cast<std::size_t>(i)]);
      l.status = ClassifyLandmark(l.support, options_.confirmation);
    }
    if (relocalising) BufferAndMatch(k);
  }

  /// The association of steps [0, end) without the deleted landmarks.
  [[nodiscard]] Association SolveAssociation(std::size_t end) const {
    Association out(association_.begin(), association_.begin() + static_cast<std::ptrdiff_t>(end));
    for (auto& step : out) {
      for (int& a : step) {
        if (a != kUnassociated && Deleted(a)) a = kUnassociated;
      }
    }
    return out;
  }

  /// Solves steps [0, end) and refreshes the marginals used by the gate.
  ceres::Solver::Summary Solve(std::size_t end, const OdometrySpec& odometry,
                               ceres::LossFunction* loss, const IncrementalSettings& settings) {
    const Association partial = SolveAssociation(end);
    const std::size_t held = HeldBefore(settings, end);
    next_held_ = HeldBefore(settings, std::min(scenario_.steps.size(), end + settings.chunk_steps));
    if (settings.held_prior && !priors_) priors_.emplace(scenario_, loss);
    if (priors_) priors_->FoldUntil(held, partial, poses_, landmarks_);
    FactorGraph graph(scenario_, odometry, partial, loss, &poses_, &landmarks_, held,
                      priors_ ? &*priors_ : nullptr);
    ceres::Solver::Summary summary = graph.Optimise(settings.solve);
    if (options_.delete_collapsed && DeleteCollapsed(partial, held) > 0) {
      FactorGraph pruned(scenario_, odometry, SolveAssociation(end), loss, &poses_, &landmarks_,
                         held, priors_ ? &*priors_ : nullptr);
      RefreshMarginals(end, held, odometry, loss, &pruned);
    } else {
      RefreshMarginals(end, held, odometry, loss, &graph);
    }
    return summary;
  }

  /// The confirmed landmarks, renumbered in order of creation.
  [[nodiscard]] AssociatedMap Confirmed() const {
    AssociatedMap out;
    std::vector<int> index(landmarks_.size(), kUnassociated);
    for (std::size_t i = 0; i < landmarks_.size(); ++i) {
      if (state_[i].status != LandmarkStatus::kConfirmed) continue;
      index[i] = static_cast<int>(out.landmarks.size());
      out.landmarks.push_back(landmarks_[i]);
    }
    out.association = association_;
    if (moving_ > 0) {
      for (const std::vector<int>& step : association_) {
        std::vector<bool>& excluded = out.excluded.emplace_back(step.size(), false);
        for (std::size_t j = 0; j < step.size(); ++j) {
          excluded[j] =
              step[j] != kUnassociated && state_[static_cast<std::size_t>(step[j])].moving;
        }
      }
    }
    for (auto& step : out.association) {
      for (int& a : step) {
        if (a != kUnassociated) a = index[static_cast<std::size_t>(a)];
      }
    }
    out.poses = poses_;
    out.born = born_;
    out.moving = moving_;
    out.relocalisations = relocalisations_;
    out.relocalisations_abandoned = relocalisations_abandoned_;
    out.dropped = static_cast<int>(landmarks_.size() - out.landmarks.size());
    return out;
  }

  [[nodiscard]] int collapsed() const { return collapsed_; }

 private:
  /// The detections of one scan as inverse-model points from its dead-reckoned pose.
  struct BufferedScan {
    std::size_t step = 0;
    std::vector<Landmark> points;
  };

  /// With re-localisation on (options_.relocalisation_position_std > 0): whether the pass is
  /// in the re-localisation mode for the current step, entered when the pose's marginal
  /// position standard deviation (larger axis) exceeds the threshold. In the mode the landmarks
  /// mapped before it are not gated scan by scan: their association is left to the multi-scan
  /// match (BufferAndMatch). Landmarks started in the mode are associated as usual.
  bool RelocalisationUnderWay(std::size_t k) {
    const double sd = options_.relocalisation_position_std;
    if (sd <= 0.0) return false;
    if (relocalising_) return true;
    const double variance =
        Eigen::SelfAdjointEigenSolver<Mat2>(px_.topLeftCorner<2, 2>()).eigenvalues().maxCoeff();
    if (variance <= sd * sd) return false;
    relocalising_ = true;
    relocalisation_start_ = k;
    relocalisation_first_landmark_ = static_cast<int>(landmarks_.size());
    buffer_.clear();
    return true;
  }

  /// Buffers step k's detections as points from its dead-reckoned pose (the last
  /// relocalisation_scans scans with detections) and, once they are full, matches them with the
  /// map from before the mode (TryRelocalise), again at every further scan until a match is
  /// unique.
  void BufferAndMatch(std::size_t k) {
    const std::vector<Measurement>& zs = scenario_.steps[k].data.measurements;
    if (zs.empty()) return;
    BufferedScan& scan = buffer_.emplace_back();
    scan.step = k;
    for (const Measurement& z : zs) scan.points.push_back(models::InverseMeasurement(poses_[k], z));
    const auto n = static_cast<std::size_t>(options_.relocalisation_scans);
    if (buffer_.size() > n) buffer_.erase(buffer_.begin());
    if (buffer_.size() == n) TryRelocalise(k);
  }

  /// Matches the buffered detections with the confirmed landmarks from before the mode within
  /// reach of the newest pose k; on a unique match associates them (a detection associated with
  /// a landmark started in the mode moves to the old one), corrects the poses since the mode
  /// began (the free ones: the full correction from the first buffered scan on, a growing
  /// fraction of it before) and the landmarks started in the mode, and leaves the mode with the
  /// pose covariance the match supports (position std the inlier distance, heading std that over
  /// the inliers' span).
  void TryRelocalise(std::size_t k) {
    const double position_variance =
        Eigen::SelfAdjointEigenSolver<Mat2>(px_.topLeftCorner<2, 2>()).eigenvalues().maxCoeff();
    std::vector<int> ids;
    std::vector<Landmark> map;
    const double limit = options_.gate.max_landmark_distance;
    const double reach = limit + 3.0 * std::sqrt(position_variance);
    for (std::size_t i = 0; i < static_cast<std::size_t>(relocalisation_first_landmark_); ++i) {
      if (state_[i].status != LandmarkStatus::kConfirmed) continue;
      if (limit > 0.0 && (landmarks_[i] - poses_[k].head<2>()).norm() > reach) continue;
      ids.push_back(static_cast<int>(i));
      map.push_back(landmarks_[i]);
    }
    std::vector<Landmark> points;
    for (const BufferedScan& scan : buffer_) {
      points.insert(points.end(), scan.points.begin(), scan.points.end());
    }
    const RelocalisationMatch match =
        MatchPointsToMap(points, map, poses_[k], px_, options_.relocalisation);
    if (!match.found && match.ambiguous && options_.relocalisation_leave_ambiguous) {
      relocalising_ = false;  // the map admits several corrections: scan by scan again
      buffer_.clear();
      ++relocalisations_abandoned_;
      return;
    }
    if (!match.found) return;
    const std::size_t first = buffer_.front().step;
    const std::size_t start = std::min(first, std::max(relocalisation_start_, next_held_));
    for (std::size_t s = start; s <= k; ++s) {
      RigidCorrection c = match.correction;
      if (s < first) {
        const double f =
            static_cast<double>(s - start + 1) / static_cast<double>(first - start + 1);
        c.rotation *= f;
        c.translation *= f;
      }
      poses_[s] = ApplyCorrection(c, poses_[s]);
    }
    for (std::size_t i = static_cast<std::size_t>(relocalisation_first_landmark_);
         i < landmarks_.size(); ++i) {
      landmarks_[i] =
          ApplyCorrection(match.correction, Pose(landmarks_[i].x(), landmarks_[i].y(), 0.0))
              .head<2>();
    }
    std::size_t n = 0;
    for (const BufferedScan& scan : buffer_) {
      for (std::size_t j = 0; j < scan.points.size(); ++j, ++n) {
        const int m = match.landmark[n];
        if (m == kUnassociated) continue;
        const int id = ids[static_cast<std::size_t>(m)];
        const int previous = association_[scan.step][j];
        if (previous != kUnassociated)
          --state_[static_cast<std::size_t>(previous)].support.detections;
        association_[scan.step][j] = id;
        ++state_[static_cast<std::size_t>(id)].support.detections;
      }
    }
    const double d = options_.relocalisation.inlier_distance;
    const double heading = d / std::max(match.baseline, d);
    px_ = Vec3(d * d, d * d, heading * heading).asDiagonal();
    if (options_.pose_landmark_cross) {
      for (PassLandmark& l : state_) l.cross = Mat23::Zero();
    }
    relocalising_ = false;
    buffer_.clear();
    ++relocalisations_;
  }

  /// Carries every live landmark's static-point anchor by one step's odometry.
  void AdvanceAnchors(const OdometryIncrement& increment) {
    for (PassLandmark& l : state_) {
      if (l.status == LandmarkStatus::kDeleted) continue;
      AdvanceTrack(increment, &l.static_point);
    }
  }

  /// With the static-point check on, whether landmark `id`, associated with z, is deleted as a
  /// moving object (MovingAfter: options_.static_point_failures detections in a row fail the
  /// check against the landmark's first detection but pass it against the latest one, i.e. the
  /// detections drift away from their first one step by step, as a moving object's do).
  bool DeletedAsMoving(int id, const Measurement& z) {
    if (options_.static_point_chi2 <= 0.0) return false;
    PassLandmark& l = state_[static_cast<std::size_t>(id)];
    const StaticPointOptions check{options_.static_point_chi2, options_.static_point_heading_std,
                                   options_.static_point_failures};
    if (!MovingAfter(z, options_.measurement_cov, check, &l.static_point)) return false;
    l.status = LandmarkStatus::kDeleted;
    l.moving = true;
    ++moving_;
    return true;
  }

  /// Carries every landmark's Cov(m, x) from pose k-1 (`base`) to pose k = base (+) inc.delta.
  void PropagateCross(const Pose& base, const OdometryIncrement& inc) {
    if (!inc.propagated) return;
    const Mat3 jt = PoseCompositionJacobian(base, inc).transpose();
    for (PassLandmark& l : state_) {
      if (l.status != LandmarkStatus::kDeleted) l.cross = l.cross * jt;
    }
  }

  /// Refreshes the gate's marginals (newest pose, landmarks near it) from `graph`, or from the
  /// squared-loss graph with options_.squared_loss_marginals. When ceres::Covariance fails and
  /// options_.marginals_without_collapsed, they are computed again from the graph without the
  /// measurements of the landmarks collapsed onto a free pose (CollapsedLandmarks), which stay in
  /// the map. Otherwise the gate keeps the propagated pose covariance.
  void RefreshMarginals(std::size_t end, std::size_t held, const OdometrySpec& odometry,
                        ceres::LossFunction* loss, FactorGraph* graph) {
    ceres::LossFunction* marginal_loss = options_.squared_loss_marginals ? nullptr : loss;
    std::optional<FactorGraph> squared;
    if (loss != nullptr && options_.squared_loss_marginals) {
      squared.emplace(scenario_, odometry, SolveAssociation(end), nullptr, &poses_, &landmarks_,
                      held, priors_ ? &*priors_ : nullptr);
    }
    if (Marginals(end, squared ? &*squared : graph) || !options_.marginals_without_collapsed)
      return;
    Association without = SolveAssociation(end);
    const std::vector<int> collapsed = CollapsedLandmarks(
        without, poses_, landmarks_, held, std::sqrt(options_.measurement_cov(0, 0)));
    if (collapsed.empty()) return;
    for (auto& step : without) {
      for (int& a : step) {
        if (std::binary_search(collapsed.begin(), collapsed.end(), a)) a = kUnassociated;
      }
    }
    FactorGraph pruned(scenario_, odometry, without, marginal_loss, &poses_, &landmarks_, held,
                       priors_ ? &*priors_ : nullptr);
    Marginals(end, &pruned);
  }

  /// The gate's marginals from `graph`; false (nothing changed) when ceres::Covariance fails.
  bool Marginals(std::size_t end, FactorGraph* graph) {
    std::vector<int> near;
    NearLandmarks(poses_[end - 1], &near);
    near.erase(
        std::remove_if(near.begin(), near.end(),
                       [&](int i) { return !graph->HasLandmark(static_cast<std::size_t>(i)); }),
        near.end());
    Mat3 px;
    std::vector<Mat2> covs;
    std::vector<Mat23> cross;
    if (!graph->NewestCovariances(near, &px, &covs,
                                  options_.pose_landmark_cross ? &cross : nullptr)) {
      return false;
    }
    px_ = px;
    if (options_.pose_landmark_cross) {
      // Landmarks outside `near` are not gated before the next refresh; their correlation with
      // the newest pose is not computed.
      for (PassLandmark& l : state_) l.cross = Mat23::Zero();
    }
    for (std::size_t n = 0; n < near.size(); ++n) {
      state_[static_cast<std::size_t>(near[n])].cov = covs[n];
      if (options_.pose_landmark_cross) state_[static_cast<std::size_t>(near[n])].cross = cross[n];
    }
    return true;
  }

  /// Deletes the landmarks of `partial` (deleted ones are unassociated there) that lie within one
  /// range standard deviation of a free pose they are associated from (CollapsedLandmarks).
  /// Returns how many were deleted.
  int DeleteCollapsed(const Association& partial, std::size_t held) {
    const std::vector<int> collapsed = CollapsedLandmarks(
        partial, poses_, landmarks_, held, std::sqrt(options_.measurement_cov(0, 0)));
    for (int i : collapsed) state_[static_cast<std::size_t>(i)].status = LandmarkStatus::kDeleted;
    collapsed_ += static_cast<int>(collapsed.size());
    return static_cast<int>(collapsed.size());
  }

  [[nodiscard]] bool Deleted(int i) const {
    return state_[static_cast<std::size_t>(i)].status == LandmarkStatus::kDeleted;
  }

  /// Live landmarks within the gate's distance limit of x (all live ones when it is 0).
  void NearLandmarks(const Pose& x, std::vector<int>* out) const {
    out->clear();
    const double limit = options_.gate.max_landmark_distance;
    for (std::size_t i = 0; i < landmarks_.size(); ++i) {
      if (state_[i].status == LandmarkStatus::kDeleted) continue;
      if (limit > 0.0 && (landmarks_[i] - x.head<2>()).squaredNorm() > limit * limit) continue;
      out->push_back(static_cast<int>(i));
    }
  }

  const datasets::Scenario& scenario_;
  const std::vector<OdometryIncrement>& increments_;
  IncrementalAssociationOptions options_;
  std::vector<Pose> poses_;
  std::vector<Landmark> landmarks_;
  std::vector<PassLandmark> state_;
  Association association_;
  Mat3 px_ = Mat3::Zero();
  int born_ = 0;
  int collapsed_ = 0;
  int moving_ = 0;                               ///< landmarks deleted by the static-point check
  std::optional<HeldMeasurementPriors> priors_;  ///< with IncrementalSettings::held_prior
  std::size_t next_held_ = 0;  ///< poses before it are held in the next chunk solve
  // Re-localisation (RelocalisationUnderWay): whether it is under way, the step it began at,
  // the first landmark started in it, and the scans buffered.
  bool relocalising_ = false;
  std::size_t relocalisation_start_ = 0;
  int relocalisation_first_landmark_ = 0;
  std::vector<BufferedScan> buffer_;
  int relocalisations_ = 0;            ///< unique matches applied
  int relocalisations_abandoned_ = 0;  ///< modes left on an ambiguous match
};

}  // namespace

void IncrementalSolve(const datasets::Scenario& scenario, const OdometrySpec& odometry,
                      const Association& association, std::size_t landmark_count,
                      ceres::LossFunction* loss, const IncrementalSettings& settings,
                      const SolveObserver& observer, std::vector<Pose>* poses,
                      std::vector<Landmark>* landmarks) {
  Validate(settings);
  const std::size_t steps = association.size();
  poses->assign(steps, Pose::Zero());
  landmarks->assign(landmark_count, Landmark::Zero());
  std::vector<bool> started(landmark_count, false);
  HeldMeasurementPriors priors(scenario, loss);
  for (std::size_t done = 0; done < steps;) {
    const std::size_t end = std::min(steps, done + settings.chunk_steps);
    for (std::size_t k = done; k < end; ++k) {
      (*poses)[k] = PredictPose(scenario, *odometry.increments, *poses, k);
      for (std::size_t j = 0; j < association[k].size(); ++j) {
        const int i = association[k][j];
        if (i == kUnassociated || started[static_cast<std::size_t>(i)]) continue;
        (*landmarks)[static_cast<std::size_t>(i)] =
            models::InverseMeasurement((*poses)[k], scenario.steps[k].data.measurements[j]);
        started[static_cast<std::size_t>(i)] = true;
      }
    }
    const Association partial(association.begin(),
                              association.begin() + static_cast<std::ptrdiff_t>(end));
    const Clock::time_point t = Clock::now();
    const std::size_t held = HeldBefore(settings, end);
    if (settings.held_prior) priors.FoldUntil(held, partial, *poses, *landmarks);
    FactorGraph graph(scenario, odometry, partial, loss, poses, landmarks, held,
                      settings.held_prior ? &priors : nullptr);
    const ceres::Solver::Summary summary = graph.Optimise(settings.solve);
    if (observer) observer(summary, SecondsSince(t));
    done = end;
  }
}

AssociatedMap IncrementalAssociation(const datasets::Scenario& scenario,
                                     const OdometrySpec& odometry, ceres::LossFunction* loss,
                                     const IncrementalSettings& settings,
                                     const IncrementalAssociationOptions& options,
                                     const SolveObserver& observer, double* association_seconds,
                                     int* collapsed) {
  Validate(settings);
  if (options.relocalisation_position_std > 0.0 && options.relocalisation_scans < 2) {
    throw std::invalid_argument(
        "IncrementalAssociationOptions.relocalisation_scans: expected >= 2");
  }
  AssociationPass pass(scenario, odometry, options);
  const std::size_t steps = scenario.steps.size();
  for (std::size_t done = 0; done < steps;) {
    const std::size_t end = std::min(steps, done + settings.chunk_steps);
    Clock::time_point t = Clock::now();
    for (std::size_t k = done; k < end; ++k) pass.Step(k);
    if (association_seconds != nullptr) *association_seconds += SecondsSince(t);
    t = Clock::now();
    const ceres::Solver::Summary summary = pass.Solve(end, odometry, loss, settings);
    if (observer) observer(summary, SecondsSince(t));
    done = end;
  }
  if (collapsed != nullptr) *collapsed = pass.collapsed();
  return pass.Confirmed();
}

}  // namespace phdslam::reference
