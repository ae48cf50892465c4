#include "validation/runner/results/results_config.h"

#include <chrono>
#include <cstdint>
#include <ctime>
#include <set>
#include <stdexcept>

#include "validation/runner/io/results_io.h"

namespace phdslam::validation {

std::string UtcNow() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  gmtime_r(&now, &utc);
  char buffer[32];
  std::strftime(buffer, sizeof(buffer), "%Y-%m-%dT%H:%M:%SZ", &utc);
  return buffer;
}

nlohmann::json ReadJsonObject(const std::filesystem::path& path) {
  nlohmann::json j = nlohmann::json::parse(ReadTextFile(path), nullptr, false);
  if (j.is_discarded() || !j.is_object()) {
    throw std::runtime_error(path.string() + ": not a JSON object");
  }
  return j;
}

nlohmann::json WithoutDataDir(nlohmann::json options) {
  if (options.is_object()) options.erase("data_dir");
  return options;
}

std::string FirstDifference(const nlohmann::json& a, const nlohmann::json& b,
                            const std::string& path) {
  if (a == b) return "";
  if (a.is_object() && b.is_object()) {
    std::set<std::string> keys;
    for (const auto& [key, value] : a.items()) keys.insert(key);
    for (const auto& [key, value] : b.items()) keys.insert(key);
    for (const std::string& key : keys) {
      const std::string sub = path.empty() ? key : path + "." + key;
      if (!a.contains(key)) return sub + " (absent before, now " + b.at(key).dump() + ")";
      if (!b.contains(key)) return sub + " (was " + a.at(key).dump() + ", now absent)";
      std::string d = FirstDifference(a.at(key), b.at(key), sub);
      if (!d.empty()) return d;
    }
  }
  return (path.empty() ? std::string("value") : path) + " (was " + a.dump() + ", now " + b.dump() +
         ")";
}

std::string ConfigConflict(const nlohmann::json& existing, const nlohmann::json& fresh,
                           const std::string& source) {
  try {
    if (existing.at("experiment") != fresh.at("experiment")) {
      return "experiment " + existing.at("experiment").dump() + ", now " +
             fresh.at("experiment").dump();
    }
    const nlohmann::json& old_scenario = existing.at("scenario");
    const nlohmann::json& new_scenario = fresh.at("scenario");
    if (old_scenario.at("name") != new_scenario.at("name")) {
      return "scenario " + old_scenario.at("name").dump() + ", now " +
             new_scenario.at("name").dump();
    }
    std::string d = FirstDifference(WithoutDataDir(old_scenario.at("options")),
                                    WithoutDataDir(new_scenario.at("options")), "scenario option");
    if (!d.empty()) return d;
    d = FirstDifference(existing.at("metrics"), fresh.at("metrics"), "metric setting");
    if (!d.empty()) return d;
    const nlohmann::json& old_estimators = existing.at("estimators");
    for (const auto& [name, entry] : fresh.at("estimators").items()) {
      if (!old_estimators.contains(name)) continue;
      const nlohmann::json& old_parameters = old_estimators.at(name).at("parameters");
      for (const auto& [n, parameters] : entry.at("parameters").items()) {
        if (!old_parameters.contains(n)) continue;
        d = FirstDifference(old_parameters.at(n), parameters, name + " N=" + n + " parameter");
        if (!d.empty()) return d;
      }
    }
    return "";
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(source + ": unexpected content (" + e.what() + ")");
  }
}

nlohmann::json UnionConfig(const nlohmann::json& existing, const nlohmann::json& fresh) {
  nlohmann::json merged = fresh;
  merged["estimators"] = existing.at("estimators");
  for (const auto& [name, entry] : fresh.at("estimators").items()) {
    if (!merged["estimators"].contains(name)) {
      merged["estimators"][name] = entry;
      continue;
    }
    nlohmann::json& old_entry = merged["estimators"][name];
    for (const auto& [n, parameters] : entry.at("parameters").items()) {
      old_entry["parameters"][n] = parameters;
    }
    old_entry["overrides"] = entry.at("overrides");
    old_entry["description"] = entry.at("description");
  }
  std::set<std::uint64_t> seeds = existing.at("seeds").get<std::set<std::uint64_t>>();
  for (std::uint64_t s : fresh.at("seeds")) seeds.insert(s);
  merged["seeds"] = seeds;
  std::set<int> particles = existing.at("particles").get<std::set<int>>();
  for (int n : fresh.at("particles")) particles.insert(n);
  merged["particles"] = particles;
  return merged;
}

}  // namespace phdslam::validation
