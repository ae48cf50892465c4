// The UTIAS Multi-Robot Cooperative Localization and Mapping data set (Leung, Halpern, Barfoot &
// Liu, IJRR 2011): one robot of one sub-dataset as single-robot landmark SLAM, read from
// <data_dir>/utias-mrclam/MRCLAM_Dataset<N>/ (any sub-dataset of that layout).
//
// One filter step per camera image (the detections that share a time stamp). Between two images
// the commanded forward and yaw rates are held (zero-order hold) over the sub-intervals between
// their time stamps and integrated by the unicycle model (MotionKind::kVelocity). The Vicon pose
// is interpolated to every step time (heading unwrapped first); a step inside a truth gap longer
// than kMrclamMaxTruthGap, or outside the truth's time span, keeps an interpolated pose but is
// marked unscored (GroundTruth::pose_scored) and left out of every pose metric. The true map is
// Landmark_Groundtruth.dat; the barcode of each detection, mapped to a subject by the folder's
// Barcodes.dat, gives its hidden origin: a landmark index, or kClutter for the other robots
// (subjects 1-5) and for barcodes of no subject (misreads).
//
// Model parameters (the defaults of MrclamOptions): one set for every sub-dataset and robot,
// estimated from the five robots of dataset 6 by datasets/estimate_mrclam_parameters.py
// (python3 datasets/estimate_mrclam_parameters.py <data_dir>/utias-mrclam/MRCLAM_Dataset6):
//  - measurement noise: standard deviations of the range and bearing residuals of landmark
//    detections against the range and bearing predicted from the interpolated Vicon pose and the
//    true landmark (15383 detections at scored times; residuals beyond 1 m or 0.2 rad, 0.06 % of
//    them, left out as outliers): range sigma 0.175 m, bearing sigma 0.0124 rad (the biases,
//    -0.036 m and -0.0020 rad, are not modelled);
//  - field of view: the largest |bearing| of any detection (0.592 rad) rounded up to 0.6 rad, and
//    the largest landmark detection range (8.63 m) rounded up to 9 m;
//  - detection probability: at every image (step) of every robot, which of the true landmarks
//    inside that field of view (seen from the Vicon pose) the image detected. The rate falls with
//    range (0.48 at 1-2 m, 0.31 at 3-4 m, 0.16 at 6-7 m, 0.03 at 8-9 m; 0.291 overall), so the
//    model is the linear profile pD = pd_max (1 - r / 9 m) with pd_max = 0.549, the value whose
//    expected number of detections equals the observed number. The steps are the images with at
//    least one detection (no other image is logged), the same steps the filters take;
//  - clutter: the detections that are not of a landmark (other robots, misread barcodes) per
//    step: 3994 in 10582 steps, 0.377 per step;
//  - odometry noise: over every interval between two consecutive steps whose ends both have
//    Vicon truth (10574), the forward and heading parts of (Vicon relative pose - relative pose
//    integrated from the commands), in the frame of the first pose; under the filters' model
//    (control noise Q_u held over each sub-interval of length dt_i) their variances are
//    sigma_v^2 sum dt_i^2 and sigma_w^2 sum dt_i^2, whose maximum-likelihood estimates are the
//    means of e^2 / sum dt_i^2: sigma_v = 0.0547 m/s, sigma_w = 0.315 rad/s.
// The numbers above are printed by the script; the code's defaults repeat them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "datasets/scenario.h"
#include "src/core/types.h"

