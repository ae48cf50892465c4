#include "datasets/mrclam.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <stdexcept>
#include <string>

#include "datasets/data_dir.h"
#include "datasets/scenario_check.h"
#include "datasets/test_data_sets.h"
#include "datasets/test_temp_dir.h"

namespace phdslam::datasets {
namespace {

namespace fs = std::filesystem;

constexpr char kHeader[] =
    "# UTIAS Multi-Robot Cooperative Localization and Mapping Dataset\n"
    "# produced by hand for a test\n"
    "# Data Format:\n"
    "# columns\n";

// A small MRCLAM_Dataset3 folder for robot 2: robots 1-5 have barcodes 5, 14, 41, 32, 23;
// landmarks 6 and 7 (barcodes 61, 90) at (2, 0) and (0, 3). Robot 2 drives along x at 1 m/s
// from t = 100 s; Vicon every 0.1 s over [99, 110] except the gap (104, 105]; images at 101,
// 102, 104.5 and 106 s; the last command is at 107 s (the image at 108 s comes after it).
class Fixture {
 public:
  Fixture() : root_(testing::FreshTestDir()) {
    fs::create_directories(folder());
    Write("Barcodes.dat",
          "  1 \t   5 \n  2 \t  14 \n  3 \t  41 \n  4 \t  32 \n  5 \t  23 \n  6 \t  61 \n"
          "  7 \t  90 \n");
    Write("Landmark_Groundtruth.dat",
          "  6 \t 2.0 \t 0.0 \t 0.0001 \t 0.0001 \n  7 \t 0.0 \t 3.0 \t 0.0001 \t 0.0001 \n");
    std::string truth;
    for (int i = 0; i <= 110; ++i) {
      const double t = 99.0 + 0.1 * i;
      if (t > 104.05 && t < 104.95) continue;  // a 1 s gap in the Vicon data
      const double x = std::max(0.0, t - 100.0);
      truth += std::to_string(t) + " \t " + std::to_string(x) + " \t 0.0 \t 0.0 \n";
    }
    Write("Robot2_Groundtruth.dat", truth);
    std::string odometry;
    for (int i = 0; i <= 70; ++i) {
      odometry += std::to_string(100.0 + 0.1 * i) + " \t 1.0 \t 0.0 \n";
    }
    Write("Robot2_Odometry.dat", odometry);
    Write("Robot2_Measurement.dat",
          "101.0 \t 61 \t 1.0 \t 0.0 \n"     // landmark 6, 1 m ahead
          "101.0 \t 5 \t 4.0 \t 0.1 \n"      // robot 1: clutter
          "102.0 \t 90 \t 3.6 \t 2.16 \n"    // landmark 7
          "102.0 \t 50 \t 2.0 \t -0.3 \n"    // a barcode of no subject: clutter
          "104.5 \t 61 \t 2.5 \t 3.14 \n"    // inside the truth gap
          "106.0 \t 23 \t 3.0 \t 0.2 \n"     // robot 5: clutter
          "108.0 \t 61 \t 6.0 \t 3.14 \n");  // after the last command
  }

  [[nodiscard]] const fs::path& root() const { return root_; }
  [[nodiscard]] fs::path folder() const { return root_ / "utias-mrclam" / "MRCLAM_Dataset3"; }
  void Write(const std::string& file, const std::string& rows) const {
    std::ofstream(folder() / file) << kHeader << rows;
  }
  [[nodiscard]] MrclamRobotData Load() const { return LoadMrclamRobot(root_, 3, 2); }

