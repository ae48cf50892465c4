#include "validation/runner/interchange/scenario_export.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "datasets/sha256.h"
#include "datasets/test_data_sets.h"
#include "datasets/test_file_bytes.h"
#include "datasets/test_temp_dir.h"
#include "validation/runner/io/results_io.h"
#include "validation/runner/registry/scenario_registry.h"
#include "validation/runner/results/results_config.h"

namespace phdslam::validation {
namespace {

using datasets::testing::FreshTestDir;

ScenarioSource PaperSynthetic(int steps) {
  ScenarioOptions options;
  options.steps = steps;
  return MakeScenarioSource("paper-synthetic", options);
}

void WriteOne(const std::filesystem::path& out, const ScenarioSource& source, std::uint64_t seed) {
  ExportDescription d;
  d.scenario = source.name;
  d.options = source.options;
  d.seeds = {seed};
  WriteExport(out, d, {source.make(seed)});
}

// The first python3 that imports numpy: $PHDSLAM_PYTHON, /usr/bin/python3, python3 on PATH.
std::string NumpyPython() {
  std::vector<std::string> candidates;
  if (const char* env = std::getenv("PHDSLAM_PYTHON")) candidates.emplace_back(env);
  candidates.emplace_back("/usr/bin/python3");
  candidates.emplace_back("python3");
  for (const std::string& c : candidates) {
    if (std::system((c + " -c 'import numpy' >/dev/null 2>&1").c_str()) == 0) return c;
  }
  return "";
}

std::string CommandOutput(const std::string& command) {
  std::string out;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return out;
  char buffer[1 << 16];
  std::size_t n = 0;
  while ((n = std::fread(buffer, 1, sizeof(buffer), pipe)) > 0) out.append(buffer, n);
  ::pclose(pipe);
  return out;
}

TEST(ScenarioExport, WritesEveryFileWithItsChecksum) {
  const std::filesystem::path out = FreshTestDir();
  const ScenarioSource source = PaperSynthetic(50);
  WriteOne(out, source, 3);
  const std::map<std::string, std::string> sums = ReadExportChecksums(out);
  for (const char* file : {"seed-3/steps.csv", "seed-3/controls.csv", "seed-3/measurements.csv",
                           "seed-3/models.json", "truth/seed-3/trajectory.tum",
                           "truth/seed-3/map.csv", "truth/seed-3/origins.csv", "export.json"}) {
    ASSERT_TRUE(sums.count(file)) << file;
    EXPECT_EQ(sums.at(file), datasets::FileSha256Hex(out / file)) << file;
  }
  EXPECT_EQ(sums.size(), 8U);
  const nlohmann::json manifest = ReadJsonObject(out / kExportManifestFile);
  EXPECT_EQ(manifest.at("format_version"), kExportFormatVersion);
  EXPECT_EQ(manifest.at("steps").at("3"), 50);
  EXPECT_EQ(manifest.at("options"), source.options);
  const CsvTable steps = ReadCsvFile(out / "seed-3/steps.csv");
  EXPECT_EQ(steps.rows.size(), 50U);
}

TEST(ScenarioExport, RealDataHasGpsAndUnknownOriginsAndSeveralControlsPerStep) {
  PHDSLAM_SKIP_WITHOUT_DATA_SET(datasets::testing::FindDataSetFiles("victoria-park"));
  ScenarioOptions options;
  options.steps = 30;
  const datasets::Scenario s = MakeScenarioSource("victoria-park", options).make(1);
  const std::map<std::string, std::string> files = ExportFiles(s);
  EXPECT_FALSE(files.count("truth/seed-1/trajectory.tum"));
  EXPECT_FALSE(files.count("truth/seed-1/map.csv"));
  ASSERT_TRUE(files.count("truth/seed-1/gps.csv"));
  EXPECT_EQ(files.at("truth/seed-1/gps.csv").rfind("t,x,y\n", 0), 0U);
  ASSERT_TRUE(files.count("truth/seed-1/origins.csv"));
  EXPECT_NE(files.at("truth/seed-1/origins.csv").find(",-2\n"), std::string::npos);
  std::size_t controls = 0;
  for (const datasets::ScenarioStep& step : s.steps) controls += step.data.controls.size();
  EXPECT_GT(controls, s.steps.size());  // 40 Hz odometry: several controls per filter step
  const CsvTable table = ParseCsv(files.at("seed-1/controls.csv"), "controls.csv");
  EXPECT_EQ(table.rows.size(), controls);
  EXPECT_EQ(ModelsJson(s).at("motion").at("kind"), "car");
  EXPECT_EQ(ModelsJson(s).at("sensor").at("detection_profile"), "linear_range");
}

TEST(ScenarioExport, ModelsHoldTheScenariosNoiseAndFieldOfView) {
  const datasets::Scenario s = PaperSynthetic(5).make(1);
  const nlohmann::json m = ModelsJson(s);
  EXPECT_EQ(m.at("motion").at("kind"), "velocity");
  EXPECT_EQ(m.at("motion").at("control_noise_cov")[1][1].get<double>(), s.control_noise_cov(1, 1));
  EXPECT_EQ(m.at("sensor").at("noise_cov")[0][0].get<double>(), s.sensor.noise_cov(0, 0));
  EXPECT_EQ(m.at("sensor").at("fov_range").get<double>(), s.sensor.fov_range);
  EXPECT_EQ(m.at("sensor").at("fov_half_angle").get<double>(), s.sensor.fov_half_angle);
  EXPECT_EQ(m.at("sensor").at("clutter_intensity").get<double>(), s.sensor.ClutterIntensity());
  EXPECT_EQ(m.at("initial_pose")[2].get<double>(), s.initial_pose(2));
}

TEST(ScenarioExport, MalformedChecksumLineNamesFileAndLine) {
  const std::filesystem::path out = FreshTestDir();
  std::ofstream(out / kExportChecksumFile) << std::string(64, 'a') << "  x.csv\nnot a checksum\n";
  try {
    ReadExportChecksums(out);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("SHA256SUMS:2"), std::string::npos) << e.what();
  }
}

// Must show: paper-synthetic seed 1, read back by the Python reader, gives exactly the
// measurements (and controls and time stamps) the runner gives the estimators.
TEST(ScenarioExport, PythonReaderReadsBackExactlyWhatTheRunnerUses) {
  const std::string python = NumpyPython();
  if (python.empty()) GTEST_SKIP() << "no python3 with numpy";
  const std::filesystem::path out = FreshTestDir();
  const ScenarioSource source = PaperSynthetic(0);  // all 4000 steps
  WriteOne(out, source, 1);
  const datasets::Scenario scenario = source.make(1);
  const std::string text =
      CommandOutput(python + " " PHDSLAM_SOURCE_DIR "/examples/python/phdslam_reader.py " +
                    out.string() + " --seed 1 --json");
  const nlohmann::json read = nlohmann::json::parse(text, nullptr, false);
  ASSERT_FALSE(read.is_discarded()) << text.substr(0, 500);
  ASSERT_EQ(read.at("times").size(), scenario.steps.size());
  std::size_t measurements = 0;
  for (std::size_t k = 0; k < scenario.steps.size(); ++k) {
    const StepData& d = scenario.steps[k].data;
    ASSERT_EQ(read["times"][k].get<double>(), scenario.StepTime(k)) << k;
    const nlohmann::json& z = read["measurements"][k];
    ASSERT_EQ(z.size(), d.measurements.size()) << "step " << k;
    for (std::size_t i = 0; i < z.size(); ++i) {
      ASSERT_EQ(z[i][0].get<double>(), d.measurements[i](0)) << "step " << k << " z " << i;
      ASSERT_EQ(z[i][1].get<double>(), d.measurements[i](1)) << "step " << k << " z " << i;
    }
    measurements += z.size();
    const nlohmann::json& u = read["controls"][k];
    ASSERT_EQ(u.size(), d.controls.size()) << "step " << k;
    for (std::size_t i = 0; i < u.size(); ++i) {
      ASSERT_EQ(u[i][0].get<double>(), d.times[i]);
      ASSERT_EQ(u[i][1].get<double>(), d.times[i + 1]);
      ASSERT_EQ(u[i][2].get<double>(), d.controls[i](0));
      ASSERT_EQ(u[i][3].get<double>(), d.controls[i](1));
    }
  }
  EXPECT_EQ(scenario.steps.size(), 4000U);
  EXPECT_GT(measurements, 40000U);
}

TEST(ExportManifest, ReadsBackTheExperimentItWasWrittenFrom) {
  const std::filesystem::path out = FreshTestDir();
  Experiment x;
  x.scenario = "paper-synthetic";
  x.steps = 30;
  x.pd = 0.9;
  x.scenario_settings = {{"landmarks", 40}};
  x.seeds = {4, 2};
  const ScenarioSource source = PaperSynthetic(x.steps);
  ExportDescription d;
  d.scenario = source.name;
  d.options = source.options;
  d.request = ExportRequest(x);
  d.seeds = x.seeds;
  WriteExport(out, d, {source.make(4), source.make(2)});
  EXPECT_TRUE(ReadJsonObject(out / kExportManifestFile).at("request").at("clutter_rate").is_null());

  const Experiment back = ReadExportManifest(out);
  EXPECT_EQ(back.scenario, "paper-synthetic");
  EXPECT_EQ(back.steps, 30);
  EXPECT_EQ(back.pd, 0.9);
  EXPECT_FALSE(back.clutter_rate.has_value());
  EXPECT_EQ(back.scenario_settings, x.scenario_settings);
  EXPECT_EQ(back.seeds, (std::vector<std::uint64_t>{4, 2}));
}

TEST(ExportManifest, RefusesAnotherFormatVersionAndMalformedContentNamingTheFile) {
  const std::filesystem::path out = FreshTestDir();
  WriteOne(out, PaperSynthetic(10), 1);
  const std::filesystem::path path = out / kExportManifestFile;
  nlohmann::json manifest = ReadJsonObject(path);
  manifest["format_version"] = kExportFormatVersion + 1;
  WriteFileAtomically(path, JsonFileText(manifest));
  EXPECT_EQ(datasets::testing::ErrorOf([&] { ReadExportManifest(out); }),
            path.string() + ": format_version " + std::to_string(kExportFormatVersion + 1) +
                ", this program reads " + std::to_string(kExportFormatVersion));

  manifest["format_version"] = kExportFormatVersion;
  manifest.erase("request");
  WriteFileAtomically(path, JsonFileText(manifest));
  const std::string error = datasets::testing::ErrorOf([&] { ReadExportManifest(out); });
  EXPECT_EQ(error.rfind(path.string() + ": unexpected content (", 0), 0u) << error;

  std::filesystem::remove(path);
  EXPECT_NE(datasets::testing::ErrorOf([&] { ReadExportManifest(out); }).find(path.string()),
            std::string::npos);
}

}  // namespace
}  // namespace phdslam::validation
