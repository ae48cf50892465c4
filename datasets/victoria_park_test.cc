#include "datasets/victoria_park.h"

#include <gtest/gtest.h>
#include <matio.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "datasets/data_dir.h"
#include "datasets/test_data_sets.h"
#include "src/models/car_motion_model.h"

namespace phdslam::datasets {
namespace {

namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------------
// Hand-made data folders.

/// A fresh <tmp>/<name>/victoria-park/ folder, removed at the end of the test.
class TempDataDir {
 public:
  explicit TempDataDir(const std::string& name)
      : root_(fs::temp_directory_path() /
              ("phdslam_vp_" + name + "_" + std::to_string(::getpid()))) {
    fs::remove_all(root_);
    fs::create_directories(folder());
  }
  ~TempDataDir() {
    std::error_code ec;
    fs::remove_all(root_, ec);
  }
  TempDataDir(const TempDataDir&) = delete;
  TempDataDir& operator=(const TempDataDir&) = delete;

  [[nodiscard]] const fs::path& root() const { return root_; }
  [[nodiscard]] fs::path folder() const { return root_ / "victoria-park"; }

  void WriteText(const std::string& file, const std::string& text) const {
    std::ofstream(folder() / file) << text;
  }

  /// Writes a MAT 5 file of column vectors.
  void WriteMat(const std::string& file,
                const std::map<std::string, std::vector<double>>& vars) const {
    const fs::path path = folder() / file;
    mat_t* mat = Mat_CreateVer(path.c_str(), nullptr, MAT_FT_MAT5);
    ASSERT_NE(mat, nullptr);
    for (const auto& [name, values] : vars) {
      std::vector<double> copy = values;
      size_t dims[2] = {copy.size(), 1};
      matvar_t* var =
          Mat_VarCreate(name.c_str(), MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims, copy.data(), 0);
      ASSERT_NE(var, nullptr);
      ASSERT_EQ(Mat_VarWrite(mat, var, MAT_COMPRESSION_NONE), 0);
      Mat_VarFree(var);
    }
    Mat_Close(mat);
  }

