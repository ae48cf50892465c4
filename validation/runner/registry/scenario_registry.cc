#include "validation/runner/registry/scenario_registry.h"

#include <stdexcept>

#include "datasets/data_dir.h"
#include "datasets/glmb_simulation.h"
#include "datasets/scenario_check.h"
#include "datasets/scenario_generator.h"
#include "datasets/scphd_simulation.h"
#include "datasets/sha256.h"
#include "datasets/simulation_limits.h"
#include "validation/runner/registry/scenario_option_tables.h"

namespace phdslam::validation {
namespace {

void RequireNonNegativeSteps(const ScenarioOptions& options) {
  if (options.steps < 0 || options.steps > datasets::kMaxSimulatedSteps) {
    throw std::invalid_argument("steps: expected 0 (all) to " +
                                std::to_string(datasets::kMaxSimulatedSteps) + ", got " +
                                std::to_string(options.steps));
  }
}

// Applies ScenarioOptions::settings through `table`, naming the scenario in errors.
template <class T>
void ApplySettings(const params::ParameterTable<T>& table, const ScenarioOptions& options,
                   const std::string& scenario, T& o) {
  try {
    table.Apply(options.settings, o);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("scenario '" + scenario + "' option: " + e.what());
  }
}

// Reads `value` into a default options struct through the row of `key`: checks its type and
// range (the struct's cross-field rules are checked when the scenario is resolved).
template <class T>
std::function<void(const std::string&, const nlohmann::json&)> OptionCheck(
    const params::ParameterTable<T>& table) {
  return [&table](const std::string& key, const nlohmann::json& value) {
    T o;
    table.Apply(nlohmann::json::object({{key, value}}), o);
  };
}

template <class T>
std::vector<ScenarioOptionHelp> OptionKeys(const params::ParameterTable<T>& table) {
  std::vector<ScenarioOptionHelp> keys;
  for (const params::Field<T>& f : table.fields()) keys.push_back({f.key, f.help});
  return keys;
}

datasets::SyntheticOptions ToSyntheticOptions(const ScenarioOptions& options) {
  RequireNonNegativeSteps(options);
  datasets::SyntheticOptions o;
  o.steps = options.steps;
  if (options.detection_probability) o.detection_probability = *options.detection_probability;
  if (options.clutter_rate) o.clutter_rate = *options.clutter_rate;
  ApplySettings(PaperSyntheticOptionsTable(), options, "paper-synthetic", o);
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
  ApplySettings(VictoriaParkOptionsTable(), options, "victoria-park", o);
  o.Validate();
  return o;
}

datasets::GeneratorOptions ToGeneratorOptions(const ScenarioOptions& options) {
  RequireNonNegativeSteps(options);
  datasets::GeneratorOptions o;
  if (options.steps > 0) o.steps = options.steps;
  if (options.detection_probability) o.detection_probability = *options.detection_probability;
  if (options.clutter_rate) o.clutter_rate = *options.clutter_rate;
  ApplySettings(GeneratedOptionsTable(), options, "generated", o);
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

// The synthetic scenario's file comes from the data folder when it holds it, else from the copy
// the repository carries (datasets/data): a clone runs it without any data folder.
std::filesystem::path PaperSyntheticDataDir(const ScenarioOptions& options) {
  return datasets::ResolveDataDirFor(options.data_dir, datasets::PaperSyntheticDataFiles());
}

ScenarioEntry PaperSyntheticEntry() {
  ScenarioEntry e;
  e.name = "paper-synthetic";
  e.option_keys = OptionKeys(PaperSyntheticOptionsTable());
  e.check_option = OptionCheck(PaperSyntheticOptionsTable());
  e.description =
      "the paper's synthetic scenario (Environment_SLAM.mat: 160 landmarks, 4000 "
      "steps of 1 s); truth poses and map; measurements drawn per seed";
  e.make = [](std::uint64_t seed, const ScenarioOptions& options, ScenarioCache& cache) {
    const datasets::SyntheticOptions o = ToSyntheticOptions(options);
    return datasets::MakePaperSyntheticScenario(
        cache.PaperSynthetic(PaperSyntheticDataDir(options)), seed, o);
  };
  e.resolved_options = [](const ScenarioOptions& options) {
    const datasets::SyntheticOptions o = ToSyntheticOptions(options);
    const std::filesystem::path data_dir = PaperSyntheticDataDir(options);
    nlohmann::json j = PaperSyntheticOptionsTable().ToJson(o);
    j["data_dir"] = data_dir.string();
    j["data_files"] = DataFileChecksums(data_dir, datasets::PaperSyntheticDataFiles());
    j["steps"] = o.steps;
    return j;
  };
  return e;
}

ScenarioEntry VictoriaParkEntry() {
  ScenarioEntry e;
  e.name = "victoria-park";
  e.option_keys = OptionKeys(VictoriaParkOptionsTable());
  e.check_option = OptionCheck(VictoriaParkOptionsTable());
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
    nlohmann::json j = VictoriaParkOptionsTable().ToJson(o);
    j["data_dir"] = data_dir.string();
    j["data_files"] = DataFileChecksums(data_dir, datasets::VictoriaParkDataFiles(data_dir));
    j["steps"] = o.max_steps;
    return j;
  };
  return e;
}

ScenarioEntry GeneratedEntry() {
  ScenarioEntry e;
  e.name = "generated";
  e.option_keys = OptionKeys(GeneratedOptionsTable());
  e.check_option = OptionCheck(GeneratedOptionsTable());
  e.description =
      "a generated scenario of the paper's kind (100 landmarks along a smooth "
      "1000-step path; map and measurements drawn per seed); no data files";
  e.uses_data_dir = false;
  e.make = [](std::uint64_t seed, const ScenarioOptions& options, ScenarioCache&) {
    return datasets::GenerateScenario(ToGeneratorOptions(options), seed);
  };
  e.resolved_options = [](const ScenarioOptions& options) {
    const datasets::GeneratorOptions o = ToGeneratorOptions(options);
    nlohmann::json j = GeneratedOptionsTable().ToJson(o);
    j["steps"] = o.steps;
    return j;
  };
  return e;
}

datasets::ScPhdSimOptions ToScPhdSimOptions(const ScenarioOptions& options) {
  RequireNonNegativeSteps(options);
  datasets::ScPhdSimOptions o;
  if (options.steps > 0) o.steps = options.steps;
  if (options.detection_probability) o.detection_probability = *options.detection_probability;
  if (options.clutter_rate) o.clutter_rate = *options.clutter_rate;
  ApplySettings(ScPhdSimOptionsTable(), options, "scphd-sim", o);
  o.Validate();
  return o;
}

ScenarioEntry ScPhdSimEntry() {
  ScenarioEntry e;
  e.name = "scphd-sim";
  e.option_keys = OptionKeys(ScPhdSimOptionsTable());
  e.check_option = OptionCheck(ScPhdSimOptionsTable());
  e.description =
      "the simulation of single-cluster PHD SLAM's paper (Lee, Clark & Salvi 2012): Ackermann "
      "vehicle, two laps of a 40 m circle among 60 fixed landmarks, 838 steps of 0.2 s; odometry "
      "and measurements drawn per seed (datasets/scphd_simulation.h); no data files";
  e.uses_data_dir = false;
  e.make = [](std::uint64_t seed, const ScenarioOptions& options, ScenarioCache&) {
    return datasets::MakeScPhdSimScenario(ToScPhdSimOptions(options), seed);
  };
  e.resolved_options = [](const ScenarioOptions& options) {
    const datasets::ScPhdSimOptions o = ToScPhdSimOptions(options);
    nlohmann::json j = ScPhdSimOptionsTable().ToJson(o);
    j["steps"] = o.steps;
    return j;
  };
  return e;
}

datasets::MrclamOptions ToMrclamOptions(const ScenarioOptions& options) {
  RequireNonNegativeSteps(options);
  datasets::MrclamOptions o;
  o.max_steps = options.steps;
  if (options.detection_probability) o.detection_probability = *options.detection_probability;
  if (options.clutter_rate) o.clutter_rate = *options.clutter_rate;
  ApplySettings(MrclamOptionsTable(), options, "mrclam", o);
  o.Validate();
  return o;
}

datasets::GlmbSimOptions ToGlmbSimOptions(const ScenarioOptions& options) {
  RequireNonNegativeSteps(options);
  datasets::GlmbSimOptions o;
  if (options.steps > 0) o.steps = options.steps;
  if (options.detection_probability) o.detection_probability = *options.detection_probability;
  if (options.clutter_rate) o.clutter_rate = *options.clutter_rate;
  ApplySettings(GlmbSimOptionsTable(), options, "glmb-sim", o);
  o.Validate();
  return o;
}

nlohmann::json MrclamCountsJson(const datasets::MrclamCounts& c) {
  return {{"steps", c.steps},
          {"unscored_steps", c.unscored_steps},
          {"landmark_detections", c.landmark_detections},
          {"other_robot_detections", c.other_robot_detections},
          {"unknown_barcode_detections", c.unknown_barcode_detections},
          {"non_landmarks_dropped", c.non_landmarks_dropped},
          {"images_skipped", c.images_skipped},
          {"odometry_out_of_order", c.odometry_out_of_order},
          {"odometry_repeated_times", c.odometry_repeated_times},
          {"truth_out_of_order", c.truth_out_of_order},
          {"truth_repeated_times", c.truth_repeated_times},
          {"detections_out_of_order", c.detections_out_of_order}};
}

ScenarioEntry MrclamEntry() {
  ScenarioEntry e;
  e.name = "mrclam";
  // A 15 m x 8 m room whose landmarks stand in clusters 0.18-0.25 m apart, the clusters 1.7 m or
  // more apart: c = 1 m is about 6 range sigmas (0.175 m), so a landmark mapped from its own
  // detections is localised, and below the distance between clusters, so an estimate in the
  // wrong cluster counts as missed and false rather than as a localisation error.
  e.gospa_c = 1.0;
  e.option_keys = OptionKeys(MrclamOptionsTable());
  e.check_option = OptionCheck(MrclamOptionsTable());
  e.description =
      "UTIAS MRCLAM (Leung et al. 2011): one robot of a sub-dataset, a step per camera image, "
      "commanded odometry, Vicon truth for poses and the 15 landmarks, barcodes as the hidden "
      "association; other robots and misread barcodes are real clutter (datasets/mrclam.h)";
  e.make = [](std::uint64_t seed, const ScenarioOptions& options, ScenarioCache& cache) {
    const datasets::MrclamOptions o = ToMrclamOptions(options);
    return datasets::MakeMrclamScenario(
        cache.Mrclam(datasets::ResolveDataDir(options.data_dir), o.dataset, o.robot), seed, o);
  };
  e.resolved_options = [](const ScenarioOptions& options) {
    const datasets::MrclamOptions o = ToMrclamOptions(options);
    const std::filesystem::path data_dir = datasets::ResolveDataDir(options.data_dir);
    nlohmann::json j = MrclamOptionsTable().ToJson(o);
    j["data_dir"] = data_dir.string();
    j["data_files"] = DataFileChecksums(data_dir, datasets::MrclamDataFiles(o.dataset, o.robot));
    j["steps"] = o.max_steps;
    // What the run is made of: steps, steps without truth, and the detections by kind.
    datasets::MrclamCounts counts;
    (void)datasets::MakeMrclamScenario(datasets::LoadMrclamRobot(data_dir, o.dataset, o.robot), 0,
                                       o, &counts);
    j["counts"] = MrclamCountsJson(counts);
    return j;
  };
  return e;
}

ScenarioEntry GlmbSimEntry() {
  ScenarioEntry e;
  e.name = "glmb-sim";
  e.option_keys = OptionKeys(GlmbSimOptionsTable());
  e.check_option = OptionCheck(GlmbSimOptionsTable());
  e.description =
      "the simulation of the delta-GLMB-SLAM paper (Moratuwage, Adams & Inostroza 2019): 23 "
      "landmarks around a 24.8 m closed loop driven at 1 m/s and revisited (175 steps of 0.2 s), "
      "3 m disc field of view, pD 0.7, Poisson clutter uniform in range-bearing "
      "(datasets/glmb_simulation.h); data per seed or one realisation (data_protocol); no data "
      "files";
  e.uses_data_dir = false;
  e.make = [](std::uint64_t seed, const ScenarioOptions& options, ScenarioCache&) {
    return datasets::MakeGlmbSimScenario(ToGlmbSimOptions(options), seed);
  };
  e.resolved_options = [](const ScenarioOptions& options) {
    const datasets::GlmbSimOptions o = ToGlmbSimOptions(options);
    nlohmann::json j = GlmbSimOptionsTable().ToJson(o);
    j["steps"] = o.steps;
    return j;
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

const datasets::MrclamRobotData& ScenarioCache::Mrclam(const std::filesystem::path& data_dir,
                                                       int dataset, int robot) {
  const std::lock_guard<std::mutex> lock(mutex_);
  auto& slot = mrclam_[{data_dir, dataset, robot}];
  if (!slot) {
    slot = std::make_unique<const datasets::MrclamRobotData>(
        datasets::LoadMrclamRobot(data_dir, dataset, robot));
  }
  return *slot;
}

const std::vector<ScenarioEntry>& ScenarioTable() {
  static const std::vector<ScenarioEntry> table = {
      PaperSyntheticEntry(), VictoriaParkEntry(), GeneratedEntry(),
      ScPhdSimEntry(),       MrclamEntry(),       GlmbSimEntry(),
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

void CheckScenarioOption(const std::string& name, const std::string& key,
                         const nlohmann::json& value) {
  const ScenarioEntry& entry = FindScenario(name);
  if (!entry.check_option) return;
  std::string row = key;
  if (key == "pd" || key == "clutter_rate") {
    row = key == "pd" ? "detection_probability" : key;
    const auto has = [&entry](const std::string& k) {
      for (const ScenarioOptionHelp& h : entry.option_keys) {
        if (h.key == k) return true;
      }
      return false;
    };
    if (!has(row) && has(row + "_max")) row += "_max";
    if (!has(row)) return;
  }
  try {
    entry.check_option(row, value);
  } catch (const std::invalid_argument& e) {
    if (row == key) throw;
    throw std::invalid_argument("scenario option '" + key + "' (" + e.what() + ")");
  }
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
