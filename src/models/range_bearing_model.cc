#include "src/models/range_bearing_model.h"

#include <cmath>

#include "src/core/angles.h"
#include "src/core/gaussian.h"

namespace phdslam::models {

Landmark InverseMeasurement(const Pose& x, const Measurement& z) {
  const double a = x(2) + z(1);
  return {x(0) + z(0) * std::cos(a), x(1) + z(0) * std::sin(a)};
}

namespace {

Mat2 JacobianFromAngle(const Measurement& z, double c, double s) {
  Mat2 g;
  g << c, -z(0) * s, s, z(0) * c;
  return g;
}

Mat2 CovarianceFromJacobian(const Mat2& g, const Mat2& r) {
  Mat2 p = g * r * g.transpose();
  Symmetrize(p);
  return p;
}

}  // namespace

Mat2 InverseMeasurementJacobian(const Pose& x, const Measurement& z) {
  const double a = x(2) + z(1);
  return JacobianFromAngle(z, std::cos(a), std::sin(a));
}

Mat2 BirthCovariance(const Pose& x, const Measurement& z, const Mat2& r) {
  return CovarianceFromJacobian(InverseMeasurementJacobian(x, z), r);
}

BirthGaussian BirthFromMeasurement(const Pose& x, const Measurement& z, const Mat2& r) {
  const double a = x(2) + z(1);
  const double c = std::cos(a);
  const double s = std::sin(a);
  return {{x(0) + z(0) * c, x(1) + z(0) * s},
          CovarianceFromJacobian(JacobianFromAngle(z, c, s), r)};
}

}  // namespace phdslam::models
