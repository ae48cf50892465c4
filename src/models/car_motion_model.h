// Guivant/Nebot car model of the Victoria Park truck with the laser offset built in
// (docs/algorithms/models.md section 2.3). Control u = [v_e, alpha] (encoder speed m/s, steering
// angle rad). The Jacobians are the simplified ones of the reference code, not the exact
// derivatives: Fu's v_e column omits 1/(1 - H/L tan(alpha)) and its alpha column ignores the
// dependence of v_c on alpha.
#pragma once

#include "src/models/motion_model.h"

namespace phdslam::models {

struct CarGeometry {
  double wheelbase_l = 2.83;
  double encoder_offset_h = 0.75;
  double laser_a = 3.78;
  double laser_b = 0.50;

  /// A kinematic bicycle: the given wheelbase, the encoder on the rear axle and the sensor at it
  /// (h = a = b = 0).
  static CarGeometry Bicycle(double wheelbase) {
    CarGeometry g;
    g.wheelbase_l = wheelbase;
    g.encoder_offset_h = 0.0;
    g.laser_a = 0.0;
    g.laser_b = 0.0;
    return g;
  }
};

class CarMotionModel final : public MotionModel {
 public:
  CarMotionModel() = default;
  explicit CarMotionModel(const CarGeometry& g) : g_(g) {}

  [[nodiscard]] Pose Predict(const Pose& x, const Control& u, double dt) const override;
  [[nodiscard]] MotionJacobians Jacobians(const Pose& x, const Control& u,
                                          double dt) const override;
  [[nodiscard]] std::unique_ptr<MotionModel> Clone() const override {
    return std::make_unique<CarMotionModel>(*this);
  }
  [[nodiscard]] const CarGeometry& geometry() const { return g_; }

 private:
  CarGeometry g_;
};

}  // namespace phdslam::models
