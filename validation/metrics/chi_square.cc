#include "validation/metrics/chi_square.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace phdslam::validation {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kEps = 1e-16;

// log P(a, y) and log Q(a, y) of the regularised incomplete gamma functions, y > 0. The smaller of
// the two is computed directly (power series below a + 1, Lentz continued fraction above), the
// other as log(1 - exp(.)), so both tails keep full relative accuracy.
struct LogGammaTails {
  double log_p;
  double log_q;
};

LogGammaTails RegularisedGammaTails(double a, double y) {
  const double log_prefactor = a * std::log(y) - y - std::lgamma(a);
  if (y < a + 1.0) {
    double term = 1.0 / a;
    double sum = term;
    for (int n = 1; n < 100000; ++n) {
      term *= y / (a + n);
      sum += term;
      if (std::abs(term) < std::abs(sum) * kEps) break;
    }
    const double log_p = std::log(sum) + log_prefactor;
    return {log_p, std::log1p(-std::exp(log_p))};
  }
  constexpr double kTiny = 1e-300;
  double b = y + 1.0 - a;
  double c = 1.0 / kTiny;
  double d = 1.0 / b;
  double h = d;
  for (int i = 1; i < 100000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < kTiny) d = kTiny;
    c = b + an / c;
    if (std::abs(c) < kTiny) c = kTiny;
    d = 1.0 / d;
    const double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1.0) < kEps) break;
  }
  const double log_q = std::log(h) + log_prefactor;
  return {std::log1p(-std::exp(log_q)), log_q};
}

void ValidateDof(double dof, const char* caller) {
  if (!(dof > 0.0) || !std::isfinite(dof)) {
    throw std::invalid_argument(std::string(caller) + ": dof = " + std::to_string(dof) +
                                "; expected a finite positive number");
  }
}

}  // namespace

double ChiSquareCdf(double x, double dof) {
  ValidateDof(dof, "ChiSquareCdf");
  if (std::isnan(x)) throw std::invalid_argument("ChiSquareCdf: x is NaN");
  if (x <= 0.0) return 0.0;
  if (x == kInf) return 1.0;
  return std::exp(RegularisedGammaTails(0.5 * dof, 0.5 * x).log_p);
}

double ChiSquareQuantile(double probability, double dof) {
  ValidateDof(dof, "ChiSquareQuantile");
  if (!(probability >= 0.0 && probability <= 1.0)) {
    throw std::invalid_argument("ChiSquareQuantile: probability = " + std::to_string(probability) +
                                "; expected a value in [0, 1]");
  }
  if (probability == 0.0) return 0.0;
  if (probability == 1.0) return kInf;

  // Solve in y = x / 2 for the gamma(a = dof / 2) distribution, on the log of the smaller tail:
  // g(y) = log P(a, y) - log p (lower) or log Q(a, y) - log(1 - p) (upper). 1 - p is exact for
  // p >= 0.5. Newton steps on g are kept inside a bracket and replaced by bisection when they leave
  // it or stall.
  const double a = 0.5 * dof;
  const bool lower = probability < 0.5;
  const double log_target = lower ? std::log(probability) : std::log(1.0 - probability);
  const auto g = [&](double y, double* slope) {
    const LogGammaTails tails = RegularisedGammaTails(a, y);
    const double log_density = (a - 1.0) * std::log(y) - y - std::lgamma(a);
    if (lower) {
      *slope = std::exp(log_density - tails.log_p);
      return tails.log_p - log_target;
    }
    *slope = -std::exp(log_density - tails.log_q);
    return tails.log_q - log_target;
  };
  // g is increasing in y for the lower tail and decreasing for the upper one; `below` says that y
  // is left of the root.
  const auto below = [&](double value) { return lower ? value < 0.0 : value > 0.0; };

  double lo = 0.0;
  double hi = std::max(a, 1.0);
  double slope = 0.0;
  for (int i = 0; i < 2000; ++i) {
    const double value = g(hi, &slope);
    if (!below(value)) break;
    lo = hi;
    hi *= 2.0;
  }
  double y = 0.5 * (lo + hi);
  for (int iteration = 0; iteration < 1000; ++iteration) {
    const double value = g(y, &slope);
    if (value == 0.0) return 2.0 * y;
    if (below(value)) {
      lo = y;
    } else {
      hi = y;
    }
    double next = y - value / slope;
    if (!(next > lo && next < hi) || !std::isfinite(next)) next = 0.5 * (lo + hi);
    if (std::abs(next - y) <= 1e-15 * y || hi - lo <= 1e-15 * hi) {
      y = next;
      break;
    }
    y = next;
  }
  return 2.0 * y;
}

}  // namespace phdslam::validation