namespace phdslam::datasets {

/// Subjects 1..kMrclamRobots are the robots in every sub-dataset; landmarks have larger numbers.
inline constexpr int kMrclamRobots = 5;
/// A step whose Vicon samples on either side are further apart than this (s) is not scored.
inline constexpr double kMrclamMaxTruthGap = 0.5;

/// One row of RobotN_Measurement.dat.
struct MrclamDetection {
  double t = 0.0;      ///< s (Unix epoch)
  int barcode = 0;     ///< the barcode read (map it to a subject with Barcodes.dat)
  double range = 0;    ///< m
  double bearing = 0;  ///< rad, counter-clockwise from the robot's forward axis
};

/// The files of one robot of one sub-dataset, checked and put in time order.
struct MrclamRobotData {
  int dataset = 0;
  int robot = 0;
  std::map<int, int> barcode_subject;  ///< Barcodes.dat: barcode -> subject
  std::vector<int> landmark_subjects;  ///< Landmark_Groundtruth.dat subjects, in file order
  std::vector<Landmark> landmarks;     ///< their positions (m), same order
  /// Commanded [v (m/s), w (rad/s)] at strictly increasing times: rows are sorted stably by time
  /// and, of rows sharing a time stamp, the last one is kept.
  std::vector<double> odometry_times;
  std::vector<Control> odometry;
  /// Vicon poses at strictly increasing times (sorted, first of equal stamps kept), heading
  /// unwrapped along the sequence.
  std::vector<double> truth_times;
  std::vector<Pose> truth_poses;
  /// Detections sorted stably by time (rows out of time order join their image).
  std::vector<MrclamDetection> detections;
  /// Rows moved or dropped by the ordering above: out of order (a time earlier than the previous
  /// row's) and repeated time stamps.
  std::size_t odometry_out_of_order = 0;
  std::size_t odometry_repeated_times = 0;
  std::size_t truth_out_of_order = 0;
  std::size_t truth_repeated_times = 0;
  std::size_t detections_out_of_order = 0;
};

/// "utias-mrclam/MRCLAM_Dataset<dataset>", relative to the data folder.
std::filesystem::path MrclamFolder(int dataset);

/// Reads Barcodes.dat, Landmark_Groundtruth.dat and Robot<robot>_{Groundtruth,Odometry,
/// Measurement}.dat of <data_dir>/utias-mrclam/MRCLAM_Dataset<dataset>/. Lines starting with '#'
/// and blank lines are skipped. Throws std::runtime_error naming the file and the line for a
/// missing file, a line without the expected number of values, a value that is not a finite
/// number, a time stamp outside [0, 4e9] s (Unix time), a subject or barcode that is not a
/// positive integer, a barcode or subject listed twice, a detection of a barcode whose landmark
/// subject has no row in Landmark_Groundtruth.dat, a range that is not positive, and a file
/// without data lines. Rows out of time order are sorted and counted (MrclamCounts).
MrclamRobotData LoadMrclamRobot(const std::filesystem::path& data_dir, int dataset, int robot);

/// The files LoadMrclamRobot reads, relative to the data folder.
std::vector<std::filesystem::path> MrclamDataFiles(int dataset, int robot);

struct MrclamOptions {
  int dataset = 6;  ///< MRCLAM_Dataset<dataset>
  int robot = 1;    ///< 1..kMrclamRobots
  /// Leave out detections of other robots and of barcodes of no subject (kept as clutter when
  /// false, the default).
  bool drop_non_landmarks = false;
  /// The sensor and noise model the filters assume (header comment: estimated from dataset 6).
  /// pD at zero range of the linear profile pD = pd (1 - r / fov_range) inside the field of view
  /// (DetectionProfile::kLinearRange); also the nominal pD of the estimate threshold.
  double detection_probability = 0.549;
  double clutter_rate = 0.377;  ///< expected clutter detections per step
  double fov_range = 9.0;       ///< m
  double fov_half_angle = 0.6;  ///< rad
  double range_buffer = 1.0;    ///< m, active-set enlargement only
  double angle_buffer = 0.1;    ///< rad, likewise
  Mat2 measurement_noise_cov;   ///< R = diag(0.175^2 m^2, 0.0124^2 rad^2)
  Mat2 control_noise_cov;       ///< Q_u = diag(0.0547^2 (m/s)^2, 0.315^2 (rad/s)^2)
  /// 0 = every step; otherwise stop after this many filter steps.
  int max_steps = 0;

  MrclamOptions();
  /// Throws std::invalid_argument naming the field that is out of range.
  void Validate() const;
};

/// What the scenario was made of (written to config.json with the resolved options).
struct MrclamCounts {
  std::size_t steps = 0;                ///< filter steps (images)
  std::size_t unscored_steps = 0;       ///< steps left out of the pose metrics (truth gaps)
  std::size_t landmark_detections = 0;  ///< detections of a landmark of the true map
  std::size_t other_robot_detections = 0;
  std::size_t unknown_barcode_detections = 0;  ///< barcodes of no subject (misreads)
  bool non_landmarks_dropped = false;          ///< the two counts above left out of the steps
  /// Images before the first step (before the first command or the first Vicon pose, or without
  /// truth) and after the last command.
  std::size_t images_skipped = 0;
  /// Rows the reader put back in time order or merged (MrclamRobotData's counts).
  std::size_t odometry_out_of_order = 0;
  std::size_t odometry_repeated_times = 0;
  std::size_t truth_out_of_order = 0;
  std::size_t truth_repeated_times = 0;
  std::size_t detections_out_of_order = 0;
};

/// The scenario of options.robot (data.robot must be that robot). Deterministic: the seed only
/// names the Monte Carlo run (the data has no random part). The first step is the first image
/// at or after both the first command and the first Vicon pose whose truth is scored; it has one
/// time stamp (no propagation) and the initial pose is its interpolated Vicon pose. A later step
/// has the time stamps [previous image, commands strictly between, image] and the controls
/// [command in force at the previous image, those commands]. Images after the last command are
/// left out. Throws std::invalid_argument for bad options or data of another robot, and
/// std::runtime_error when no image can start the run.
Scenario MakeMrclamScenario(const MrclamRobotData& data, std::uint64_t seed,
                            const MrclamOptions& options = {}, MrclamCounts* counts = nullptr);

/// The Vicon pose at time t, interpolated linearly (heading unwrapped) between the samples around
/// t; `scored` is false when t lies outside the samples' span or the two samples are more than
/// kMrclamMaxTruthGap apart.
struct MrclamTruthAt {
  Pose pose = Pose::Zero();
  bool scored = false;
};
MrclamTruthAt InterpolateMrclamTruth(const std::vector<double>& times,
                                     const std::vector<Pose>& poses, double t);

}  // namespace phdslam::datasets
