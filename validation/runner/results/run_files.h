// Writes one run's files (steps.csv, trajectory.tum, map.csv, metrics.json) and the scenario's
// truth files into a results folder. Every file is written atomically; metrics.json comes last,
// so its presence marks a finished run.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "datasets/scenario.h"
#include "validation/runner/evaluation/run_metrics.h"
#include "validation/runner/evaluation/run_record.h"

namespace phdslam::validation {

/// The steps.csv text: header
/// step,t,x,y,theta,x_true,y_true,theta_true,pos_err_m,heading_err_deg,ess,resampled,hypotheses,
/// map_components,ms,nees,nees_rb,nis_sum,nis_count,gps_nees_rb and one row per step (cells
/// empty where a value is unknown).
std::string StepsCsv(const RunRecord& record, const datasets::Scenario& scenario,
                     const RunEvaluation& evaluation);

/// The particles.csv text: header step,particle,x,y,log_weight and one row per particle per
/// step of record.particle_states; log_weight is normalised per step (log-sum-exp over the
/// step's particles is 0). Empty when the record has no particle states.
std::string ParticlesCsv(const RunRecord& record);

/// Writes steps.csv, trajectory.tum, map.csv, particles.csv (when the record has particle
/// states; a stale one is removed otherwise) and, last, metrics.json = `identity` (estimator,
/// particles, seed, ...) merged with ToJson(evaluation.metrics) into `folder` (created if
/// needed), and removes a stale error.json. Throws std::runtime_error naming the file on failure.
void WriteRunFiles(const std::filesystem::path& folder, const RunRecord& record,
                   const datasets::Scenario& scenario, const RunEvaluation& evaluation,
                   const nlohmann::json& identity);

/// Writes `identity` plus {"error": message} to `folder`/error.json.
void WriteRunError(const std::filesystem::path& folder, const nlohmann::json& identity,
                   const std::string& message);

/// Writes <out>/truth/seed-<seed>/truth.tum (true poses at the step times),
/// <out>/truth/seed-<seed>/truth_map.csv (true landmarks, weight 1) and
/// <out>/truth/seed-<seed>/gps.csv (GPS fixes: t,x,y) when the scenario has them and the files
/// do not exist yet. `tag` distinguishes concurrent writers (temporary names).
void WriteTruthFiles(const std::filesystem::path& out, const datasets::Scenario& scenario,
                     std::string_view tag);

/// Writes <out>/truth_map.csv, the true map of `scenario`, when it has one. The runner calls it
/// with the plan's lowest seed before any run starts, so the file does not depend on which run
/// finishes first, nor on sharding (the map is the same for every seed of paper-synthetic; for
/// a generated scenario the per-seed maps are in truth/seed-<s>/).
void WriteRootTruthMap(const std::filesystem::path& out, const datasets::Scenario& scenario);

}  // namespace phdslam::validation
