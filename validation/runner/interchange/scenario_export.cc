#include "validation/runner/interchange/scenario_export.h"

#include <cmath>
#include <fstream>
#include <stdexcept>

#include "datasets/sha256.h"
#include "datasets/text_fields.h"
#include "validation/runner/experiment/experiment_keys.h"
#include "validation/runner/io/results_io.h"
#include "validation/runner/io/results_layout.h"
#include "validation/runner/results/results_config.h"

namespace phdslam::validation {
namespace {

using datasets::text::FormatDouble;

std::string Row(std::initializer_list<std::string> cells) {
  std::string line;
  for (const std::string& c : cells) line += (line.empty() ? "" : ",") + c;
  return line + "\n";
}

std::string Index(std::size_t i) { return std::to_string(i); }

nlohmann::json MatrixJson(const Mat2& m) { return {{m(0, 0), m(0, 1)}, {m(1, 0), m(1, 1)}}; }

nlohmann::json MotionJson(const datasets::Scenario& s) {
  nlohmann::json motion = {{"control_noise_cov", MatrixJson(s.control_noise_cov)}};
  if (s.motion == datasets::MotionKind::kCar) {
    motion["kind"] = "car";
    motion["control"] = "[v_e, alpha]: encoder speed (m/s), steering angle (rad)";
    motion["geometry"] = {{"wheelbase_l", s.car.wheelbase_l},
                          {"encoder_offset_h", s.car.encoder_offset_h},
                          {"laser_a", s.car.laser_a},
                          {"laser_b", s.car.laser_b}};
    motion["equations"] = "src/models/car_motion_model.cc (Guivant/Nebot car with laser offset)";
  } else {
    motion["kind"] = "velocity";
    motion["control"] = "[v, omega]: speed (m/s), turn rate (rad/s)";
    motion["equations"] =
        "x' = x + v/w (sin(th + w dt) - sin th), y' = y + v/w (cos th - cos(th + w dt)), "
        "th' = th + w dt; for |w| < 1e-9: x' = x + v dt cos th, y' = y + v dt sin th";
  }
  return motion;
}

nlohmann::json SensorJson(const models::SensorModel& s) {
  const bool linear = s.profile == models::DetectionProfile::kLinearRange;
  return {{"measurement",
           "[r, phi] = [|m - p|, wrap(atan2(m_y - y, m_x - x) - theta)], phi in "
           "[-pi, pi]"},
          {"noise_cov", MatrixJson(s.noise_cov)},
          {"fov_range", s.fov_range},
          {"fov_half_angle", s.fov_half_angle},
          {"range_buffer", s.range_buffer},
          {"angle_buffer", s.angle_buffer},
          {"detection_profile", linear ? "linear_range" : "constant"},
          {"pd_max", s.pd_max},
          {"pd_nominal", s.pd_nominal},
          {"clutter_rate", s.clutter_rate},
          {"clutter_intensity", s.ClutterIntensity()},
          {"clutter_intensity_formula",
           "max(clutter_rate, 1e-3) / (fov_half_angle * fov_range^2), per unit of (r, phi)"}};
}

std::string StepsCsv(const datasets::Scenario& s) {
  std::string text = "step,t,controls,measurements\n";
  for (std::size_t k = 0; k < s.steps.size(); ++k) {
    const StepData& d = s.steps[k].data;
    text += Row({Index(k), FormatDouble(s.StepTime(k)), Index(d.controls.size()),
                 Index(d.measurements.size())});
  }
  return text;
}

std::string ControlsCsv(const datasets::Scenario& s) {
  std::string text = "step,t_start,t_end,u1,u2\n";
  for (std::size_t k = 0; k < s.steps.size(); ++k) {
    const StepData& d = s.steps[k].data;
    for (std::size_t i = 0; i < d.controls.size(); ++i) {
      text += Row({Index(k), FormatDouble(d.times[i]), FormatDouble(d.times[i + 1]),
                   FormatDouble(d.controls[i](0)), FormatDouble(d.controls[i](1))});
    }
  }
  return text;
}

std::string MeasurementsCsv(const datasets::Scenario& s) {
  std::string text = "step,index,range,bearing\n";
  for (std::size_t k = 0; k < s.steps.size(); ++k) {
    const std::vector<Measurement>& z = s.steps[k].data.measurements;
    for (std::size_t i = 0; i < z.size(); ++i) {
      text += Row({Index(k), Index(i), FormatDouble(z[i](0)), FormatDouble(z[i](1))});
    }
  }
  return text;
}

std::string TruthTum(const datasets::Scenario& s) {
  std::string text = "# t x y z qx qy qz qw\n";
  for (std::size_t k = 0; k < s.truth.poses.size(); ++k) {
    const Pose& p = s.truth.poses[k];
    text += FormatDouble(s.StepTime(k)) + " " + FormatDouble(p(0)) + " " + FormatDouble(p(1)) +
            " 0 0 0 " + FormatDouble(std::sin(p(2) / 2.0)) + " " +
            FormatDouble(std::cos(p(2) / 2.0)) + "\n";
  }
  return text;
}

std::string TruthMapCsv(const datasets::Scenario& s) {
  std::string text = "id,x,y\n";
  for (std::size_t i = 0; i < s.truth.landmarks.size(); ++i) {
    const Landmark& m = s.truth.landmarks[i];
    text += Row({Index(i), FormatDouble(m(0)), FormatDouble(m(1))});
  }
  return text;
}

std::string OriginsCsv(const datasets::Scenario& s) {
  std::string text = "step,index,origin\n";
  for (std::size_t k = 0; k < s.steps.size(); ++k) {
    const std::vector<int>& origin = s.steps[k].origin;
    for (std::size_t i = 0; i < origin.size(); ++i) {
      text += Row({Index(k), Index(i), std::to_string(origin[i])});
    }
  }
  return text;
}

std::string GpsCsv(const datasets::Scenario& s) {
  std::string text = "t,x,y\n";
  for (const datasets::GpsFix& fix : s.truth.gps) {
    text +=
        Row({FormatDouble(fix.t), FormatDouble(fix.position.x()), FormatDouble(fix.position.y())});
  }
  return text;
}

bool HasOrigins(const datasets::Scenario& s) {
  for (const datasets::ScenarioStep& step : s.steps) {
    if (!step.origin.empty()) return true;
  }
  return false;
}

}  // namespace

nlohmann::json ModelsJson(const datasets::Scenario& scenario) {
  const Pose& x0 = scenario.initial_pose;
  return {{"format_version", kExportFormatVersion},
          {"scenario", scenario.name},
          {"seed", scenario.seed},
          {"steps", scenario.steps.size()},
          {"initial_pose", {x0(0), x0(1), x0(2)}},
          {"motion", MotionJson(scenario)},
          {"sensor", SensorJson(scenario.sensor)}};
}

std::map<std::string, std::string> ExportFiles(const datasets::Scenario& scenario) {
  const std::string seed = SeedFolderName(scenario.seed) + "/";
  const std::string truth = std::string(kTruthFolder) + "/" + seed;
  std::map<std::string, std::string> files;
  files[seed + "steps.csv"] = StepsCsv(scenario);
  files[seed + "controls.csv"] = ControlsCsv(scenario);
  files[seed + "measurements.csv"] = MeasurementsCsv(scenario);
  files[seed + "models.json"] = JsonFileText(ModelsJson(scenario));
  if (scenario.truth.poses.size() == scenario.steps.size() && !scenario.truth.poses.empty()) {
    files[truth + "trajectory.tum"] = TruthTum(scenario);
  }
  if (!scenario.truth.landmarks.empty()) files[truth + "map.csv"] = TruthMapCsv(scenario);
  if (!scenario.truth.gps.empty()) files[truth + "gps.csv"] = GpsCsv(scenario);
  if (HasOrigins(scenario)) files[truth + "origins.csv"] = OriginsCsv(scenario);
  return files;
}

void RequireEmptyExportFolder(const std::filesystem::path& out) {
  if (!std::filesystem::exists(out)) return;
  if (!std::filesystem::is_directory(out)) {
    throw std::invalid_argument("export: --out " + out.string() + " is not a folder");
  }
  if (!std::filesystem::is_empty(out)) {
    throw std::invalid_argument("export: --out " + out.string() +
                                " is not empty; give a new or empty folder (an export is not "
                                "written over another)");
  }
}

void WriteExport(const std::filesystem::path& out, const ExportDescription& description,
                 const std::vector<datasets::Scenario>& scenarios) {
  RequireEmptyExportFolder(out);
  std::map<std::string, std::string> checksums;
  nlohmann::json steps = nlohmann::json::object();
  for (const datasets::Scenario& scenario : scenarios) {
    for (const auto& [path, content] : ExportFiles(scenario)) {
      const std::filesystem::path file = out / path;
      std::filesystem::create_directories(file.parent_path());
      WriteFileAtomically(file, content);
      checksums[path] = datasets::Sha256Hex(content);
    }
    steps[std::to_string(scenario.seed)] = scenario.steps.size();
  }
  const nlohmann::json manifest = {{"format", "phdslam-export"},
                                   {"format_version", kExportFormatVersion},
                                   {"scenario", description.scenario},
                                   {"options", description.options},
                                   {"request", description.request},
                                   {"seeds", description.seeds},
                                   {"steps", steps}};
  const std::string manifest_text = JsonFileText(manifest);
  WriteFileAtomically(out / kExportManifestFile, manifest_text);
  checksums[kExportManifestFile] = datasets::Sha256Hex(manifest_text);
  std::string sums;
  for (const auto& [path, hex] : checksums) sums += hex + "  " + path + "\n";
  WriteFileAtomically(out / kExportChecksumFile, sums);
}

std::map<std::string, std::string> ReadExportChecksums(const std::filesystem::path& folder) {
  const std::filesystem::path path = folder / kExportChecksumFile;
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path.string() + ": cannot be read");
  std::map<std::string, std::string> sums;
  std::string line;
  for (std::size_t number = 1; std::getline(in, line); ++number) {
    if (datasets::text::Trim(line).empty()) continue;
    if (line.size() < 67 || line.compare(64, 2, "  ") != 0 ||
        line.find_first_not_of("0123456789abcdef") < 64) {
      throw std::runtime_error(datasets::text::Where(path, number) +
                               ": expected '<64 hex digits>  <path>', got '" +
                               datasets::text::Printable(line) + "'");
    }
    sums[line.substr(66)] = line.substr(0, 64);
  }
  return sums;
}