 private:
  fs::path root_;
};

// Controls of the hand-made folder: 13 samples at 40 Hz from t = 0.2 s (ms = 21167),
// u_i = [1 + i, 0.01 i] (+ a small offset in the MAT-file only, to tell the two sources apart).
constexpr int kNumControls = 13;
double ControlTime(int i) { return (200.0 + 25.0 * i) / 1000.0; }
Control MatControl(int i) { return Control(1.0 + i + 1e-4, i / 100.0 + 1e-5); }
Control TextControl(int i) { return Control(1.0 + i, i / 100.0); }

void WriteInputsDat(const TempDataDir& dir) {
  std::string text;
  char line[128];
  for (int i = 0; i < kNumControls; ++i) {
    std::snprintf(line, sizeof(line), "  %.3f  %.3f  %.4f\n", ControlTime(i), TextControl(i)(0),
                  TextControl(i)(1));
    text += line;
  }
  dir.WriteText("inputs.dat", text);
}

void WriteDrMat(const TempDataDir& dir) {
  std::vector<double> time;
  std::vector<double> speed;
  std::vector<double> steering;
  for (int i = 0; i < kNumControls; ++i) {
    time.push_back(21167.0 + 25.0 * i);
    speed.push_back(MatControl(i)(0));
    steering.push_back(MatControl(i)(1));
  }
  dir.WriteMat("aa3_dr.mat", {{"time", time}, {"speed", speed}, {"steering", steering}});
}

void WriteGpsMat(const TempDataDir& dir) {
  dir.WriteMat("aa3_gpsx.mat", {{"timeGps", {20967.0, 21167.0, 21367.0}},
                                {"Lo_m", {1.0, 2.0, 3.0}},
                                {"La_m", {-1.0, -2.0, -3.0}}});
}

// Scans: 0.100 (before the first control), 0.330, 0.410 (only a negative-diameter detection:
// clutter only), 0.450 (equal to control time 10: taken at the next control), 0.550 (after the
// last control at 0.500: dropped).
constexpr double kHalfPi = std::numbers::pi / 2.0;
const char* const kMeasurements =
    "0.100  10.0  1.5707963267948966  0.30\n"
    "0.100  60.0  1.0  0.30\n"  // range > 50: dropped
    "\n"                        // blank lines are allowed
    "0.330  20.0  2.0  0.20\n"
    "0.330   5.0  0.0  0.20\n"   // bearing -90 deg: outside +-85 deg, dropped
    "0.330  50.0  3.0  0.00\n"   // range exactly 50, bearing 81.9 deg: kept
    "0.410  30.0  1.0  -0.10\n"  // negative diameter: dropped
    "0.450  12.0  1.2  0.10\n"
    "0.550  15.0  1.4  0.10\n";

void WriteSmallFolder(const TempDataDir& dir, bool with_dr_mat) {
  dir.WriteText("measurements.dat", kMeasurements);
  WriteInputsDat(dir);
  if (with_dr_mat) WriteDrMat(dir);
  WriteGpsMat(dir);
}

VictoriaParkOptions NoClutter() {
  VictoriaParkOptions o;
  o.clutter_rate = 0.0;
  return o;
}

// ---------------------------------------------------------------------------------------------
// Loading and merging on the hand-made folder.

TEST(VictoriaParkLoadTest, ReadsScansWithDetectorLimitsAndShiftedBearings) {
  const TempDataDir dir("scans");
  WriteSmallFolder(dir, /*with_dr_mat=*/true);
  const VictoriaParkData data = LoadVictoriaParkData(dir.root());

  ASSERT_EQ(data.scans.size(), 5u);
  EXPECT_EQ(data.scans[0].t, 0.100);
  ASSERT_EQ(data.scans[0].trees.size(), 1u);
  EXPECT_DOUBLE_EQ(data.scans[0].trees[0](0), 10.0);
  EXPECT_NEAR(data.scans[0].trees[0](1), 0.0, 1e-15);
  EXPECT_EQ(data.scans[0].diameters, std::vector<double>{0.30});

  ASSERT_EQ(data.scans[1].trees.size(), 2u);
  EXPECT_DOUBLE_EQ(data.scans[1].trees[0](1), 2.0 - kHalfPi);
  EXPECT_DOUBLE_EQ(data.scans[1].trees[1](0), 50.0);
  EXPECT_DOUBLE_EQ(data.scans[1].trees[1](1), 3.0 - kHalfPi);
  EXPECT_EQ(data.scans[1].diameters, (std::vector<double>{0.20, 0.00}));

  EXPECT_EQ(data.scans[2].t, 0.410);
  EXPECT_TRUE(data.scans[2].trees.empty());  // kept, clutter only
  EXPECT_EQ(data.scans[3].trees.size(), 1u);
  EXPECT_EQ(data.scans[4].t, 0.550);

  ASSERT_EQ(data.gps.size(), 3u);
  EXPECT_EQ(data.gps[1].t, 0.2);
  EXPECT_EQ(data.gps[2].position, Vec2(3.0, -3.0));
}

TEST(VictoriaParkLoadTest, PrefersDrMatAndFallsBackToInputsDat) {
  const TempDataDir dir("controls");
  WriteSmallFolder(dir, /*with_dr_mat=*/true);
  const VictoriaParkData from_mat = LoadVictoriaParkData(dir.root());
  ASSERT_EQ(from_mat.controls.size(), static_cast<size_t>(kNumControls));
  for (int i = 0; i < kNumControls; ++i) {
    EXPECT_EQ(from_mat.control_times[i], ControlTime(i)) << i;
    EXPECT_EQ(from_mat.controls[i], MatControl(i)) << i;
  }

  fs::remove(dir.folder() / "aa3_dr.mat");
  const VictoriaParkData from_text = LoadVictoriaParkData(dir.root());
  ASSERT_EQ(from_text.controls.size(), static_cast<size_t>(kNumControls));
  for (int i = 0; i < kNumControls; ++i) {
    EXPECT_EQ(from_text.control_times[i], ControlTime(i)) << i;
    EXPECT_EQ(from_text.controls[i], TextControl(i)) << i;
  }
}

TEST(VictoriaParkMergeTest, FirstScanBeforeFirstControlHasNoPropagation) {
  const TempDataDir dir("merge");
  WriteSmallFolder(dir, /*with_dr_mat=*/false);
  const Scenario s = MakeVictoriaParkScenario(LoadVictoriaParkData(dir.root()), 1, NoClutter());

  // The 0.550 s scan comes after the last control (0.500 s) and is dropped.
  ASSERT_EQ(s.steps.size(), 4u);
  const auto u = TextControl;

  // Step 1: the scan precedes the first control: no propagation, nothing held afterwards.
  EXPECT_EQ(s.steps[0].data.times, std::vector<double>{0.100});
  EXPECT_TRUE(s.steps[0].data.controls.empty());

  // Step 2: taken at the first control later than 0.330 (0.350 = sample 6); it starts at the
  // first control time with no held control.
  EXPECT_EQ(s.steps[1].data.times,
            (std::vector<double>{0.200, 0.225, 0.250, 0.275, 0.300, 0.325, 0.330}));
  EXPECT_EQ(s.steps[1].data.controls, (std::vector<Control>{u(0), u(1), u(2), u(3), u(4), u(5)}));

  // Step 3: starts at the previous scan with the control held there (sample 5), then samples
  // 6..8 up to the scan at 0.410 (< 0.425 = sample 9).
  EXPECT_EQ(s.steps[2].data.times, (std::vector<double>{0.330, 0.350, 0.375, 0.400, 0.410}));
  EXPECT_EQ(s.steps[2].data.controls, (std::vector<Control>{u(5), u(6), u(7), u(8)}));
  EXPECT_TRUE(s.steps[2].data.measurements.empty());  // clutter-only scan, no clutter drawn

  // Step 4: the scan at 0.450 equals sample 10's time, so (strict <) it is taken at sample 11:
  // the last sub-interval has zero length.
  EXPECT_EQ(s.steps[3].data.times, (std::vector<double>{0.410, 0.425, 0.450, 0.450}));
  EXPECT_EQ(s.steps[3].data.controls, (std::vector<Control>{u(8), u(9), u(10)}));

  for (const auto& step : s.steps) {
    EXPECT_EQ(step.data.controls.size() + 1, step.data.times.size());
    EXPECT_EQ(step.origin, std::vector<int>(step.data.measurements.size(), kUnknownOrigin));
  }
  EXPECT_EQ(s.steps[1].data.measurements.size(), 2u);
  EXPECT_EQ(s.StepTime(1), 0.330);
}

TEST(VictoriaParkMergeTest, FirstScanAfterFirstControlPropagatesFromFirstControl) {
  const TempDataDir dir("merge_late");
  dir.WriteText("measurements.dat",
                "0.260 10.0 1.6 0.3\n"
                "0.300 11.0 1.6 0.3\n"    // equal to control time 4: taken at sample 5
                "0.312 12.0 1.6 0.3\n");  // before control 5 like the previous scan
  WriteInputsDat(dir);
  WriteGpsMat(dir);
  const Scenario s = MakeVictoriaParkScenario(LoadVictoriaParkData(dir.root()), 1, NoClutter());
  const auto u = TextControl;
  ASSERT_EQ(s.steps.size(), 3u);
  EXPECT_EQ(s.steps[0].data.times, (std::vector<double>{0.200, 0.225, 0.250, 0.260}));
  EXPECT_EQ(s.steps[0].data.controls, (std::vector<Control>{u(0), u(1), u(2)}));
  EXPECT_EQ(s.steps[1].data.times, (std::vector<double>{0.260, 0.275, 0.300, 0.300}));
  EXPECT_EQ(s.steps[1].data.controls, (std::vector<Control>{u(2), u(3), u(4)}));
  EXPECT_EQ(s.steps[2].data.times, (std::vector<double>{0.300, 0.312}));
  EXPECT_EQ(s.steps[2].data.controls, (std::vector<Control>{u(4)}));
}

TEST(VictoriaParkMergeTest, MaxStepsKeepsTheSamePrefix) {
  const TempDataDir dir("max_steps");
  WriteSmallFolder(dir, /*with_dr_mat=*/false);
  const VictoriaParkData data = LoadVictoriaParkData(dir.root());
  VictoriaParkOptions limited;
  limited.clutter_rate = 20.0;
  limited.max_steps = 2;
  VictoriaParkOptions all = limited;
  all.max_steps = 0;
  const Scenario a = MakeVictoriaParkScenario(data, 3, limited);
  const Scenario b = MakeVictoriaParkScenario(data, 3, all);
  ASSERT_EQ(a.steps.size(), 2u);
  ASSERT_EQ(b.steps.size(), 4u);
  for (size_t k = 0; k < a.steps.size(); ++k) {
    EXPECT_EQ(a.steps[k].data.times, b.steps[k].data.times);
    EXPECT_EQ(a.steps[k].data.measurements, b.steps[k].data.measurements);
  }
}

TEST(VictoriaParkScenarioTest, FillsModelSensorAndTruth) {
  const TempDataDir dir("fields");
  WriteSmallFolder(dir, /*with_dr_mat=*/true);
  const VictoriaParkData data = LoadVictoriaParkData(dir.root());
  const Scenario s = MakeVictoriaParkScenario(data, 42);
  EXPECT_EQ(s.name, "victoria-park");
  EXPECT_EQ(s.seed, 42u);
  EXPECT_EQ(s.motion, MotionKind::kCar);
  EXPECT_DOUBLE_EQ(s.car.wheelbase_l, 2.83);
  EXPECT_DOUBLE_EQ(s.car.encoder_offset_h, 0.75);
  EXPECT_DOUBLE_EQ(s.car.laser_a, 3.78);
  EXPECT_DOUBLE_EQ(s.car.laser_b, 0.50);
  EXPECT_DOUBLE_EQ(s.initial_pose(0), -67.6493);
  EXPECT_DOUBLE_EQ(s.initial_pose(1), -41.7142);
  EXPECT_DOUBLE_EQ(s.initial_pose(2), 35.5 * std::numbers::pi / 180.0);
  EXPECT_DOUBLE_EQ(s.control_noise_cov(0, 0), 1.0);
  EXPECT_NEAR(s.control_noise_cov(1, 1), 4.8739e-3, 1e-7);
  EXPECT_EQ(s.control_noise_cov(0, 1), 0.0);
  EXPECT_DOUBLE_EQ(s.sensor.fov_range, 50.0);
  EXPECT_DOUBLE_EQ(s.sensor.fov_half_angle, 85.0 * std::numbers::pi / 180.0);
  EXPECT_DOUBLE_EQ(s.sensor.range_buffer, 5.0);
  EXPECT_DOUBLE_EQ(s.sensor.angle_buffer, 5.0 * std::numbers::pi / 180.0);
  EXPECT_EQ(s.sensor.profile, models::DetectionProfile::kLinearRange);
  EXPECT_DOUBLE_EQ(s.sensor.pd_max, 0.7);
  EXPECT_NEAR(std::log((1.0 - s.sensor.pd_nominal) * (1.0 - s.sensor.pd_nominal)), -2.4079, 1e-4);
  EXPECT_DOUBLE_EQ(s.sensor.noise_cov(0, 0), 1.0);
  EXPECT_NEAR(s.sensor.noise_cov(1, 1), 3.0462e-4, 1e-8);
  EXPECT_DOUBLE_EQ(s.sensor.clutter_rate, 5.0);
  // lambda_c of docs/algorithms/models.md section 3.6:
  EXPECT_NEAR(s.sensor.ClutterIntensity(), 1.3481e-3, 1e-7);
  EXPECT_TRUE(s.truth.poses.empty());
  EXPECT_TRUE(s.truth.landmarks.empty());
  ASSERT_EQ(s.truth.gps.size(), 3u);
  EXPECT_EQ(s.truth.gps[2].position, data.gps[2].position);
  EXPECT_NE(dynamic_cast<models::CarMotionModel*>(s.MakeMotionModel().get()), nullptr);
}

// ---------------------------------------------------------------------------------------------
// Errors.

/// Runs the loader on the folder and returns the error message (empty if nothing was thrown).
std::string LoadError(const TempDataDir& dir) {
  try {
    (void)LoadVictoriaParkData(dir.root());
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(VictoriaParkErrorTest, MalformedMeasurementLinesNameFileAndLine) {
  const TempDataDir dir("bad_meas");
  WriteSmallFolder(dir, /*with_dr_mat=*/true);
  dir.WriteText("measurements.dat", "0.1 10 1.5 0.3\n0.1 10 abc 0.3\n");
  std::string msg = LoadError(dir);
  EXPECT_NE(msg.find("measurements.dat:2:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("'abc' is not a number"), std::string::npos) << msg;

  dir.WriteText("measurements.dat", "0.1 10 1.5 0.3\n\n0.2 10 1.5\n");
  msg = LoadError(dir);
  EXPECT_NE(msg.find("measurements.dat:3:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("only 3 values"), std::string::npos) << msg;

  dir.WriteText("measurements.dat", "0.1 10 1.5 0.3 7\n");
  msg = LoadError(dir);
  EXPECT_NE(msg.find("measurements.dat:1:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("too many values"), std::string::npos) << msg;

  dir.WriteText("measurements.dat", "0.1 10 1.5 0.3\n0.1 10 nan 0.3\n");
  msg = LoadError(dir);
  EXPECT_NE(msg.find("measurements.dat:2:"), std::string::npos) << msg;

  dir.WriteText("measurements.dat", "0.2 10 1.5 0.3\n0.1 10 1.5 0.3\n");
  msg = LoadError(dir);
  EXPECT_NE(msg.find("measurements.dat:2:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("time order"), std::string::npos) << msg;
}

TEST(VictoriaParkErrorTest, NegativeRangeIsRefused) {
  const TempDataDir dir("negative_range");
  WriteSmallFolder(dir, /*with_dr_mat=*/true);
  dir.WriteText("measurements.dat", "0.1 10 1.5 0.3\n0.2 -4 1.5 0.3\n");
  const std::string msg = LoadError(dir);
  EXPECT_NE(msg.find("measurements.dat:2: range -4"), std::string::npos) << msg;
  EXPECT_NE(msg.find("negative"), std::string::npos) << msg;
}

TEST(VictoriaParkErrorTest, RawBytesAreEscapedAndLongTokensCapped) {
  const TempDataDir dir("raw_bytes");
  WriteSmallFolder(dir, /*with_dr_mat=*/true);
  dir.WriteText("measurements.dat", "0.1 10 \x1b]0;owned\x07\x1b[2J 0.3\n");
  std::string msg = LoadError(dir);
  EXPECT_EQ(msg.find('\x1b'), std::string::npos) << msg;
  EXPECT_EQ(msg.find('\x07'), std::string::npos) << msg;
  EXPECT_NE(msg.find("\\x1b]0;owned\\x07"), std::string::npos) << msg;

  dir.WriteText("measurements.dat", "0.1 10 " + std::string(1 << 20, 'z') + " 0.3\n");
  msg = LoadError(dir);
  EXPECT_NE(msg.find("measurements.dat:1:"), std::string::npos) << msg;
  EXPECT_LT(msg.size(), 1000U) << msg.substr(0, 200);
}

TEST(VictoriaParkErrorTest, MalformedInputsLineNamesFileAndLine) {
  const TempDataDir dir("bad_inputs");
  WriteSmallFolder(dir, /*with_dr_mat=*/false);
  dir.WriteText("inputs.dat", "0.200 1.0 0.0\n0.225 1.0 0.0\n0.250 1.0x 0.0\n");
  std::string msg = LoadError(dir);
  EXPECT_NE(msg.find("inputs.dat:3:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("'1.0x'"), std::string::npos) << msg;

  dir.WriteText("inputs.dat", "0.200 1.0 0.0\n0.200 1.0 0.0\n");
  msg = LoadError(dir);
  EXPECT_NE(msg.find("inputs.dat:2"), std::string::npos) << msg;
  EXPECT_NE(msg.find("strictly increasing"), std::string::npos) << msg;
}

TEST(VictoriaParkErrorTest, BadMatVariablesAndMissingFilesAreNamed) {
  const TempDataDir dir("bad_mat");
  WriteSmallFolder(dir, /*with_dr_mat=*/true);
  dir.WriteMat("aa3_gpsx.mat", {{"timeGps", {20967.0, 21167.0}}, {"Lo_m", {1.0, 2.0}}});
  std::string msg = LoadError(dir);
  EXPECT_NE(msg.find("aa3_gpsx.mat, variable 'La_m': missing"), std::string::npos) << msg;

  dir.WriteMat("aa3_gpsx.mat",
               {{"timeGps", {20967.0, 21167.0}}, {"Lo_m", {1.0, 2.0}}, {"La_m", {1.0}}});
  msg = LoadError(dir);
  EXPECT_NE(msg.find("variable 'La_m': has 1 elements but 'timeGps' has 2"), std::string::npos)
      << msg;

  dir.WriteMat("aa3_dr.mat",
               {{"time", {21167.0, 21142.0}}, {"speed", {1.0, 1.0}}, {"steering", {0.0, 0.0}}});
  msg = LoadError(dir);
  EXPECT_NE(msg.find("aa3_dr.mat, variable 'time', element 2"), std::string::npos) << msg;

  fs::remove(dir.folder() / "aa3_dr.mat");
  fs::remove(dir.folder() / "inputs.dat");
  msg = LoadError(dir);
  EXPECT_NE(msg.find("controls missing"), std::string::npos) << msg;

  fs::remove(dir.folder() / "measurements.dat");
  msg = LoadError(dir);
  EXPECT_NE(msg.find("measurements.dat' is missing"), std::string::npos) << msg;
}

TEST(VictoriaParkErrorTest, InvalidOptionsAreRejected) {
  VictoriaParkOptions o;
  EXPECT_NO_THROW(o.Validate());
  o.clutter_rate = -1.0;
  EXPECT_THROW(o.Validate(), std::invalid_argument);
  o = VictoriaParkOptions();
  o.detection_probability_nominal = 1.0;
  EXPECT_THROW(o.Validate(), std::invalid_argument);
  o = VictoriaParkOptions();
  o.measurement_noise_cov(1, 1) = -1.0;
  EXPECT_THROW(o.Validate(), std::invalid_argument);
  o = VictoriaParkOptions();
  o.max_steps = -2;
  EXPECT_THROW(MakeVictoriaParkScenario(VictoriaParkData{}, 1, o), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------
// The real data (skipped when the data folder cannot be found).

class VictoriaParkRealDataTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    found_ = testing::FindDataSetFiles("victoria-park");
    const auto& root = found_.dir;
    if (!root) return;
    const auto start = std::chrono::steady_clock::now();
    data_ = new VictoriaParkData(LoadVictoriaParkData(*root));
    const auto loaded = std::chrono::steady_clock::now();
    scenario_ = new Scenario(MakeVictoriaParkScenario(*data_, 1));
    const auto built = std::chrono::steady_clock::now();
    using Ms = std::chrono::duration<double, std::milli>;
    std::printf("[ info ] load %.1f ms, scenario build %.1f ms\n", Ms(loaded - start).count(),
                Ms(built - loaded).count());
  }
  static void TearDownTestSuite() {
    delete scenario_;
    delete data_;
    scenario_ = nullptr;
    data_ = nullptr;
  }
  void SetUp() override { PHDSLAM_SKIP_WITHOUT_DATA_SET(found_); }
  static testing::DataSetLookup found_;
  static const VictoriaParkData* data_;
  static const Scenario* scenario_;
};
testing::DataSetLookup VictoriaParkRealDataTest::found_;
const VictoriaParkData* VictoriaParkRealDataTest::data_ = nullptr;
const Scenario* VictoriaParkRealDataTest::scenario_ = nullptr;

// Expected counts below were computed independently (a short script over measurements.dat and
// inputs.dat applying docs/algorithms/models.md sections 6.2 and 6.4).
TEST_F(VictoriaParkRealDataTest, ScanAndDetectionCounts) {
  EXPECT_EQ(data_->scans.size(), 7230u);  // distinct detection times in the file
  size_t kept = 0;
  size_t empty = 0;
  for (const auto& scan : data_->scans) {
    kept += scan.trees.size();
    empty += scan.trees.empty() ? 1 : 0;
    for (const auto& z : scan.trees) {
      EXPECT_LE(z(0), 50.0);
      EXPECT_LE(std::abs(z(1)), 85.0 * std::numbers::pi / 180.0);
    }
  }
  // 52,974 rows minus 1,789 beyond 50 m and 524 outside +-85 deg; no negative diameters.
  EXPECT_EQ(kept, 50681u);
  EXPECT_EQ(empty, 2u);  // clutter-only scans
  EXPECT_EQ(data_->controls.size(), 61945u);
  EXPECT_EQ(data_->control_times.front(), 0.973);
  EXPECT_EQ(data_->control_times.back(), 1549.573);
  EXPECT_EQ(data_->gps.size(), 4466u);
  EXPECT_EQ(data_->gps.front().t, 0.0);
  EXPECT_NEAR(data_->gps.front().position(0), -67.649271, 1e-6);
  EXPECT_NEAR(data_->gps.front().position(1), -41.714218, 1e-6);
}

TEST_F(VictoriaParkRealDataTest, MatAndTextControlsAgree) {
  // A folder that links the real files except aa3_dr.mat, so the loader reads inputs.dat.
  const TempDataDir dir("real_text");
  const fs::path real = *found_.dir / "victoria-park";
  for (const char* f : {"measurements.dat", "inputs.dat", "aa3_gpsx.mat"}) {
    fs::create_symlink(fs::absolute(real / f), dir.folder() / f);
  }
  const VictoriaParkData text = LoadVictoriaParkData(dir.root());
  ASSERT_EQ(text.controls.size(), data_->controls.size());
  EXPECT_EQ(text.control_times, data_->control_times);  // same clock, bit for bit
  double max_speed_diff = 0.0;
  double max_steer_diff = 0.0;
  for (size_t i = 0; i < text.controls.size(); ++i) {
    max_speed_diff =
        std::max(max_speed_diff, std::abs(text.controls[i](0) - data_->controls[i](0)));
    max_steer_diff =
        std::max(max_steer_diff, std::abs(text.controls[i](1) - data_->controls[i](1)));
  }
  EXPECT_LE(max_speed_diff, 0.0005 + 1e-12);   // inputs.dat speeds have 3 decimals
  EXPECT_LE(max_steer_diff, 0.00005 + 1e-12);  // and steering 4
}

TEST_F(VictoriaParkRealDataTest, StepsAndSubIntervals) {
  const auto& steps = scenario_->steps;
  // The last scan (1549.241 s) precedes the last control (1549.573 s): every scan is a step.
  ASSERT_EQ(steps.size(), 7230u);
  EXPECT_EQ(steps[0].data.times, std::vector<double>{0.852});  // before the first control
  EXPECT_EQ(steps[1].data.times.front(), 0.973);               // starts at the first control
  EXPECT_EQ(steps[1].data.times.back(), 1.066);

  size_t sub_intervals = 0;
  size_t zero_length = 0;
  std::map<size_t, size_t> full_25ms_histogram;  // steps by number of full 25 ms sub-intervals
  for (size_t k = 0; k < steps.size(); ++k) {
    const auto& t = steps[k].data.times;
    ASSERT_EQ(steps[k].data.controls.size() + 1, t.size());
    EXPECT_EQ(t.back(), data_->scans[k].t);
    if (k > 1) {
      EXPECT_EQ(t.front(), steps[k - 1].data.times.back());
    }
    sub_intervals += t.size() - 1;
    size_t full = 0;
    for (size_t i = 0; i + 1 < t.size(); ++i) {
      const double dt = t[i + 1] - t[i];
      ASSERT_GE(dt, 0.0);
      zero_length += dt == 0.0 ? 1 : 0;
      full += std::abs(dt - 0.025) < 1e-9 ? 1 : 0;
    }
    ++full_25ms_histogram[full];
  }
  EXPECT_EQ(sub_intervals, 69159u);
  EXPECT_EQ(zero_length, 285u);  // scans stamped exactly at a control time
  // The typical step: 8 full 25 ms sub-intervals (plus the partial ones at both ends).
  EXPECT_EQ(full_25ms_histogram[8], 4217u);
  EXPECT_EQ(full_25ms_histogram[7], 2996u);
  std::printf("[ info ] %zu steps, %zu sub-intervals (%.2f per step)\n", steps.size(),
              sub_intervals, static_cast<double>(sub_intervals) / steps.size());
}

TEST_F(VictoriaParkRealDataTest, ClutterIsSeededAndDrawnInsideTheFov) {
  const Scenario same = MakeVictoriaParkScenario(*data_, 1);
  const Scenario other = MakeVictoriaParkScenario(*data_, 2);
  size_t clutter = 0;
  size_t real = 0;
  size_t differing_steps = 0;
  for (size_t k = 0; k < scenario_->steps.size(); ++k) {
    const ScenarioStep& step = scenario_->steps[k];
    EXPECT_EQ(step.data.measurements, same.steps[k].data.measurements) << k;
    const size_t n_real = data_->scans[k].trees.size();
    ASSERT_GE(step.data.measurements.size(), n_real);
    for (size_t i = 0; i < step.data.measurements.size(); ++i) {
      const Measurement& z = step.data.measurements[i];
      if (i < n_real) {
        EXPECT_EQ(step.origin[i], kUnknownOrigin);
        EXPECT_EQ(z, data_->scans[k].trees[i]);  // real detections first, unchanged
        ++real;
      } else {
        EXPECT_EQ(step.origin[i], kClutter);
        EXPECT_GE(z(0), 0.0);
        EXPECT_LT(z(0), 50.0);
        EXPECT_LE(std::abs(z(1)), 85.0 * std::numbers::pi / 180.0);
        ++clutter;
      }
    }
    // The real detections are the same for every seed; only the clutter differs.
    const auto& o = other.steps[k].data.measurements;
    ASSERT_GE(o.size(), n_real);
    if (o != step.data.measurements) ++differing_steps;
  }
  EXPECT_EQ(real, 50681u);
  // Poisson(5) per scan: mean within 6 standard errors (sqrt(5 / 7230) = 0.026).
  const double mean_clutter = static_cast<double>(clutter) / scenario_->steps.size();
  EXPECT_NEAR(mean_clutter, 5.0, 0.16);
  EXPECT_GT(differing_steps, scenario_->steps.size() * 9 / 10);
  std::printf("[ info ] mean measurements per step %.3f (real %.3f + clutter %.3f)\n",
              static_cast<double>(real + clutter) / scenario_->steps.size(),
              static_cast<double>(real) / scenario_->steps.size(), mean_clutter);
}

TEST_F(VictoriaParkRealDataTest, DeadReckoningEndsNearTheLastGpsFix) {
  const models::CarMotionModel model(scenario_->car);
  Pose x = scenario_->initial_pose;
  for (const auto& step : scenario_->steps) {
    const auto& t = step.data.times;
    for (size_t i = 0; i + 1 < t.size(); ++i)
      x = model.Predict(x, step.data.controls[i], t[i + 1] - t[i]);
  }
  const GpsFix& last = data_->gps.back();
  const double error = (x.head<2>() - last.position).norm();
  std::printf(
      "[ info ] dead reckoning final pose (%.2f, %.2f, %.1f deg) at t = %.3f s; last GPS "
      "fix (%.2f, %.2f) at t = %.3f s; distance %.2f m\n",
      x(0), x(1), x(2) * 180.0 / std::numbers::pi, scenario_->steps.back().data.times.back(),
      last.position(0), last.position(1), last.t, error);
  EXPECT_TRUE(x.allFinite());
  EXPECT_TRUE(std::isfinite(error));
}

}  // namespace
}  // namespace phdslam::datasets
