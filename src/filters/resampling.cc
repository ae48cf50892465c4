#include "src/filters/resampling.h"

#include <cmath>

#include "src/core/log_sum_exp.h"

namespace phdslam::filters {

std::vector<double> NormalisedWeights(std::span<const double> log_weights) {
  const double total = LogSumExp(log_weights);
  std::vector<double> w(log_weights.size());
  for (std::size_t i = 0; i < w.size(); ++i) w[i] = std::exp(log_weights[i] - total);
  return w;
}

double EffectiveSampleSize(std::span<const double> weights) {
  double s = 0.0;
  for (double w : weights) s += w * w;
  return 1.0 / s;
}

std::vector<int> StratifiedResample(std::span<const double> weights,
                                    std::span<const double> uniforms) {
  const int n = static_cast<int>(weights.size());
  std::vector<int> out;
  out.reserve(n);
  double c = 0.0;
  for (int i = 0; i < n && static_cast<int>(out.size()) < n; ++i) {
    c += n * weights[i];
    if (c >= 1.0) {
      const double whole = std::floor(c);
      for (int k = 0; k < static_cast<int>(whole) && static_cast<int>(out.size()) < n; ++k) {
        out.push_back(i);
      }
      c -= whole;
    }
    if (static_cast<int>(out.size()) < n && c >= uniforms[out.size()]) {
      out.push_back(i);
      c -= 1.0;
    }
  }
  // Rounding can leave the last slot(s) empty; fill them with the last particle.
  while (static_cast<int>(out.size()) < n) out.push_back(n - 1);
  return out;
}

}  // namespace phdslam::filters
