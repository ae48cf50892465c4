#include "validation/runner/results/run_files.h"

#include <cmath>
#include <stdexcept>
#include <system_error>
#include <vector>

#include "datasets/map_io.h"
#include "datasets/trajectory_io.h"
#include "src/core/log_sum_exp.h"
#include "validation/runner/io/results_io.h"
#include "validation/runner/io/results_layout.h"

namespace phdslam::validation {
namespace {

std::vector<datasets::StampedPose> Stamped(const std::vector<double>& times,
                                           const std::vector<Pose>& poses) {
  std::vector<datasets::StampedPose> out;
  out.reserve(poses.size());
  for (std::size_t k = 0; k < poses.size(); ++k) out.push_back({times[k], poses[k]});
  return out;
}

std::vector<datasets::MapPoint> MapPoints(const filters::MapEstimate& map) {
  std::vector<datasets::MapPoint> points;
  points.reserve(map.size());
  for (std::size_t i = 0; i < map.size(); ++i) {
    datasets::MapPoint p;
    p.position = map.means[i];
    p.weight = i < map.log_weights.size() ? std::exp(map.log_weights[i]) : 0.0;
    // A covariance that could not be computed (e.g. the smoother's marginal of a landmark the
    // rank-deficient Jacobian leaves unobservable) is written as "not available".
    if (i < map.covs.size() && map.covs[i].allFinite()) p.cov = map.covs[i];
    points.push_back(p);
  }
  return points;
}

}  // namespace

std::string StepsCsv(const RunRecord& record, const datasets::Scenario& scenario,
                     const RunEvaluation& evaluation) {
  std::vector<std::string> header = {"step",       "t",
                                     "x",          "y",
                                     "theta",      "x_true",
                                     "y_true",     "theta_true",
                                     "pos_err_m",  "heading_err_deg",
                                     "ess",        "resampled",
                                     "hypotheses", "map_components",
                                     "ms",         "nees",
                                     "nees_rb",    "nis_sum",
                                     "nis_count",  "gps_nees_rb"};
  // The opt-in map OSPA (phdslam run --map-ospa) is appended as the last column.
  const bool has_map_ospa = evaluation.map_ospa_m.size() == record.poses.size();
  if (has_map_ospa) header.push_back("map_ospa_m");
  std::string text = CsvRow(header);
  const bool has_truth = scenario.truth.poses.size() == record.poses.size();
  const bool has_diag = record.diagnostics.size() == record.poses.size();
  const bool has_ms = record.step_ms.size() == record.poses.size();
  std::vector<std::string> cells(has_map_ospa ? 21 : 20);
  for (std::size_t k = 0; k < record.poses.size(); ++k) {
    const Pose& p = record.poses[k];
    cells[0] = FormatInteger(static_cast<std::int64_t>(k));
    cells[1] = FormatNumber(record.step_times[k]);
    cells[2] = FormatNumber(p(0));
    cells[3] = FormatNumber(p(1));
    cells[4] = FormatNumber(p(2));
    for (int i = 0; i < 3; ++i) {
      cells[5 + static_cast<std::size_t>(i)] = has_truth && scenario.truth.PoseScored(k)
                                                   ? FormatNumber(scenario.truth.poses[k](i))
                                                   : std::string();
    }
    cells[8] = k < evaluation.position_error_m.size() ? FormatNumber(evaluation.position_error_m[k])
                                                      : std::string();
    cells[9] = k < evaluation.heading_error_deg.size()
                   ? FormatNumber(evaluation.heading_error_deg[k])
                   : std::string();
    if (has_diag) {
      const filters::StepDiagnostics& d = record.diagnostics[k];
      // A deterministic estimator has no particle weights: no ESS, no resampling.
      cells[10] = record.particle_weights ? FormatNumber(d.ess) : std::string();
      cells[11] = record.particle_weights ? FormatInteger(d.resampled ? 1 : 0) : std::string();
      cells[12] = FormatInteger(d.hypotheses);
      cells[13] = FormatInteger(d.map_components);
    } else {
      for (std::size_t c = 10; c < 14; ++c) cells[c].clear();
    }
    cells[14] = has_ms ? FormatNumber(record.step_ms[k]) : std::string();
    cells[15] =
        k < evaluation.pose_nees.size() ? FormatNumber(evaluation.pose_nees[k]) : std::string();
    cells[16] = k < evaluation.pose_nees_rb.size() ? FormatNumber(evaluation.pose_nees_rb[k])
                                                   : std::string();
    const bool has_nis = has_diag && record.diagnostics[k].nis_count > 0;
    cells[17] = has_nis ? FormatNumber(record.diagnostics[k].nis_sum) : std::string();
    cells[18] = has_nis ? FormatInteger(record.diagnostics[k].nis_count) : std::string();
    cells[19] =
        k < evaluation.gps_nees_rb.size() ? FormatNumber(evaluation.gps_nees_rb[k]) : std::string();
    if (has_map_ospa) cells[20] = FormatNumber(evaluation.map_ospa_m[k]);
    text += CsvRow(cells);
  }
  return text;
}

std::string ParticlesCsv(const RunRecord& record) {
  if (record.particle_states.empty()) return "";
  std::string text = CsvRow({"step", "particle", "x", "y", "log_weight"});
  std::vector<double> log_weights;
  for (std::size_t k = 0; k < record.particle_states.size(); ++k) {
    const auto& states = record.particle_states[k];
    log_weights.clear();
    for (const auto& [pose, log_weight] : states) log_weights.push_back(log_weight);
    const double log_total = LogSumExp(log_weights);
    for (std::size_t i = 0; i < states.size(); ++i) {
      text += CsvRow({FormatInteger(static_cast<std::int64_t>(k)),
                      FormatInteger(static_cast<std::int64_t>(i)), FormatNumber(states[i].first(0)),
                      FormatNumber(states[i].first(1)), FormatNumber(log_weights[i] - log_total)});
    }
  }
  return text;
}

void WriteRunFiles(const std::filesystem::path& folder, const RunRecord& record,
                   const datasets::Scenario& scenario, const RunEvaluation& evaluation,
                   const nlohmann::json& identity) {
  std::filesystem::create_directories(folder);
  WriteFileAtomically(folder / kStepsFile, StepsCsv(record, scenario, evaluation));
  WriteFileAtomically(folder / kTrajectoryFile, [&](const std::filesystem::path& temp) {
    datasets::WriteTumTrajectory(temp, Stamped(record.step_times, record.poses));
  });
  WriteFileAtomically(folder / kMapFile, [&](const std::filesystem::path& temp) {
    datasets::WriteMapCsv(temp, MapPoints(record.final_map));
  });
  std::error_code ignored;
  if (record.particle_states.empty()) {
    std::filesystem::remove(folder / kParticlesFile, ignored);
  } else {
    WriteFileAtomically(folder / kParticlesFile, ParticlesCsv(record));
  }
  std::filesystem::remove(folder / kErrorFile, ignored);
  nlohmann::json metrics = identity;
  metrics.update(ToJson(evaluation.metrics));
  WriteFileAtomically(folder / kMetricsFile, JsonFileText(metrics));
}

void WriteRunError(const std::filesystem::path& folder, const nlohmann::json& identity,
                   const std::string& message) {
  std::filesystem::create_directories(folder);
  nlohmann::json j = identity;
  j["error"] = message;
  WriteFileAtomically(folder / kErrorFile, JsonFileText(j));
}

namespace {

void WriteTruthMap(const std::filesystem::path& file, const datasets::Scenario& scenario,
                   std::string_view tag) {
  std::vector<datasets::MapPoint> points;
  points.reserve(scenario.truth.landmarks.size());
  for (const Landmark& m : scenario.truth.landmarks) points.push_back({m, 1.0, std::nullopt});
  WriteFileAtomically(
      file, [&](const std::filesystem::path& temp) { datasets::WriteMapCsv(temp, points); }, tag);
}

}  // namespace

void WriteRootTruthMap(const std::filesystem::path& out, const datasets::Scenario& scenario) {
  if (scenario.truth.landmarks.empty()) return;
  WriteTruthMap(out / kTruthMapFile, scenario, "root");
}

void WriteTruthFiles(const std::filesystem::path& out, const datasets::Scenario& scenario,
                     std::string_view tag) {
  const std::filesystem::path folder = TruthFolder(out, scenario.seed);
  if (!scenario.truth.landmarks.empty() && !std::filesystem::exists(folder / kTruthMapFile)) {
    std::filesystem::create_directories(folder);
    WriteTruthMap(folder / kTruthMapFile, scenario, tag);
  }
  if (!scenario.truth.gps.empty() && !std::filesystem::exists(folder / kTruthGpsFile)) {
    std::filesystem::create_directories(folder);
    std::string text = "t,x,y\n";
    for (const datasets::GpsFix& fix : scenario.truth.gps) {
      text += FormatNumber(fix.t) + "," + FormatNumber(fix.position.x()) + "," +
              FormatNumber(fix.position.y()) + "\n";
    }
    WriteFileAtomically(folder / kTruthGpsFile, text, tag);
  }
  if (!scenario.truth.poses.empty() && scenario.truth.poses.size() == scenario.steps.size()) {
    if (std::filesystem::exists(folder / kTruthTrajectoryFile)) return;
    std::filesystem::create_directories(folder);
    std::vector<double> times;
    std::vector<Pose> poses;  // the scored steps only: no stand-ins for truth gaps
    times.reserve(scenario.steps.size());
    poses.reserve(scenario.steps.size());
    for (std::size_t k = 0; k < scenario.steps.size(); ++k) {
      if (!scenario.truth.PoseScored(k)) continue;
      times.push_back(scenario.StepTime(k));
      poses.push_back(scenario.truth.poses[k]);
    }
    WriteFileAtomically(
        folder / kTruthTrajectoryFile,
        [&](const std::filesystem::path& temp) {
          datasets::WriteTumTrajectory(temp, Stamped(times, poses));
        },
        tag);
  }
}

}  // namespace phdslam::validation
