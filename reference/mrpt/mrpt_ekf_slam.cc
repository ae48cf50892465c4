#include "reference/mrpt/mrpt_ekf_slam.h"

#include <mrpt/math/CMatrixFixed.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt/poses/CPosePDFGaussian.h>
#include <mrpt/slam/CRangeBearingKFSLAM2D.h>
#include <mrpt/slam/data_association.h>
#include <mrpt/system/COutputLogger.h>

#include <Eigen/Core>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "reference/mrpt/motion_increment.h"
#include "src/core/angles.h"
#include "src/core/gaussian.h"

namespace phdslam::reference {

// CRangeBearingKFSLAM2D with one hook: when the KD-tree candidate search is switched off, the
// association step calls MRPT's data_association_full_covariance itself with use_kd_tree = false.
// Everything else (observation building, predictions, the association routine, the results kept
// for getLastDataAssociation()) follows MRPT's own OnGetObservationsAndDataAssociation.
class MrptEkfSlam::Filter final : public mrpt::slam::CRangeBearingKFSLAM2D {
 public:
  explicit Filter(bool kdtree_candidates) : kdtree_candidates_(kdtree_candidates) {}

  /// Removes the landmarks whose `keep` flag is false: their entries of the state vector, their
  /// rows and columns of the covariance, and the id map, which is rebuilt as index <-> index (the
  /// ids MRPT itself gives landmarks measured with id -1).
  void KeepLandmarks(const std::vector<bool>& keep) {
    std::vector<Eigen::Index> rows = {0, 1, 2};
    for (std::size_t i = 0; i < keep.size(); ++i) {
      if (!keep[i]) continue;
      rows.push_back(static_cast<Eigen::Index>(3 + 2 * i));
      rows.push_back(static_cast<Eigen::Index>(4 + 2 * i));
    }
    const Eigen::VectorXd x = m_xkk.asEigen()(rows);
    const Eigen::MatrixXd p = m_pkk.asEigen()(rows, rows);
    m_xkk.resize(x.size());
    m_xkk.asEigen() = x;
    m_pkk.setSize(p.rows(), p.cols());
    m_pkk.asEigen() = p;
    m_IDs.clear();
    const auto n = static_cast<unsigned int>((x.size() - 3) / 2);
    for (unsigned int j = 0; j < n; ++j) m_IDs.insert(j, j);
  }

 protected:
  void OnGetObservationsAndDataAssociation(vector_KFArray_OBS& out_z,
                                           std::vector<int>& out_data_association,
                                           const vector_KFArray_OBS& in_all_predictions,
                                           const KFMatrix& in_s,
                                           const std::vector<size_t>& in_lm_indices_in_s,
                                           const KFMatrix_OxO& in_r) override {
    if (kdtree_candidates_) {
      CRangeBearingKFSLAM2D::OnGetObservationsAndDataAssociation(
          out_z, out_data_association, in_all_predictions, in_s, in_lm_indices_in_s, in_r);
      return;
    }
    const auto obs = m_SF->getObservationByClass<mrpt::obs::CObservationBearingRange>();
    if (!obs) throw std::logic_error("MrptEkfSlam: the sensory frame has no bearing-range scan");
    const std::size_t n_obs = obs->sensedData.size();
    out_z.resize(n_obs);
    mrpt::math::CMatrixDouble z_means(n_obs, 2);
    for (std::size_t j = 0; j < n_obs; ++j) {
      out_z[j][0] = obs->sensedData[j].range;
      out_z[j][1] = obs->sensedData[j].yaw;
      z_means(j, 0) = out_z[j][0];
      z_means(j, 1) = out_z[j][1];
    }
    // Every measurement carries landmark id -1, so every one goes through association.
    out_data_association.assign(n_obs, -1);
    const std::size_t n_pred = in_lm_indices_in_s.size();
    if (n_obs == 0 || n_pred == 0) {
      m_last_data_association = TDataAssocInfo();
      return;
    }
    TDataAssocInfo& info = m_last_data_association;
    info.clear();
    info.Y_pred_covs = in_s;
    info.Y_pred_means.setSize(n_pred, 2);
    for (std::size_t q = 0; q < n_pred; ++q) {
      const std::size_t lm = in_lm_indices_in_s[q];
      info.Y_pred_means(q, 0) = in_all_predictions[lm][0];
      info.Y_pred_means(q, 1) = in_all_predictions[lm][1];
      info.predictions_IDs.push_back(lm);
    }
    mrpt::slam::data_association_full_covariance(
        z_means, info.Y_pred_means, info.Y_pred_covs, info.results, options.data_assoc_method,
        options.data_assoc_metric, options.data_assoc_IC_chi2_thres, /*DAT_ASOC_USE_KDTREE=*/false,
        info.predictions_IDs, options.data_assoc_IC_metric, options.data_assoc_IC_ml_threshold);
    for (const auto& [obs_index, lm_index] : info.results.associations) {
      out_data_association[obs_index] = static_cast<int>(lm_index);
    }
  }

