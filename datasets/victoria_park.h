// The Victoria Park data set (ACFR, Guivant & Nebot): tree detections, 40 Hz car odometry and GPS,
// read from <data_dir>/victoria-park/ and turned into one Scenario per Monte Carlo seed
// (docs/algorithms/models.md section 6).
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include "datasets/scenario.h"
#include "src/core/angles.h"
#include "src/core/types.h"

namespace phdslam::datasets {

/// Millisecond clock value of t = 0 s: every source is put on t = (ms - 20967) / 1000 s.
inline constexpr double kVictoriaParkClockOriginMs = 20967.0;

/// Detector limits applied on loading (docs/algorithms/models.md section 6.2): the kept detections.
inline constexpr double kVictoriaParkMaxRange = 50.0;                 ///< m
inline constexpr double kVictoriaParkMaxAbsBearing = DegToRad(85.0);  ///< rad

/// The raw, seed-independent data on one clock (s).
struct VictoriaParkData {
  /// 40 Hz odometry: controls[i] = [v_e (m/s), alpha (rad)] stamped control_times[i].
  std::vector<double> control_times;
  std::vector<Control> controls;

  struct Scan {
    double t = 0.0;
    /// Detections [range, bearing] with the bearing shifted by -pi/2 (forward 0, left positive),
    /// only those with range <= 50 m, |bearing| <= 85 deg and diameter >= 0.
    std::vector<Measurement> trees;
    std::vector<double> diameters;  ///< m, one per kept detection
  };
  /// One per distinct detection time of measurements.dat, in time order. A scan whose detections
  /// all fall outside the limits is kept with no trees (it becomes a clutter-only step).
  std::vector<Scan> scans;

  /// GPS fixes from aa3_gpsx.mat: x = Lo_m, y = La_m. Jumps and gaps are left as they are.
  std::vector<GpsFix> gps;
};

/// Reads <data_dir>/victoria-park/: measurements.dat (tree detections), the controls and
/// aa3_gpsx.mat (GPS). Controls come from aa3_dr.mat when it exists (full precision); otherwise
/// from inputs.dat (the same samples, speed rounded to 3 decimals and steering to 4). Throws
/// std::runtime_error naming the file and the line or variable on missing files, malformed lines,
/// non-finite values, times that go backwards, or variables of mismatched length.
VictoriaParkData LoadVictoriaParkData(const std::filesystem::path& data_dir);

/// The files LoadVictoriaParkData reads from `data_dir` (inputs.dat only when aa3_dr.mat is
/// absent), relative to `data_dir`; files that do not exist are left out.
std::vector<std::filesystem::path> VictoriaParkDataFiles(const std::filesystem::path& data_dir);

struct VictoriaParkOptions {
  double clutter_rate = 5.0;  ///< Poisson mean per scan; range U[0, fov_range], bearing in FOV
  double fov_range = 50.0;    ///< m
  double fov_half_angle = DegToRad(85.0);  ///< rad
  double range_buffer = 5.0;               ///< m, active set: docs/algorithms/models.md section 3.4
  double angle_buffer = DegToRad(5.0);     ///< rad, likewise
  /// pD = pd_max (1 - r / fov_range) inside the FOV (DetectionProfile::kLinearRange).
  double detection_probability_max = 0.7;
  /// Nominal pD of the estimate threshold log((1 - pD)^2) = log(0.09)
  /// (docs/algorithms/phd-slam.md section 3.5).
  double detection_probability_nominal = 0.7;
  Mat2 measurement_noise_cov;  ///< R = diag(1 m^2, (1 deg)^2)
  Mat2 control_noise_cov;      ///< Q_u = diag(1 (m/s)^2, (4 deg)^2), steering angle variance
  /// 0 = every scan that the controls cover; otherwise stop after this many filter steps. The
  /// first steps are the same whatever the limit.
  int max_steps = 0;

  VictoriaParkOptions();
  /// Throws std::invalid_argument naming the field that is out of range.
  void Validate() const;
};

/// One Monte Carlo run (docs/algorithms/models.md sections 6.3 and 6.4). Controls and scans are
/// merged as the reference code does: walking over the control samples k, a filter step is taken
/// for the next scan j when tau_j < t_k (strictly). Its time stamps are [previous scan time,
/// t_{k_last} .. t_{k-1}, tau_j] and its controls [control held at the previous scan (sample k-1 of
/// that step), u_{k_last} .. u_{k-1}] (zero-order hold); then k_last = k. The previous scan time
/// and held control are recorded only when k > 1 (1-based), so when the first scan precedes the
/// first control the first step has the single time stamp tau_1 (no propagation) and the second
/// step starts at the first control time. The merge ends when every scan is used or the controls
/// run out (later scans are dropped). Should two scans fall between the same two control samples
/// (never in the real data), the second is taken at the same k with the single sub-interval
/// [previous scan, tau] and the held control, where the reference loop would go back in time.
///
/// Each step's measurements are the scan's real detections (origin kUnknownOrigin, no noise, no
/// thinning) followed by Poisson(clutter_rate) artificial clutter points (origin kClutter), each
/// drawn as range ~ U[0, fov_range) then bearing ~ U[-fov_half_angle, fov_half_angle), from
/// RandomStream(DeriveSeed(HashName("victoria-park"), seed)), one scan after the other.
Scenario MakeVictoriaParkScenario(const VictoriaParkData& data, std::uint64_t seed,
                                  const VictoriaParkOptions& options = {});

}  // namespace phdslam::datasets
