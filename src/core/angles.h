// Angle helpers. Only bearings are wrapped (docs/algorithms/models.md section 1.2); headings never
// are.
#pragma once

#include <cmath>
#include <numbers>

namespace phdslam {

/// Wraps an angle into [-pi, pi].
inline double WrapAngle(double a) {
  constexpr double kPi = std::numbers::pi;
  constexpr double kTwoPi = 2.0 * std::numbers::pi;
  // Fast paths for the common cases (already wrapped, or off by one turn).
  if (a >= -kPi && a <= kPi) return a;
  if (a > kPi && a <= 3.0 * kPi) return a - kTwoPi;
  if (a < -kPi && a >= -3.0 * kPi) return a + kTwoPi;
  double w = std::fmod(a + kPi, kTwoPi);
  if (w < 0.0) w += kTwoPi;
  return w - kPi;
}

constexpr double DegToRad(double deg) { return deg * std::numbers::pi / 180.0; }
constexpr double RadToDeg(double rad) { return rad * 180.0 / std::numbers::pi; }

}  // namespace phdslam
