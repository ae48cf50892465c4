#include "reference/pcrb/information_reduction.h"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "src/core/random.h"

namespace phdslam::reference::pcrb {
namespace {

void Check(const ReductionSettings& s) {
  if (!(s.detection_probability > 0.0 && s.detection_probability <= 1.0)) {
    throw std::invalid_argument(
        "information reduction: detection probability must be in (0, 1], "
        "got " +
        std::to_string(s.detection_probability));
  }
  if (!(s.clutter_per_area >= 0.0) || !std::isfinite(s.clutter_per_area)) {
    throw std::invalid_argument("information reduction: clutter density must be finite and >= 0");
  }
  if (!(s.gate_sigma > 0.0) || !std::isfinite(s.gate_sigma)) {
    throw std::invalid_argument("information reduction: gate_sigma must be finite and > 0");
  }
  if (s.samples < 1) throw std::invalid_argument("information reduction: samples must be >= 1");
}

struct Point {
  double x = 0.0;
  double y = 0.0;
};

double Density(const Point& z) {
  return std::exp(-0.5 * (z.x * z.x + z.y * z.y)) / (2.0 * std::numbers::pi);
}

Point UniformInDisc(double radius, RandomStream& rng) {
  const double r = radius * std::sqrt(rng.Uniform());
  const double a = 2.0 * std::numbers::pi * rng.Uniform();
  return {r * std::cos(a), r * std::sin(a)};
}

// |s|^2 of one draw of the measurement set.
double SquaredScore(const ReductionSettings& s, RandomStream& rng) {
  const double pd = s.detection_probability;
  const bool detected = rng.Uniform() < pd;
  Point d;
  if (detected) d = {rng.Normal(), rng.Normal()};
  if (detected && d.x * d.x + d.y * d.y > s.gate_sigma * s.gate_sigma) {
    return d.x * d.x + d.y * d.y;  // outside the disc only the landmark explains it
  }
  const double area = std::numbers::pi * s.gate_sigma * s.gate_sigma;
  const int clutter = rng.Poisson(s.clutter_per_area * area);
  double weight = 0.0;
  Point sum;
  auto add = [&](const Point& z) {
    const double g = Density(z);
    weight += g;
    sum.x += g * z.x;
    sum.y += g * z.y;
  };
  if (detected) add(d);
  for (int c = 0; c < clutter; ++c) add(UniformInDisc(s.gate_sigma, rng));
  const double denominator = (1.0 - pd) * s.clutter_per_area + pd * weight;
  if (!(denominator > 0.0)) return 0.0;  // nothing in the disc: no information
  const double sx = pd * sum.x / denominator;
  const double sy = pd * sum.y / denominator;
  return sx * sx + sy * sy;
}

}  // namespace

double InformationReductionFactor(const ReductionSettings& settings, std::uint64_t stream_seed) {
  Check(settings);
  if (settings.clutter_per_area == 0.0) return settings.detection_probability;
  RandomStream rng(stream_seed);
  double total = 0.0;
  for (int i = 0; i < settings.samples; ++i) total += SquaredScore(settings, rng);
  return total / (2.0 * settings.samples);
}

}  // namespace phdslam::reference::pcrb