 private:
  fs::path root_;
};

MrclamOptions RobotTwoOfDatasetThree() {
  MrclamOptions o;
  o.dataset = 3;
  o.robot = 2;
  return o;
}

std::string LoadError(const Fixture& f) {
  try {
    (void)f.Load();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(MrclamLoader, MapsBarcodesToSubjectsAndLandmarks) {
  const Fixture f;
  const MrclamRobotData data = f.Load();
  EXPECT_EQ(data.barcode_subject.size(), 7u);
  EXPECT_EQ(data.barcode_subject.at(14), 2);
  EXPECT_EQ(data.barcode_subject.at(90), 7);
  ASSERT_EQ(data.landmarks.size(), 2u);
  EXPECT_EQ(data.landmark_subjects, (std::vector<int>{6, 7}));
  EXPECT_EQ(data.landmarks[1], Landmark(0.0, 3.0));
  EXPECT_EQ(data.detections.size(), 7u);
  EXPECT_EQ(data.detections[2].barcode, 90);
}

TEST(MrclamScenario, OneStepPerImageWithOriginsFromTheBarcodes) {
  const Fixture f;
  MrclamCounts counts;
  const Scenario s = MakeMrclamScenario(f.Load(), 1, RobotTwoOfDatasetThree(), &counts);
  CheckScenario(s, "fixture");
  ASSERT_EQ(s.steps.size(), 4u);  // 101, 102, 104.5, 106; 108 comes after the last command
  EXPECT_EQ(s.steps[0].origin, (std::vector<int>{0, kClutter}));  // landmark 6, robot 1
  EXPECT_EQ(s.steps[1].origin, (std::vector<int>{1, kClutter}));  // landmark 7, barcode 50
  EXPECT_EQ(s.steps[2].origin, (std::vector<int>{0}));
  EXPECT_EQ(s.steps[3].origin, (std::vector<int>{kClutter}));  // robot 5
  EXPECT_EQ(counts.steps, 4u);
  EXPECT_EQ(counts.landmark_detections, 3u);
  EXPECT_EQ(counts.other_robot_detections, 2u);
  EXPECT_EQ(counts.unknown_barcode_detections, 1u);
  EXPECT_EQ(counts.images_skipped, 1u);
  EXPECT_FALSE(counts.non_landmarks_dropped);
  EXPECT_EQ(s.truth.landmarks.size(), 2u);
  EXPECT_EQ(s.steps[0].data.measurements[1], Measurement(4.0, 0.1));
}

TEST(MrclamScenario, DropsOtherRobotsAndUnknownBarcodesOnRequest) {
  const Fixture f;
  MrclamOptions o = RobotTwoOfDatasetThree();
  o.drop_non_landmarks = true;
  MrclamCounts counts;
  const Scenario s = MakeMrclamScenario(f.Load(), 1, o, &counts);
  ASSERT_EQ(s.steps.size(), 4u);  // the step of robot 5 alone stays, with an empty scan
  EXPECT_EQ(s.steps[0].origin, (std::vector<int>{0}));
  EXPECT_EQ(s.steps[1].origin, (std::vector<int>{1}));
  EXPECT_TRUE(s.steps[3].data.measurements.empty());
  EXPECT_EQ(counts.other_robot_detections, 2u);  // still counted
  EXPECT_EQ(counts.unknown_barcode_detections, 1u);
  EXPECT_TRUE(counts.non_landmarks_dropped);
}

TEST(MrclamScenario, IntegratesTheCommandsBetweenImages) {
  const Fixture f;
  const Scenario s = MakeMrclamScenario(f.Load(), 1, RobotTwoOfDatasetThree());
  // First step: one time stamp, initial pose = Vicon at 101 s.
  EXPECT_EQ(s.steps[0].data.times, (std::vector<double>{101.0}));
  EXPECT_NEAR(s.initial_pose(0), 1.0, 1e-9);
  // Second step: [101, the 9 commands strictly between, 102], controls 1 m/s.
  const StepData& d = s.steps[1].data;
  ASSERT_EQ(d.times.size(), 11u);
  EXPECT_EQ(d.controls.size(), 10u);
  EXPECT_DOUBLE_EQ(d.times.front(), 101.0);
  EXPECT_DOUBLE_EQ(d.times.back(), 102.0);
  // The unicycle model over the step moves the pose by 1 m, the Vicon displacement.
  const auto motion = s.MakeMotionModel();
  Pose x = s.initial_pose;
  for (std::size_t i = 0; i < d.controls.size(); ++i) {
    x = motion->Predict(x, d.controls[i], d.times[i + 1] - d.times[i]);
  }
  EXPECT_NEAR(x(0), s.truth.poses[1](0), 1e-9);
  EXPECT_NEAR(x(1), 0.0, 1e-12);
}

TEST(MrclamScenario, LeavesStepsInTruthGapsUnscored) {
  const Fixture f;
  MrclamCounts counts;
  const Scenario s = MakeMrclamScenario(f.Load(), 1, RobotTwoOfDatasetThree(), &counts);
  EXPECT_EQ(s.truth.pose_scored, (std::vector<bool>{true, true, false, true}));
  EXPECT_EQ(counts.unscored_steps, 1u);
  EXPECT_FALSE(s.truth.PoseScored(2));
  EXPECT_NEAR(s.truth.poses[2](0), 4.5, 1e-6);  // the stand-in, interpolated across the gap
  EXPECT_NEAR(s.truth.poses[3](0), 6.0, 1e-6);
}

TEST(MrclamTruth, InterpolatesWithinShortGapsOnly) {
  const std::vector<double> times = {0.0, 0.4, 1.4};
  const std::vector<Pose> poses = {Pose(0, 0, 0), Pose(4, 0, 1), Pose(14, 0, 2)};
  const MrclamTruthAt a = InterpolateMrclamTruth(times, poses, 0.1);
  EXPECT_TRUE(a.scored);
  EXPECT_NEAR(a.pose(0), 1.0, 1e-12);
  EXPECT_NEAR(a.pose(2), 0.25, 1e-12);
  EXPECT_FALSE(InterpolateMrclamTruth(times, poses, 0.9).scored);  // 1 s gap
  EXPECT_TRUE(InterpolateMrclamTruth(times, poses, 1.4).scored);   // on a sample
  EXPECT_FALSE(InterpolateMrclamTruth(times, poses, -0.1).scored);
  EXPECT_FALSE(InterpolateMrclamTruth(times, poses, 1.5).scored);
}

TEST(MrclamLoader, SortsOutOfOrderRowsAndResolvesRepeatedTimeStamps) {
  Fixture f;
  f.Write("Robot2_Odometry.dat",
          "100.0 \t 1.0 \t 0.0 \n100.5 \t 0.0 \t 0.0 \n100.5 \t 2.0 \t 0.0 \n"
          "100.3 \t 1.5 \t 0.0 \n107.0 \t 0.0 \t 0.0 \n");
  f.Write("Robot2_Measurement.dat",
          "101.0 \t 61 \t 1.0 \t 0.0 \n102.0 \t 90 \t 3.6 \t 2.16 \n101.0 \t 5 \t 4.0 \t 0.1 \n");
  f.Write("Robot2_Groundtruth.dat",
          "99.0 \t 0 \t 0 \t 3.1 \n99.2 \t 0 \t 0 \t -3.1 \n99.1 \t 0 \t 0 \t 3.0 \n"
          "99.2 \t 9 \t 9 \t 0 \n101.0 \t 1 \t 0 \t -3.0 \n102.0 \t 2 \t 0 \t -3.0 \n");
  const MrclamRobotData data = f.Load();
  EXPECT_EQ(data.odometry_times, (std::vector<double>{100.0, 100.3, 100.5, 107.0}));
  EXPECT_EQ(data.odometry[2], Control(2.0, 0.0));  // the last row of a repeated stamp
  EXPECT_EQ(data.odometry_out_of_order, 1u);
  EXPECT_EQ(data.odometry_repeated_times, 1u);
  EXPECT_EQ(data.detections_out_of_order, 1u);
  // The row of 101.0 out of order joins its image.
  const Scenario s = MakeMrclamScenario(data, 1, RobotTwoOfDatasetThree());
  ASSERT_EQ(s.steps.size(), 2u);
  EXPECT_EQ(s.steps[0].origin, (std::vector<int>{0, kClutter}));
  // Vicon: sorted, the first of a repeated stamp kept, heading unwrapped (3.0, 3.1, 2pi - 3.1).
  EXPECT_EQ(data.truth_times, (std::vector<double>{99.0, 99.1, 99.2, 101.0, 102.0}));
  EXPECT_EQ(data.truth_repeated_times, 1u);
  EXPECT_EQ(data.truth_out_of_order, 1u);
  EXPECT_NEAR(data.truth_poses[2](2), 2.0 * std::numbers::pi - 3.1, 1e-12);
  EXPECT_NEAR(data.truth_poses[3](2), 2.0 * std::numbers::pi - 3.0, 1e-12);
  // The step at 102 s integrates 1.5 m/s (held from 100.3) then 2 m/s from 100.5 s on.
  const StepData& d = s.steps[1].data;
  EXPECT_EQ(d.times, (std::vector<double>{101.0, 102.0}));
  EXPECT_EQ(d.controls, (std::vector<Control>{Control(2.0, 0.0)}));
}

TEST(MrclamLoader, NamesTheFileAndLineOfAMalformedLine) {
  Fixture f;
  f.Write("Robot2_Odometry.dat", "100.0 \t 1.0 \t 0.0 \n100.1 \t 1.0 \n");
  std::string error = LoadError(f);
  EXPECT_NE(error.find("Robot2_Odometry.dat:6: 2 values"), std::string::npos) << error;
  f.Write("Robot2_Odometry.dat", "100.0 \t 1.0 \t 0.0 \n107.0 \t 1.0 \t 0.0 \n");
  f.Write("Robot2_Measurement.dat", "101.0 \t 61 \t 1.0 \t 0.0 \n101.0 \t 6x1 \t 1.0 \t 0.0 \n");
  error = LoadError(f);
  EXPECT_NE(error.find("Robot2_Measurement.dat:6: '6x1' is not a number"), std::string::npos)
      << error;
  f.Write("Robot2_Measurement.dat", "101.0 \t 61.5 \t 1.0 \t 0.0 \n");
  error = LoadError(f);
  EXPECT_NE(error.find("Robot2_Measurement.dat:5: barcode 61.5 is not a positive integer"),
            std::string::npos)
      << error;
  f.Write("Robot2_Measurement.dat", "101.0 \t 61 \t -1.0 \t 0.0 \n");
  error = LoadError(f);
  EXPECT_NE(error.find("Robot2_Measurement.dat:5: range -1 m is not positive"), std::string::npos)
      << error;
  f.Write("Robot2_Measurement.dat", "101.0 \t 61 \t nan \t 0.0 \n");
  error = LoadError(f);
  EXPECT_NE(error.find("Robot2_Measurement.dat:5: value 3 is not finite"), std::string::npos)
      << error;
  f.Write("Barcodes.dat", "  1 \t   5 \n  2 \t   5 \n");
  error = LoadError(f);
  EXPECT_NE(error.find("Barcodes.dat:6: barcode 5 already given to subject 1"), std::string::npos)
      << error;
}

TEST(MrclamLoader, NamesATruncatedOrMissingFile) {
  Fixture f;
  f.Write("Landmark_Groundtruth.dat", "  6 \t 2.0 \t 0.0 \t 0.0001");  // cut mid-line
  std::string error = LoadError(f);
  EXPECT_NE(error.find("Landmark_Groundtruth.dat:5: 4 values"), std::string::npos) << error;
  f.Write("Landmark_Groundtruth.dat", "");
  error = LoadError(f);
  EXPECT_NE(error.find("Landmark_Groundtruth.dat' holds no data lines"), std::string::npos)
      << error;
  f.Write("Landmark_Groundtruth.dat", "  6 \t 2.0 \t 0.0 \t 0.0001 \t 0.0001 \n");
  fs::remove(f.folder() / "Robot2_Odometry.dat");
  error = LoadError(f);
  EXPECT_NE(error.find("Robot2_Odometry.dat' is missing"), std::string::npos) << error;
  EXPECT_THROW((void)LoadMrclamRobot(f.root(), 4, 2), std::runtime_error);  // no such folder
  EXPECT_THROW((void)LoadMrclamRobot(f.root(), 3, 6), std::invalid_argument);
}

TEST(MrclamScenario, RejectsBadOptionsAndDataOfAnotherRobot) {
  const Fixture f;
  const MrclamRobotData data = f.Load();
  MrclamOptions o = RobotTwoOfDatasetThree();
  o.robot = 3;
  EXPECT_THROW((void)MakeMrclamScenario(data, 1, o), std::invalid_argument);
  o = RobotTwoOfDatasetThree();
  o.detection_probability = 1.5;
  EXPECT_THROW((void)MakeMrclamScenario(data, 1, o), std::invalid_argument);
  o.detection_probability = 0.0;
  EXPECT_THROW((void)MakeMrclamScenario(data, 1, o), std::invalid_argument);
  // pD = 1 is in the range `phdslam list` and --pd give every scenario, (0, 1].
  o.detection_probability = 1.0;
  EXPECT_EQ(MakeMrclamScenario(data, 1, o).sensor.pd_nominal, 1.0);
  o = RobotTwoOfDatasetThree();
  o.measurement_noise_cov(0, 1) = 5.0;
  EXPECT_THROW((void)MakeMrclamScenario(data, 1, o), std::invalid_argument);
}

// The real sub-dataset 6 when the data folder holds it (facts of its README).
TEST(MrclamDataset6, RobotFourHasItsTruthGapsAndCounts) {
  const testing::DataSetLookup found = testing::FindDataSetFiles("mrclam");
  PHDSLAM_SKIP_WITHOUT_DATA_SET(found);
  const fs::path data_dir = *found.dir;
  MrclamOptions o;
  o.robot = 4;
  MrclamCounts counts;
  const Scenario s = MakeMrclamScenario(LoadMrclamRobot(data_dir, 6, 4), 1, o, &counts);
  CheckScenario(s, "mrclam robot 4");
  EXPECT_EQ(s.truth.landmarks.size(), 15u);
  EXPECT_EQ(counts.steps, 1459u);  // every image: none before the commands or after them
  EXPECT_EQ(counts.images_skipped, 0u);
  EXPECT_EQ(counts.unscored_steps, 2u);  // inside the 2.0 s and 0.56 s Vicon gaps
  EXPECT_EQ(counts.landmark_detections + counts.other_robot_detections +
                counts.unknown_barcode_detections,
            2399u);                                  // every row of Robot4_Measurement.dat
  EXPECT_EQ(counts.unknown_barcode_detections, 3u);  // barcode 50
  // Robot 1's Vicon data ends before its images do: the later steps are not scored.
  MrclamOptions o1;
  MrclamCounts counts1;
  (void)MakeMrclamScenario(LoadMrclamRobot(data_dir, 6, 1), 1, o1, &counts1);
  EXPECT_EQ(counts1.steps, 1234u);
  EXPECT_EQ(counts1.unscored_steps, 0u);
}

}  // namespace
}  // namespace phdslam::datasets
