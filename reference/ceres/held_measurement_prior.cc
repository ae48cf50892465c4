#include "reference/ceres/held_measurement_prior.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <stdexcept>
#include <string>

#include "reference/ceres/linear_prior.h"
#include "reference/ceres/odometry_increment.h"
#include "src/core/angles.h"
#include "src/core/gaussian.h"
#include "src/models/range_bearing_model.h"

namespace phdslam::reference {

HeldMeasurementPriors::HeldMeasurementPriors(const datasets::Scenario& scenario,
                                             const ceres::LossFunction* loss)
    : scenario_(scenario), loss_(loss), whitening_(WhiteningMatrix<2>(scenario.sensor.noise_cov)) {}

void HeldMeasurementPriors::FoldUntil(std::size_t end, const Association& association,
                                      const std::vector<Pose>& poses,
                                      const std::vector<Landmark>& landmarks) {
  if (end > association.size() || end > poses.size() || end > scenario_.steps.size()) {
    throw std::invalid_argument("HeldMeasurementPriors::FoldUntil: step " + std::to_string(end) +
                                " beyond the association, the poses or the scenario");
  }
  if (information_.size() < landmarks.size()) {
    information_.resize(landmarks.size(), Mat2::Zero());
    vector_.resize(landmarks.size(), Vec2::Zero());
    count_.resize(landmarks.size(), 0);
  }
  for (std::size_t k = folded_; k < end; ++k) {
    const std::vector<Measurement>& zs = scenario_.steps[k].data.measurements;
    if (association[k].size() != zs.size()) {
      throw std::invalid_argument("HeldMeasurementPriors::FoldUntil: step " + std::to_string(k) +
                                  " has " + std::to_string(association[k].size()) + " labels for " +
                                  std::to_string(zs.size()) + " measurements");
    }
    for (std::size_t j = 0; j < zs.size(); ++j) {
      const int label = association[k][j];
      if (label == kUnassociated) continue;
      const auto i = static_cast<std::size_t>(label);
      const Landmark& m0 = landmarks.at(i);
      if ((m0 - poses[k].head<2>()).squaredNorm() < 1e-18) continue;  // bearing undefined
      const models::PredictionWithJacobians h = models::PredictWithJacobians(poses[k], m0);
      const Vec2 r0 = whitening_ * Vec2(h.z_hat(0) - zs[j](0), WrapAngle(h.z_hat(1) - zs[j](1)));
      const Mat2 jm = whitening_ * h.j.hm;
      double weight = 1.0;
      if (loss_ != nullptr) {
        double rho[3];
        loss_->Evaluate(r0.squaredNorm(), rho);
        weight = rho[1];
      }
      information_[i] += weight * jm.transpose() * jm;
      vector_[i] += weight * jm.transpose() * (jm * m0 - r0);
      ++count_[i];
    }
  }
  folded_ = std::max(folded_, end);
}

Landmark HeldMeasurementPriors::Mean(std::size_t i) const {
  return information_[i].ldlt().solve(vector_[i]);
}

ceres::CostFunction* HeldMeasurementPriors::MakeFactor(std::size_t i, double* block) const {
  Mat2 info = information_[i];
  Symmetrize(info);
  const auto lower = CholeskyLower<2>(info);
  if (!lower) return nullptr;
  LinearPrior prior;
  prior.blocks = {block};
  prior.linearization_points = {Mean(i)};
  prior.a = lower->transpose();
  prior.b = Eigen::Vector2d::Zero();
  return LinearPriorFactor::Create(prior);
}

}  // namespace phdslam::reference
