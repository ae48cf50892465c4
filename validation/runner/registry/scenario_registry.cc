#include "validation/runner/registry/scenario_registry.h"

#include <stdexcept>

#include "datasets/data_dir.h"
#include "datasets/glmb_simulation.h"
#include "datasets/scenario_check.h"
#include "datasets/scenario_generator.h"
#include "datasets/scphd_simulation.h"
#include "validation/runner/registry/scenario_option_tables.h"
#include "validation/runner/registry/scenario_shorthands.h"
#include "validation/runner/registry/scenario_spec.h"

namespace phdslam::validation {
namespace {

// The synthetic scenario's file comes from the data folder when it holds it, else from the copy
// the repository carries (datasets/data): a clone runs it without any data folder.
std::filesystem::path PaperSyntheticDataDir(const ScenarioOptions& options) {
  return datasets::ResolveDataDirFor(options.data_dir, datasets::PaperSyntheticDataFiles());
}

std::filesystem::path DataFolder(const ScenarioOptions& options) {
  return datasets::ResolveDataDir(options.data_dir);
}

ScenarioEntry PaperSyntheticEntry() {
  using O = datasets::SyntheticOptions;
  return EntryFromSpec<O>({
      .name = "paper-synthetic",
      .description = "the paper's synthetic scenario (Environment_SLAM.mat: 160 landmarks, 4000 "
                     "steps of 1 s); truth poses and map; measurements drawn per seed",
      .options_table = &PaperSyntheticOptionsTable(),
      .steps = &O::steps,
      .step_limit = StepLimit::kZeroIsAll,
      .data_dir = PaperSyntheticDataDir,
      .data_files = [](const std::filesystem::path&,
                       const O&) { return datasets::PaperSyntheticDataFiles(); },
      .make =
          [](const O& o, std::uint64_t seed, const std::filesystem::path& data_dir,
             ScenarioCache& cache) {
            return datasets::MakePaperSyntheticScenario(cache.PaperSynthetic(data_dir), seed, o);
          },
  });
}

ScenarioEntry VictoriaParkEntry() {
  using O = datasets::VictoriaParkOptions;
  return EntryFromSpec<O>({
      .name = "victoria-park",
      .description = "ACFR Victoria Park: tree detections, car odometry, GPS as the only truth; "
                     "artificial clutter drawn per seed",
      .options_table = &VictoriaParkOptionsTable(),
      .steps = &O::max_steps,
      .step_limit = StepLimit::kZeroIsAll,
      // pD at zero range and the nominal pD of the estimate threshold alike.
      .shorthand_rows = {{"pd", {"detection_probability_max", "detection_probability_nominal"}},
                         {"clutter_rate", {"clutter_rate"}}},
      .data_dir = DataFolder,
      .data_files = [](const std::filesystem::path& data_dir,
                       const O&) { return datasets::VictoriaParkDataFiles(data_dir); },
      .make =
          [](const O& o, std::uint64_t seed, const std::filesystem::path& data_dir,
             ScenarioCache& cache) {
            return datasets::MakeVictoriaParkScenario(cache.VictoriaPark(data_dir), seed, o);
          },
  });
}

ScenarioEntry GeneratedEntry() {
  using O = datasets::GeneratorOptions;
  return EntryFromSpec<O>({
      .name = "generated",
      .description = "a generated scenario of the paper's kind (100 landmarks along a smooth "
                     "1000-step path; map and measurements drawn per seed); no data files",
      .options_table = &GeneratedOptionsTable(),
      .steps = &O::steps,
      .make = [](const O& o, std::uint64_t seed, const std::filesystem::path&,
                 ScenarioCache&) { return datasets::GenerateScenario(o, seed); },
  });
}

ScenarioEntry ScPhdSimEntry() {
  using O = datasets::ScPhdSimOptions;
  return EntryFromSpec<O>({
      .name = "scphd-sim",
      .description =
          "the simulation of single-cluster PHD SLAM's paper (Lee, Clark & Salvi 2012): Ackermann "
          "vehicle, two laps of a 40 m circle among 60 fixed landmarks, 838 steps of 0.2 s; "
          "odometry and measurements drawn per seed (datasets/scphd_simulation.h); no data files",
      .options_table = &ScPhdSimOptionsTable(),
      .steps = &O::steps,
      .make = [](const O& o, std::uint64_t seed, const std::filesystem::path&,
                 ScenarioCache&) { return datasets::MakeScPhdSimScenario(o, seed); },
  });
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

// What a MRCLAM run is made of: steps, steps without truth, and the detections by kind.
void DescribeMrclamRun(const datasets::MrclamOptions& o, const std::filesystem::path& data_dir,
                       nlohmann::json& j) {
  datasets::MrclamCounts counts;
  (void)datasets::MakeMrclamScenario(datasets::LoadMrclamRobot(data_dir, o.dataset, o.robot), 0, o,
                                     &counts);
  j["counts"] = MrclamCountsJson(counts);
}

ScenarioEntry MrclamEntry() {
  using O = datasets::MrclamOptions;
  return EntryFromSpec<O>({
      .name = "mrclam",
      .description =
          "UTIAS MRCLAM (Leung et al. 2011): one robot of a sub-dataset, a step per camera image, "
          "commanded odometry, Vicon truth for poses and the 15 landmarks, barcodes as the hidden "
          "association; other robots and misread barcodes are real clutter (datasets/mrclam.h)",
      .options_table = &MrclamOptionsTable(),
      .steps = &O::max_steps,
      .step_limit = StepLimit::kZeroIsAll,
      .data_dir = DataFolder,
      .data_files = [](const std::filesystem::path&,
                       const O& o) { return datasets::MrclamDataFiles(o.dataset, o.robot); },
      .make =
          [](const O& o, std::uint64_t seed, const std::filesystem::path& data_dir,
             ScenarioCache& cache) {
            return datasets::MakeMrclamScenario(cache.Mrclam(data_dir, o.dataset, o.robot), seed,
                                                o);
          },
      .describe_data = DescribeMrclamRun,
      // A 15 m x 8 m room whose landmarks stand in clusters 0.18-0.25 m apart, the clusters 1.7 m
      // or more apart: c = 1 m is about 6 range sigmas (0.175 m), so a landmark mapped from its
      // own detections is localised, and below the distance between clusters, so an estimate in
      // the wrong cluster counts as missed and false rather than as a localisation error.
      .gospa_c = 1.0,
  });
}

ScenarioEntry GlmbSimEntry() {
  using O = datasets::GlmbSimOptions;
  return EntryFromSpec<O>({
      .name = "glmb-sim",
      .description =
          "the simulation of the delta-GLMB-SLAM paper (Moratuwage, Adams & Inostroza 2019): 23 "
          "landmarks around a 24.8 m closed loop driven at 1 m/s and revisited (175 steps of 0.2 "
          "s), 3 m disc field of view, pD 0.7, Poisson clutter uniform in range-bearing "
          "(datasets/glmb_simulation.h); data per seed or one realisation (data_protocol); no "
          "data files",
      .options_table = &GlmbSimOptionsTable(),
      .steps = &O::steps,
      .make = [](const O& o, std::uint64_t seed, const std::filesystem::path&,
                 ScenarioCache&) { return datasets::MakeGlmbSimScenario(o, seed); },
  });
}

}  // namespace

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
  if (FindScenarioShorthand(key) == nullptr) {
    entry.check_option(key, value);
    return;
  }
  for (const std::string& row : ShorthandRows(entry, key)) {
    try {
      entry.check_option(row, value);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("scenario option '" + key + "' (" + e.what() + ")");
    }
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
