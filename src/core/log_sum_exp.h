// Log-domain arithmetic for weights, which are natural logarithms everywhere in phdslam.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>

namespace phdslam {

constexpr double kNegInf = -std::numeric_limits<double>::infinity();

/// log(exp(a) + exp(b)) without overflow; -inf is the identity.
inline double LogAddExp(double a, double b) {
  if (a == kNegInf) return b;
  if (b == kNegInf) return a;
  const double m = std::max(a, b);
  return m + std::log1p(std::exp(-std::abs(a - b)));
}

/// log(sum_i exp(x_i)); -inf for an empty span or when every entry is -inf.
inline double LogSumExp(std::span<const double> x) {
  if (x.empty()) return kNegInf;
  const double m = *std::max_element(x.begin(), x.end());
  if (m == kNegInf) return kNegInf;
  double s = 0.0;
  for (double v : x) s += std::exp(v - m);
  return m + std::log(s);
}

}  // namespace phdslam
