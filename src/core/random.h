// Seeded random streams. Every draw in phdslam comes from a RandomStream whose seed is derived
// from (experiment, scenario seed, estimator, run); no clock and no global generator is used.
// The normal and Poisson samplers are written here (not std::*_distribution) so that a stream
// gives the same numbers with every standard library.
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <string_view>

namespace phdslam {

/// SplitMix64 finaliser: a bijective 64-bit mixer used to combine seed parts.
constexpr std::uint64_t MixSeed(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

/// FNV-1a hash of a name, for turning estimator or experiment names into seed parts.
constexpr std::uint64_t HashName(std::string_view s) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (char c : s) {
    h ^= static_cast<unsigned char>(c);
    h *= 0x100000001b3ULL;
  }
  return h;
}

/// Derives a stream seed from its parts: (purpose, seed) -> 64 bits, order-sensitive.
constexpr std::uint64_t DeriveSeed(std::uint64_t a, std::uint64_t b) {
  return MixSeed(MixSeed(a) ^ (b + 0x632be59bd9b4e019ULL));
}
constexpr std::uint64_t DeriveSeed(std::uint64_t a, std::uint64_t b, std::uint64_t c) {
  return DeriveSeed(DeriveSeed(a, b), c);
}

/// Standard normals by Marsaglia's polar method from any source of uniforms on [0, 1) (a
/// RandomStream, a KeyedStream): each accepted pair gives two normals, the second cached.
class PolarNormals {
 public:
  template <typename UniformSource>
  double Next(UniformSource& source) {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    double u = 0.0;
    double v = 0.0;
    double s = 0.0;
    do {
      u = 2.0 * source.Uniform() - 1.0;
      v = 2.0 * source.Uniform() - 1.0;
      s = u * u + v * v;
    } while (s >= 1.0 || s == 0.0);
    const double f = std::sqrt(-2.0 * std::log(s) / s);
    spare_ = v * f;
    has_spare_ = true;
    return u * f;
  }

 private:
  double spare_ = 0.0;
  bool has_spare_ = false;
};

class RandomStream {
 public:
  explicit RandomStream(std::uint64_t seed) : engine_(MixSeed(seed)) {}

  /// Uniform on [0, 1).
  double Uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  /// Uniform on [a, b).
  double Uniform(double a, double b) { return a + (b - a) * Uniform(); }

  /// Standard normal (Marsaglia polar method, one cached value).
  double Normal() { return normals_.Next(*this); }

  /// Poisson(lambda) by Knuth's multiplication method (fine for the small rates used here);
  /// for lambda > 30 the normal approximation rounded at zero is used instead.
  int Poisson(double lambda) {
    if (lambda <= 0.0) return 0;
    if (lambda > 30.0) {
      const double x = std::round(lambda + std::sqrt(lambda) * Normal());
      return x < 0.0 ? 0 : static_cast<int>(x);
    }
    const double limit = std::exp(-lambda);
    int k = 0;
    double p = Uniform();
    while (p > limit) {
      ++k;
      p *= Uniform();
    }
    return k;
  }

  std::uint64_t NextU64() { return engine_(); }

 private:
  std::mt19937_64 engine_;
  PolarNormals normals_;
};

}  // namespace phdslam