nlohmann::json ExportRequest(const Experiment& experiment) {
  nlohmann::json request = nlohmann::json::object();
  for (const ExperimentKey& key : ExperimentKeys()) {
    if (!key.manifest_key.empty()) request[key.manifest_key] = key.write_manifest(experiment);
  }
  return request;
}

Experiment ReadExportManifest(const std::filesystem::path& export_dir) {
  const std::filesystem::path path = export_dir / kExportManifestFile;
  const nlohmann::json manifest = ReadJsonObject(path);
  try {
    if (manifest.at("format_version").get<int>() != kExportFormatVersion) {
      throw std::runtime_error(path.string() + ": format_version " +
                               manifest.at("format_version").dump() + ", this program reads " +
                               std::to_string(kExportFormatVersion));
    }
    Experiment x;
    x.scenario = manifest.at("scenario").get<std::string>();
    const nlohmann::json& request = manifest.at("request");
    for (const ExperimentKey& key : ExperimentKeys()) {
      if (!key.manifest_key.empty()) key.read_manifest(request.at(key.manifest_key), x);
    }
    x.seeds = manifest.at("seeds").get<std::vector<std::uint64_t>>();
    return x;
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(path.string() + ": unexpected content (" + e.what() + ")");
  }
}

}  // namespace phdslam::validation