 private:
  bool kdtree_candidates_;
};

namespace {

mrpt::math::CMatrixDouble33 ToMrpt(const Mat3& m) {
  mrpt::math::CMatrixDouble33 out;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) out(r, c) = m(r, c);
  }
  return out;
}

mrpt::obs::CActionCollection::Ptr MakeOdometryAction(const PoseGaussian& increment) {
  mrpt::obs::CActionRobotMovement2D movement;
  movement.estimationMethod = mrpt::obs::CActionRobotMovement2D::emOdometry;
  const mrpt::poses::CPose2D mean(increment.mean(0), increment.mean(1), increment.mean(2));
  movement.rawOdometryIncrementReading = mean;
  movement.poseChange = mrpt::poses::CPosePDFGaussian::Create(mean, ToMrpt(increment.cov));
  auto actions = mrpt::obs::CActionCollection::Create();
  actions->insert(movement);
  return actions;
}

mrpt::obs::CSensoryFrame::Ptr MakeScan(const std::vector<Measurement>& measurements,
                                       const models::SensorModel& sensor) {
  auto scan = mrpt::obs::CObservationBearingRange::Create();
  scan->minSensorDistance = 0.0F;
  scan->maxSensorDistance = static_cast<float>(sensor.fov_range);
  scan->fieldOfView_yaw = static_cast<float>(2.0 * sensor.fov_half_angle);
  scan->fieldOfView_pitch = 0.0F;
  scan->sensorLocationOnRobot = mrpt::poses::CPose3D();
  scan->validCovariances = false;
  scan->sensor_std_range = static_cast<float>(std::sqrt(sensor.noise_cov(0, 0)));
  scan->sensor_std_yaw = static_cast<float>(std::sqrt(sensor.noise_cov(1, 1)));
  scan->sensor_std_pitch = 0.0F;
  scan->sensedData.resize(measurements.size());
  for (std::size_t j = 0; j < measurements.size(); ++j) {
    auto& m = scan->sensedData[j];
    m.range = static_cast<float>(measurements[j](0));
    m.yaw = static_cast<float>(measurements[j](1));
    m.pitch = 0.0F;
    m.landmarkID = -1;  // unknown association, for every measurement
  }
  auto sf = mrpt::obs::CSensoryFrame::Create();
  sf->insert(scan);
  return sf;
}

}  // namespace

MrptEkfSlam::MrptEkfSlam(filters::EstimatorContext context, MrptEkfSlamOptions options)
    : context_(std::move(context)), options_(options) {
  options_.Validate();
  if (!context_.motion) throw std::invalid_argument("mrpt-ekf: the context has no motion model");
  const Mat2& r = context_.sensor.noise_cov;
  if (r(0, 1) != 0.0 || r(1, 0) != 0.0 || !(r(0, 0) > 0.0) || !(r(1, 1) > 0.0)) {
    throw std::invalid_argument(
        "mrpt-ekf: CRangeBearingKFSLAM2D needs a diagonal, positive measurement noise covariance "
        "(sensor.noise_cov)");
  }
  filter_ = std::make_unique<Filter>(options_.mrpt_kdtree_candidates);
  filter_->setVerbosityLevel(mrpt::system::LVL_ERROR);
  filter_->KF_options.method = mrpt::bayes::kfEKFNaive;
  filter_->KF_options.enable_profiler = false;
  auto& o = filter_->options;
  o.std_sensor_range = static_cast<float>(std::sqrt(r(0, 0)));
  o.std_sensor_yaw = static_cast<float>(std::sqrt(r(1, 1)));
  o.create_simplemap = false;
  o.data_assoc_method = options_.association == AssociationMethod::kJcbb ? mrpt::slam::assocJCBB
                                                                         : mrpt::slam::assocNN;
  o.data_assoc_metric = options_.metric == AssociationMetric::kMatchingLikelihood
                            ? mrpt::slam::metricML
                            : mrpt::slam::metricMaha;
  o.data_assoc_IC_metric = mrpt::slam::metricMaha;
  o.data_assoc_IC_chi2_thres = options_.ic_chi2_quantile;
  // The filter starts at the known initial pose with zero covariance (reset() puts it at 0).
  filter_->reset();
  auto& x = filter_->internal_getXkk();
  x[0] = context_.initial_pose(0);
  x[1] = context_.initial_pose(1);
  x[2] = WrapAngle(context_.initial_pose(2));
  heading_ = context_.initial_pose(2);
}

MrptEkfSlam::~MrptEkfSlam() = default;

