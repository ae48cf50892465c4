#include "validation/runner/experiment/experiment_keys.h"

#include <cmath>
#include <optional>
#include <utility>

#include "validation/runner/experiment/experiment_assignments.h"
#include "validation/runner/experiment/experiment_file_lists.h"
#include "validation/runner/experiment/yaml_file_values.h"
#include "validation/runner/io/list_arguments.h"

namespace phdslam::validation {
namespace {

using Json = nlohmann::json;

// An integer >= 0 of a file; `zero_means` explains 0 in the message.
int CountFromFile(const YamlKeyValue& v, const std::string& zero_means) {
  const int n = v.Number<int>();
  if (n < 0) v.Fail("expected >= 0 (" + zero_means + ")");
  return n;
}

bool FlagFromFile(const YamlKeyValue& v) {
  const std::string flag = v.Text();
  if (flag != "true" && flag != "false") v.Fail("expected true or false, got '" + flag + "'");
  return flag == "true";
}

Json NumberOrNull(const std::optional<double>& value) { return value ? Json(*value) : Json(); }

std::optional<double> NumberOrNothing(const Json& v) {
  return v.is_null() ? std::nullopt : std::optional<double>(v.get<double>());
}

// --estimator: the named estimators, each with the file's settings when the file lists it.
std::vector<ExperimentEstimator> SelectEstimators(const std::string& names,
                                                  const std::vector<ExperimentEstimator>& in_file) {
  std::vector<ExperimentEstimator> selected;
  for (const std::string& name : ParseNameList(names, "estimator")) {
    ExperimentEstimator e{name};
    for (const ExperimentEstimator& listed : in_file) {
      if (listed.name == name) e = listed;  // keeps the file's `set` and `particles`
    }
    selected.push_back(std::move(e));
  }
  return selected;
}

std::vector<ExperimentKey> Rows() {
  using K = OptionKind;
  return {
      {.file_key = "scenario",
       .option = "--scenario",
       .help = "Scenario name (see `phdslam list`)",
       .required = true,
       .export_option = true,
       .read_file = [](const YamlKeyValue& v, Experiment& x) { x.scenario = v.Text(); },
       .apply_option = [](const Json& v, Experiment& x) { x.scenario = v.get<std::string>(); }},
      {.file_key = "estimators",
       .option = "--estimator",
       .help = "Estimator name, or a comma list of names (see `phdslam list`); with an "
               "experiment file, an estimator it lists keeps its `set` and `particles`",
       .required = true,
       .read_file = [](const YamlKeyValue& v, Experiment& x) { x.estimators = EstimatorList(v); },
       .apply_option =
           [](const Json& v, Experiment& x) {
             x.estimators = SelectEstimators(v.get<std::string>(), x.estimators);
           }},
      {.file_key = "particles",
       .option = "--particles",
       .help = "Particle count (1 to 100000), or a comma list such as 1,10,100",
       .default_text = "1",
       .read_file = [](const YamlKeyValue& v, Experiment& x) { x.particles = ParticleList(v); },
       .apply_option =
           [](const Json& v, Experiment& x) {
             x.particles = ParseParticleList(v.get<std::string>());
           }},
      {.file_key = "seeds",
       .option = "--seeds",
       .help = "Monte Carlo seeds: a range a-b (inclusive), a single seed, or a comma list such "
               "as 1,3,10-12",
       .required = true,
       .export_option = true,
       .read_file = [](const YamlKeyValue& v, Experiment& x) { x.seeds = SeedList(v); },
       .apply_option = [](const Json& v,
                          Experiment& x) { x.seeds = ParseSeedList(v.get<std::string>()); }},
      {.file_key = "steps",
       .option = "--steps",
       .manifest_key = "steps",
       .kind = K::kCount,
       .help = "Use only the first N filter steps of the scenario (0 = all)",
       .default_text = "0",
       .export_option = true,
       .read_file = [](const YamlKeyValue& v,
                       Experiment& x) { x.steps = CountFromFile(v, "0 = all"); },
       .apply_option = [](const Json& v, Experiment& x) { x.steps = v.get<int>(); },
       .write_manifest = [](const Experiment& x) { return Json(x.steps); },
       .read_manifest = [](const Json& v, Experiment& x) { x.steps = v.get<int>(); }},
      {.file_key = "jobs",
       .option = "--jobs",
       .kind = K::kCount,
       .help = "Worker threads (0 = one per hardware thread); results do not depend on it",
       .default_text = "0",
       .read_file = [](const YamlKeyValue& v,
                       Experiment& x) { x.jobs = CountFromFile(v, "0 = one per hardware thread"); },
       .apply_option = [](const Json& v, Experiment& x) { x.jobs = v.get<int>(); }},
      {.file_key = "name",
       .option = "--experiment-name",
       .help = "Experiment name, part of every estimator's random stream seed (default: the "
               "experiment file's name, else 'default')",
       .default_text = "default",
       .read_file =
           [](const YamlKeyValue& v, Experiment& x) {
             x.name = v.Text();
             if (x.name.empty()) v.errors.Fail(v.node, "'" + v.key + "' is empty");
           },
       .apply_option = [](const Json& v, Experiment& x) { x.name = v.get<std::string>(); }},
      {.option = "--pd",
       .manifest_key = "pd",
       .kind = K::kNumber,
       .help = "Override the scenario's detection probability (0, 1]; as scenario option pd",
       .export_option = true,
       .apply_option =
           [](const Json& v, Experiment& x) {
             x.pd = CheckedScenarioNumber(x, "--pd", kSweepParameterPd, v.get<double>());
           },
       .write_manifest = [](const Experiment& x) { return NumberOrNull(x.pd); },
       .read_manifest = [](const Json& v, Experiment& x) { x.pd = NumberOrNothing(v); }},
      {.option = "--clutter-rate",
       .manifest_key = "clutter_rate",
       .kind = K::kNumber,
       .help = "Override the scenario's mean clutter count per scan (0 to 1000); as scenario "
               "option clutter_rate",
       .export_option = true,
       .apply_option =
           [](const Json& v, Experiment& x) {
             x.clutter_rate = CheckedScenarioNumber(x, "--clutter-rate", kSweepParameterClutterRate,
                                                    v.get<double>());
           },
       .write_manifest = [](const Experiment& x) { return NumberOrNull(x.clutter_rate); },
       .read_manifest = [](const Json& v, Experiment& x) { x.clutter_rate = NumberOrNothing(v); }},
      {.option = "--data-dir",
       .help = "Data sets folder (default: $PHDSLAM_DATA, else the folder compiled in)",
       .export_option = true,
       .machine_setting = true,
       .apply_option = [](const Json& v, Experiment& x) { x.data_dir = v.get<std::string>(); }},
      {.option = "--set",
       .kind = K::kRepeated,
       .help = "Estimator parameter override [estimator:]key=value (repeatable; dotted keys reach "
               "nested parameters; the value is JSON when it parses, else a string)",
       .apply_option =
           [](const Json& v, Experiment& x) {
             ApplyParameterAssignments(v.get<std::vector<std::string>>(), x);
           }},
      {.file_key = "scenario_options",
       .option = "--scenario-set",
       .manifest_key = "settings",
       .kind = K::kRepeated,
       .help = "Scenario option key=value (repeatable; the keys of each scenario are listed by "
               "`phdslam list`; pd and clutter_rate as --pd and --clutter-rate; the value is "
               "JSON when it parses, else a string)",
       .export_option = true,
       .read_file = [](const YamlKeyValue& v, Experiment& x) { ReadScenarioOptions(v, x); },
       .apply_option =
           [](const Json& v, Experiment& x) {
             ApplyScenarioAssignments(v.get<std::vector<std::string>>(), x);
           },
       .write_manifest = [](const Experiment& x) { return x.scenario_settings; },
       .read_manifest = [](const Json& v, Experiment& x) { x.scenario_settings = v; }},
      {.file_key = "map_ospa",
       .option = "--map-ospa",
       .kind = K::kFlag,
       .help = "Also write the map OSPA (p = 1, c = 5 m unless --map-ospa-cutoff) after every "
               "step, against the true landmarks detected so far, as the last steps.csv column "
               "map_ospa_m (online estimators on scenarios with a true map)",
       .read_file = [](const YamlKeyValue& v, Experiment& x) { x.map_ospa = FlagFromFile(v); },
       .apply_option = [](const Json& v, Experiment& x) { x.map_ospa = v.get<bool>(); }},
      {.file_key = "map_ospa_cutoff",
       .option = "--map-ospa-cutoff",
       .kind = K::kPositiveNumber,
       .help = "Cut-off c (m, > 0) of the per-step map OSPA; implies --map-ospa (default 5)",
       .read_file =
           [](const YamlKeyValue& v, Experiment& x) {
             const double c = v.Number<double>();
             if (!(c > 0.0) || !std::isfinite(c)) v.Fail("expected a finite number > 0 (m)");
             x.map_ospa_cutoff = c;
           },
       .apply_option = [](const Json& v, Experiment& x) { x.map_ospa_cutoff = v.get<double>(); }},
      {.file_key = "sweep",
       .read_file = [](const YamlKeyValue& v, Experiment& x) { x.sweep = ReadSweep(v, x); }},
  };
}

}  // namespace

const std::vector<ExperimentKey>& ExperimentKeys() {
  static const std::vector<ExperimentKey> keys = Rows();
  return keys;
}

const ExperimentKey* FindExperimentOption(const std::string& option) {
  for (const ExperimentKey& key : ExperimentKeys()) {
    if (!key.option.empty() && key.option == option) return &key;
  }
  return nullptr;
}

}  // namespace phdslam::validation
