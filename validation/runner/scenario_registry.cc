#include "validation/runner/scenario_registry.h"

#include <stdexcept>

#include "datasets/data_dir.h"
#include "datasets/scenario_check.h"
#include "datasets/scenario_generator.h"
#include "datasets/sha256.h"

namespace phdslam::validation {
namespace {

void RequireNonNegativeSteps(const ScenarioOptions& options) {
  if (options.steps < 0) {
    throw std::invalid_argument("steps: expected >= 0 (0 = all), got " +
                                std::to_string(options.steps));
  }
}

datasets::SyntheticOptions ToSyntheticOptions(const ScenarioOptions& options) {
  RequireNonNegativeSteps(options);
  datasets::SyntheticOptions o;
  o.steps = options.steps;
  if (options.detection_probability) o.detection_probability = *options.detection_probability;
  if (options.clutter_rate) o.clutter_rate = *options.clutter_rate;
  o.Validate();
  return o;
}

datasets::VictoriaParkOptions ToVictoriaParkOptions(const ScenarioOptions& options) {
  RequireNonNegativeSteps(options);
  datasets::VictoriaParkOptions o;
  o.max_steps = options.steps;
  if (options.detection_probability) {
    o.detection_probability_max = *options.detection_probability;
    o.detection_probability_nominal = *options.detection_probability;
  }
  if (options.clutter_rate) o.clutter_rate = *options.clutter_rate;
  o.Validate();
  return o;
}

datasets::GeneratorOptions ToGeneratorOptions(const ScenarioOptions& options) {
  RequireNonNegativeSteps(options);
  datasets::GeneratorOptions o;
  if (options.steps > 0) o.steps = options.steps;
  if (options.detection_probability) o.detection_probability = *options.detection_probability;
  if (options.clutter_rate) o.clutter_rate = *options.clutter_rate;
  o.Validate();
  return o;
}

// {"<relative path>": "sha256:<hex>"} for the data files a scenario reads: part of a run's
// identity, so results made from other data are never mixed with these.
nlohmann::json DataFileChecksums(const std::filesystem::path& data_dir,
                                 const std::vector<std::filesystem::path>& files) {
  nlohmann::json out = nlohmann::json::object();
  std::error_code ec;
  for (const std::filesystem::path& file : files) {
    if (!std::filesystem::is_regular_file(data_dir / file, ec)) continue;  // the loader says so
    out[file.generic_string()] = "sha256:" + datasets::FileSha256Hex(data_dir / file);
  }
  return out;
}

nlohmann::json MatrixJson(const Mat2& m) {
  return nlohmann::json::array(
      {nlohmann::json::array({m(0, 0), m(0, 1)}), nlohmann::json::array({m(1, 0), m(1, 1)})});
}

ScenarioEntry PaperSyntheticEntry() {
  ScenarioEntry e;
  e.name = "paper-synthetic";
  e.description =
      "the paper's synthetic scenario (Environment_SLAM.mat: 160 landmarks, 4000 "
      "steps of 1 s); truth poses and map; measurements drawn per seed";
  e.make = [](std::uint64_t seed, const ScenarioOptions& options, ScenarioCache& cache) {
    const datasets::SyntheticOptions o = ToSyntheticOptions(options);
    return datasets::MakePaperSyntheticScenario(
        cache.PaperSynthetic(datasets::ResolveDataDir(options.data_dir)), seed, o);
  };
  e.resolved_options = [](const ScenarioOptions& options) {
    const datasets::SyntheticOptions o = ToSyntheticOptions(options);
    const std::filesystem::path data_dir = datasets::ResolveDataDir(options.data_dir);
    return nlohmann::json{
        {"data_dir", data_dir.string()},
        {"data_files", DataFileChecksums(data_dir, datasets::PaperSyntheticDataFiles())},
        {"steps", o.steps},
        {"detection_probability", o.detection_probability},
        {"clutter_rate", o.clutter_rate},
        {"fov_range", o.fov_range},
        {"fov_half_angle", o.fov_half_angle},
        {"range_buffer", o.range_buffer},
        {"angle_buffer", o.angle_buffer},
        {"measurement_noise_cov", MatrixJson(o.measurement_noise_cov)},
        {"control_noise_cov", MatrixJson(o.control_noise_cov)},
    };
  };
  return e;
}

ScenarioEntry VictoriaParkEntry() {
  ScenarioEntry e;
  e.name = "victoria-park";
  e.description =
      "ACFR Victoria Park: tree detections, car odometry, GPS as the only truth; "
      "artificial clutter drawn per seed";
  e.make = [](std::uint64_t seed, const ScenarioOptions& options, ScenarioCache& cache) {
    const datasets::VictoriaParkOptions o = ToVictoriaParkOptions(options);
    return datasets::MakeVictoriaParkScenario(
        cache.VictoriaPark(datasets::ResolveDataDir(options.data_dir)), seed, o);
  };
  e.resolved_options = [](const ScenarioOptions& options) {
    const datasets::VictoriaParkOptions o = ToVictoriaParkOptions(options);
    const std::filesystem::path data_dir = datasets::ResolveDataDir(options.data_dir);
    return nlohmann::json{
        {"data_dir", data_dir.string()},
        {"data_files", DataFileChecksums(data_dir, datasets::VictoriaParkDataFiles(data_dir))},
        {"steps", o.max_steps},
        {"detection_probability_max", o.detection_probability_max},
        {"detection_probability_nominal", o.detection_probability_nominal},
        {"clutter_rate", o.clutter_rate},
        {"fov_range", o.fov_range},
        {"fov_half_angle", o.fov_half_angle},
        {"range_buffer", o.range_buffer},
        {"angle_buffer", o.angle_buffer},
        {"measurement_noise_cov", MatrixJson(o.measurement_noise_cov)},
        {"control_noise_cov", MatrixJson(o.control_noise_cov)},
    };
  };
  return e;
}

ScenarioEntry GeneratedEntry() {
  ScenarioEntry e;
  e.name = "generated";
  e.description =
      "a generated scenario of the paper's kind (100 landmarks along a smooth "
      "1000-step path; map and measurements drawn per seed); no data files";
  e.uses_data_dir = false;
  e.make = [](std::uint64_t seed, const ScenarioOptions& options, ScenarioCache&) {
    return datasets::GenerateScenario(ToGeneratorOptions(options), seed);
  };
  e.resolved_options = [](const ScenarioOptions& options) {
    const datasets::GeneratorOptions o = ToGeneratorOptions(options);
    return nlohmann::json{
        {"steps", o.steps},
        {"dt", o.dt},
        {"speed", o.speed},
        {"turn_amplitude", o.turn_amplitude},
        {"landmarks", o.landmarks},
        {"corridor_half_width", o.corridor_half_width},
        {"detection_probability", o.detection_probability},
        {"clutter_rate", o.clutter_rate},
        {"fov_range", o.fov_range},
        {"fov_half_angle", o.fov_half_angle},
        {"range_buffer", o.range_buffer},
        {"angle_buffer", o.angle_buffer},
        {"measurement_noise_cov", MatrixJson(o.measurement_noise_cov)},
        {"control_noise_cov", MatrixJson(o.control_noise_cov)},
        {"initial_pose", {o.initial_pose(0), o.initial_pose(1), o.initial_pose(2)}},
    };
  };
  return e;
}

}  // namespace

const datasets::PaperSyntheticEnvironment& ScenarioCache::PaperSynthetic(
    const std::filesystem::path& data_dir) {
  const std::lock_guard<std::mutex> lock(mutex_);
  auto& slot = paper_synthetic_[data_dir];
  if (!slot) {
    slot = std::make_unique<const datasets::PaperSyntheticEnvironment>(
        datasets::LoadPaperSyntheticEnvironment(data_dir));
  }
  return *slot;
}

const datasets::VictoriaParkData& ScenarioCache::VictoriaPark(
    const std::filesystem::path& data_dir) {
  const std::lock_guard<std::mutex> lock(mutex_);
  auto& slot = victoria_park_[data_dir];
  if (!slot) {
    slot = std::make_unique<const datasets::VictoriaParkData>(
        datasets::LoadVictoriaParkData(data_dir));
  }
  return *slot;
}

const std::vector<ScenarioEntry>& ScenarioTable() {
  static const std::vector<ScenarioEntry> table = {
      PaperSyntheticEntry(),
      VictoriaParkEntry(),
      GeneratedEntry(),
  };
  return table;
}

const ScenarioEntry& FindScenario(const std::string& name) {
  std::string known;
  for (const ScenarioEntry& e : ScenarioTable()) {
    if (e.name == name) return e;
    known += known.empty() ? e.name : ", " + e.name;
  }
  throw std::invalid_argument("unknown scenario '" + name + "' (known: " + known + ")");
}

datasets::Scenario MakeScenario(const std::string& name, std::uint64_t seed,
                                const ScenarioOptions& options, ScenarioCache& cache) {
  datasets::Scenario scenario = FindScenario(name).make(seed, options, cache);
  datasets::CheckScenario(scenario, name + " seed " + std::to_string(seed));
  return scenario;
}

datasets::Scenario MakeScenario(const std::string& name, std::uint64_t seed,
                                const ScenarioOptions& options) {
  ScenarioCache cache;
  return MakeScenario(name, seed, options, cache);
}

}  // namespace phdslam::validation

namespace phdslam::validation {

ScenarioSource MakeScenarioSource(const std::string& name, const ScenarioOptions& options) {
  const ScenarioEntry& entry = FindScenario(name);
  ScenarioSource source;
  source.name = entry.name;
  source.options = entry.resolved_options(options);
  auto cache = std::make_shared<ScenarioCache>();
  source.make = [name, options, cache](std::uint64_t seed) {
    return MakeScenario(name, seed, options, *cache);
  };
  return source;
}

}  // namespace phdslam::validation