filters::StepOutput MrptEkfSlam::Step(const datasets::StepData& step) {
  auto& x = filter_->internal_getXkk();
  auto& p = filter_->internal_getPkk();
  const Pose from(x[0], x[1], heading_);
  PoseGaussian increment =
      RobotFrameIncrement(*context_.motion, context_.control_noise_cov, step, from);

  if (filter_->isMapEmpty() && step.times.size() > 1) {
    // MRPT would skip the prediction: apply it here with MRPT's own formulas (pose composition,
    // F = d(x (+) d)/dx, Q = the increment covariance rotated into the world frame).
    const Mat3 rot = RobotToWorldRotation(x[2]);
    Mat3 f = Mat3::Identity();
    f(0, 2) = -increment.mean(0) * std::sin(x[2]) - increment.mean(1) * std::cos(x[2]);
    f(1, 2) = increment.mean(0) * std::cos(x[2]) - increment.mean(1) * std::sin(x[2]);
    Mat3 pxx;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) pxx(r, c) = p(r, c);
    }
    pxx = f * pxx * f.transpose() + rot * increment.cov * rot.transpose();
    Symmetrize(pxx);
    const Pose moved = ComposePose(Pose(x[0], x[1], x[2]), increment.mean);
    x[0] = moved(0);
    x[1] = moved(1);
    x[2] = WrapAngle(moved(2));
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) p(r, c) = pxx(r, c);
    }
    increment = PoseGaussian{};
  }

  auto actions = MakeOdometryAction(increment);
  auto scan = MakeScan(step.measurements, context_.sensor);
  filter_->processActionObservation(actions, scan);
  if (options_.symmetrize_covariance) {
    auto pkk = filter_->internal_getPkk().asEigen();
    pkk = (0.5 * (pkk + pkk.transpose())).eval();
  }

  std::size_t n_landmarks = filter_->getNumberOfLandmarksInTheMap();
  association_counts_.resize(n_landmarks, 0);
  birth_steps_.resize(n_landmarks, step_index_);
  last_associations_.assign(step.measurements.size(), -1);
  for (const auto& [obs_index, lm_index] : filter_->getLastDataAssociation().results.associations) {
    if (lm_index < association_counts_.size()) ++association_counts_[lm_index];
    if (obs_index < last_associations_.size()) {
      last_associations_[obs_index] = static_cast<int>(lm_index);
    }
  }
  if (options_.prune_after_steps > 0) {
    std::vector<bool> keep(n_landmarks, true);
    bool any_removed = false;
    for (std::size_t i = 0; i < n_landmarks; ++i) {
      if (association_counts_[i] < options_.prune_min_associations &&
          step_index_ - birth_steps_[i] == options_.prune_after_steps) {
        keep[i] = false;
        any_removed = true;
      }
    }
    if (any_removed) {
      filter_->KeepLandmarks(keep);
      std::vector<int> new_index(n_landmarks, -1);
      std::size_t j = 0;
      for (std::size_t i = 0; i < n_landmarks; ++i) {
        if (!keep[i]) continue;
        new_index[i] = static_cast<int>(j);
        association_counts_[j] = association_counts_[i];
        birth_steps_[j] = birth_steps_[i];
        ++j;
      }
      n_landmarks = j;
      for (int& a : last_associations_) {
        if (a >= 0) a = new_index[static_cast<std::size_t>(a)];
      }
      association_counts_.resize(j);
      birth_steps_.resize(j);
    }
  }
  ++step_index_;

  const auto& xs = filter_->internal_getXkk();
  const auto& ps = filter_->internal_getPkk();
  heading_ += WrapAngle(xs[2] - heading_);
  filters::StepOutput out;
  out.pose = Pose(xs[0], xs[1], heading_);
  Mat3 cov;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) cov(r, c) = ps(r, c);
  }
  out.pose_cov = cov;
  out.diag.ess = 1.0;
  out.diag.resampled = false;
  out.diag.hypotheses = 1;
  out.diag.map_components = static_cast<int>(n_landmarks);
  return out;
}

filters::MapEstimate MrptEkfSlam::Map() const {
  filters::MapEstimate map;
  const std::size_t n = filter_->getNumberOfLandmarksInTheMap();
  for (std::size_t i = 0; i < n; ++i) {
    mrpt::slam::CRangeBearingKFSLAM2D::KFArray_FEAT mean;
    mrpt::slam::CRangeBearingKFSLAM2D::KFMatrix_FxF cov;
    filter_->getLandmarkMean(i, mean);
    filter_->getLandmarkCov(i, cov);
    map.means.emplace_back(mean[0], mean[1]);
    Mat2 c;
    c << cov(0, 0), cov(0, 1), cov(1, 0), cov(1, 1);
    map.covs.push_back(c);
    map.log_weights.push_back(0.0);
  }
  return map;
}

filters::MapEstimate MrptEkfSlam::PostProcessedMap() const {
  const filters::MapEstimate raw = Map();
  filters::MapEstimate kept;
  for (std::size_t i = 0; i < raw.size(); ++i) {
    const int count = i < association_counts_.size() ? association_counts_[i] : 0;
    if (count < options_.min_associations) continue;
    kept.means.push_back(raw.means[i]);
    kept.covs.push_back(raw.covs[i]);
    kept.log_weights.push_back(raw.log_weights[i]);
  }
  return kept;
}

}  // namespace phdslam::reference
