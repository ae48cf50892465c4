// config.json of a results folder: reading it, and deciding whether two configurations may share
// one folder (resume, added seeds, merged shards) and what their union is.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace phdslam::validation {

/// The current time in UTC as config.json's started_utc records it: "YYYY-MM-DDTHH:MM:SSZ".
std::string UtcNow();

/// The object in a JSON file; throws std::runtime_error naming the file when it cannot be read or
/// is not a JSON object.
nlohmann::json ReadJsonObject(const std::filesystem::path& path);

/// `options` without its "data_dir" key (the same data may live in another folder).
nlohmann::json WithoutDataDir(nlohmann::json options);

/// The first path (`path`.key.subkey) at which a and b differ, with both values, or "" when they
/// are equal. For error messages.
std::string FirstDifference(const nlohmann::json& a, const nlohmann::json& b,
                            const std::string& path);

/// Why runs configured by `fresh` may not join runs configured by `existing`, or "" when they
/// may: another experiment name, scenario, scenario option (data_dir aside), metric setting, or
/// other resolved parameters for an (estimator, particles) pair both hold. Throws
/// std::runtime_error naming `source` when a config lacks one of these fields.
std::string ConfigConflict(const nlohmann::json& existing, const nlohmann::json& fresh,
                           const std::string& source);

/// The union of two compatible configs: `fresh` with the estimators, parameters, seeds and
/// particle counts of both (seeds and particle counts sorted).
nlohmann::json UnionConfig(const nlohmann::json& existing, const nlohmann::json& fresh);

}  // namespace phdslam::validation
