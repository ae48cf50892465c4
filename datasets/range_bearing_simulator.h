// Simulation of range-bearing scans and noisy odometry along a known true trajectory: the
// measurement rules of the paper's synthetic scenario (docs/algorithms/models.md section 4), shared
// by the paper scenario and the scenario generator.
#pragma once

#include <string_view>
#include <vector>

#include "datasets/scenario.h"
#include "src/core/random.h"
#include "src/core/types.h"
#include "src/models/sensor_model.h"

namespace phdslam::datasets {

/// Largest mean clutter count per scan accepted (each clutter point costs every filter an update).
inline constexpr double kMaxClutterRate = 1000.0;

/// The sensor and noise settings of a simulated scenario.
struct SimulationSettings {
  double detection_probability = 0.95;
  double clutter_rate = 5.0;  ///< Poisson mean per scan, before pD thinning
  double fov_range = 150.0;
  double fov_half_angle = 0.0;
  double range_buffer = 0.0;
  double angle_buffer = 0.0;
  Mat2 measurement_noise_cov = Mat2::Zero();
  Mat2 control_noise_cov = Mat2::Zero();

  /// Throws std::invalid_argument naming `owner` and the field when a value is out of range:
  /// detection_probability in (0, 1]; clutter_rate in [0, kMaxClutterRate]; fov_range > 0;
  /// fov_half_angle in (0, pi]; buffers >= 0; covariances finite, symmetric and positive
  /// semi-definite.
  void Validate(std::string_view owner) const;
  /// The sensor model filters use: constant profile, pd_max = pd_nominal = detection_probability.
  [[nodiscard]] models::SensorModel Sensor() const;

  /// The settings of a scenario's options struct with fields of the same names.
  template <class Options>
  static SimulationSettings Of(const Options& o) {
    SimulationSettings s;
    s.detection_probability = o.detection_probability;
    s.clutter_rate = o.clutter_rate;
    s.fov_range = o.fov_range;
    s.fov_half_angle = o.fov_half_angle;
    s.range_buffer = o.range_buffer;
    s.angle_buffer = o.angle_buffer;
    s.measurement_noise_cov = o.measurement_noise_cov;
    s.control_noise_cov = o.control_noise_cov;
    return s;
  }
};

/// A factor L with L L^T = cov for a symmetric positive semi-definite 2x2 matrix (the Cholesky
/// factor when cov is positive definite; a zero column where a variance is zero).
Mat2 NoiseFactor(const Mat2& cov);

/// Simulates every step along `truth`, docs/algorithms/models.md section 4.1, drawing from `rng`:
///   1. visible landmarks: squared range <= fov_range^2 and |wrap(bearing)| <= fov_half_angle
///      (both inclusive), listed in landmark-index order;
///   2. clutter: Poisson(clutter_rate) points, each a range uniform on [0, fov_range) then a
///      bearing uniform on [-fov_half_angle, fov_half_angle) (uniform in (r, phi), not in area);
///   3. N(0, R) noise added to every entry (two standard normals per entry, in list order), so a
///      clutter range near 0 can become negative, as in the reference;
///   4. pD thinning of every entry, clutter included (one uniform per entry, in list order);
///   5. bearings wrapped;
///   6. odometry of the step: true_controls[k] + N(0, Q_u).
/// truth[k] is the true pose at step k (0-based) and true_controls[k] the noise-free control held
/// from step k to k + 1; both have the same size. Time stamps are t_k = k dt. Step 0 carries times
/// {t_0} and no control; step k > 0 carries times {t_{k-1}, t_k} and the odometry of step k - 1.
/// origin[] holds the landmark index or kClutter of every kept measurement.
std::vector<ScenarioStep> SimulateRangeBearingSteps(const std::vector<Pose>& truth,
                                                    const std::vector<Control>& true_controls,
                                                    const std::vector<Landmark>& landmarks,
                                                    const SimulationSettings& settings, double dt,
                                                    RandomStream& rng);

}  // namespace phdslam::datasets
