#include "validation/runner/experiment/merge_results.h"

#include <unistd.h>

#include <chrono>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>

#include "validation/runner/evaluation/run_metrics.h"
#include "validation/runner/experiment/sweep.h"
#include "validation/runner/io/results_io.h"
#include "validation/runner/io/results_layout.h"
#include "validation/runner/results/results_check.h"
#include "validation/runner/results/results_config.h"
#include "validation/runner/results/results_lock.h"
#include "validation/runner/results/summary.h"

namespace phdslam::validation {
namespace {

namespace fs = std::filesystem;

// A run folder relative to a results folder: runs/<group>/seed-<s>.
using RunKey = fs::path;

struct RunSource {
  fs::path folder;       ///< absolute run folder in an input
  bool finished = true;  ///< metrics.json present; otherwise error.json only
};

// The results of a metrics.json: without the timing keys (ms_*), which differ between runs,
// without format_version, and without the keys that hold null ("none"), so that a run written
// by an earlier format version (version 1 without format_version, version 2 without
// relocalisations: keys added since, which read as none) and the same run written now compare
// equal.
nlohmann::json ResultsOf(nlohmann::json metrics) {
  for (auto it = metrics.begin(); it != metrics.end();) {
    const bool drop = it.key().rfind("ms_", 0) == 0 || it->is_null();
    it = drop ? metrics.erase(it) : std::next(it);
  }
  metrics.erase(kFormatVersionKey);
  return metrics;
}

// Finished and failed run folders of a results folder, by key.
std::map<RunKey, RunSource> ListRuns(const fs::path& results) {
  std::map<RunKey, RunSource> runs;
  const fs::path runs_dir = results / kRunsFolder;
  if (!fs::is_directory(runs_dir)) return runs;
  for (const auto& group : fs::directory_iterator(runs_dir)) {
    if (!group.is_directory()) continue;
    for (const auto& run : fs::directory_iterator(group.path())) {
      if (!run.is_directory()) continue;
      const RunKey key = fs::path(kRunsFolder) / group.path().filename() / run.path().filename();
      if (fs::exists(run.path() / kMetricsFile)) {
        runs[key] = {run.path(), true};
      } else if (fs::exists(run.path() / kErrorFile)) {
        runs[key] = {run.path(), false};
      }
    }
  }
  return runs;
}

bool IsTemporary(const fs::path& file) {
  return file.filename().string().find(".tmp-") != std::string::npos;
}

// Places `source` at `target` atomically: a hard link when the file system allows one (results
// files are never modified in place, only replaced by rename), else a copy.
void LinkOrCopy(const fs::path& source, const fs::path& target) {
  fs::path temp = target;
  temp += ".tmp-merge";
  std::error_code ec;
  fs::remove(temp, ec);
  fs::create_hard_link(source, temp, ec);
  if (ec) {
    fs::copy_file(source, temp, fs::copy_options::overwrite_existing, ec);
    if (ec) {
      throw std::runtime_error("cannot copy " + source.string() + " to " + temp.string() + ": " +
                               ec.message());
    }
  }
  fs::rename(temp, target, ec);
  if (ec) {
    fs::remove(temp, ec);
    throw std::runtime_error("cannot rename " + temp.string() + " to " + target.string());
  }
}

void CopyFinishedRun(const fs::path& source, const fs::path& target) {
  fs::create_directories(target);
  for (const auto& file : fs::directory_iterator(source)) {
    if (!file.is_regular_file() || IsTemporary(file.path())) continue;
    const fs::path name = file.path().filename();
    if (name == kMetricsFile || name == kErrorFile) continue;
    LinkOrCopy(file.path(), target / name);
  }
  std::error_code ignored;
  fs::remove(target / kErrorFile, ignored);
  LinkOrCopy(source / kMetricsFile, target / kMetricsFile);
}

void CopyTruthFiles(const fs::path& input, const fs::path& out) {
  if (fs::exists(input / kTruthMapFile) && !fs::exists(out / kTruthMapFile)) {
    LinkOrCopy(input / kTruthMapFile, out / kTruthMapFile);
  }
  const fs::path truth = input / kTruthFolder;
  if (!fs::is_directory(truth)) return;
  for (const auto& seed : fs::directory_iterator(truth)) {
    for (const char* name : {kTruthTrajectoryFile, kTruthMapFile, kTruthGpsFile}) {
      const fs::path file = seed.path() / name;
      const fs::path target = out / kTruthFolder / seed.path().filename() / name;
      if (!fs::exists(file) || fs::exists(target)) continue;
      fs::create_directories(target.parent_path());
      LinkOrCopy(file, target);
    }
  }
}

// `folder` as the real folder it names (a link to a folder resolved), without a trailing
// separator, so that its filename names it.
fs::path Named(const fs::path& folder) {
  const fs::path normal = fs::weakly_canonical(fs::absolute(folder));
  return normal.has_filename() ? normal : normal.parent_path();
}

// A folder beside `out` (on its file system, so that moving it is a rename): where the merge
// is staged, or where `out` is moved while the staged folder takes its place.
fs::path Beside(const fs::path& out, const std::string& role) {
  const fs::path named = Named(out);
  return named.parent_path() / ("." + named.filename().string() + "." + role);
}

// `to` becomes a copy of `from` made of hard links where the file system allows them (results
// files are only ever replaced by rename, never changed in place, so the links leave `from`
// as it was). The lock file is linked too, so that the staged folder is locked as soon as it
// takes `from`'s place; temporary files of interrupted writes are left out.
void MirrorFolder(const fs::path& from, const fs::path& to) {
  fs::create_directories(to);
  for (auto it = fs::recursive_directory_iterator(from); it != fs::recursive_directory_iterator();
       ++it) {
    const fs::path target = to / fs::relative(it->path(), from);
    if (it->is_directory()) {
      fs::create_directories(target);
    } else if (it->path().filename() == kLockFile) {
      std::error_code unlinked;  // without hard links the swap is only briefly unlocked
      fs::create_hard_link(it->path(), target, unlinked);
    } else if (it->is_regular_file() && !IsTemporary(it->path())) {
      LinkOrCopy(it->path(), target);
    }
  }
}

// Puts the complete `staged` folder in the place of `out` (two renames); on failure `out` is
// put back as it was.
void ReplaceFolder(const fs::path& staged, const fs::path& out) {
  const fs::path previous = Beside(out, "merge-previous");
  fs::remove_all(previous);
  fs::rename(Named(out), previous);
  std::error_code ec;
  fs::rename(staged, Named(out), ec);
  if (ec) {
    std::error_code restored;
    fs::rename(previous, Named(out), restored);
    throw std::runtime_error("merge: cannot move " + staged.string() + " to " + out.string() +
                             ": " + ec.message());
  }
  fs::remove_all(previous, ec);
}

// `root`, or its sweep folder `name` (empty: the root itself).
fs::path Under(const fs::path& root, const fs::path& name) {
  return name.empty() ? root : root / name;
}

void RequireDistinct(const fs::path& out, const fs::path& input) {
  if (!fs::exists(input)) throw std::invalid_argument("merge: " + input.string() + " not found");
  std::error_code ec;
  if (fs::exists(out) && fs::equivalent(out, input, ec)) {
    throw std::invalid_argument("merge: the output folder " + out.string() +
                                " is also an input; give a new --out");
  }
}

// The plan of one results folder's merge, checked before anything is written.
struct FolderMerge {
  nlohmann::json config;
  std::map<RunKey, RunSource> copies;  ///< runs to copy, by key
  std::size_t already_present = 0;
};

FolderMerge PlanFolderMerge(const fs::path& out, const std::vector<fs::path>& inputs) {
  FolderMerge plan;
  std::string config_source;
  if (fs::exists(out / kConfigFile)) {
    plan.config = ReadJsonObject(out / kConfigFile);
    config_source = out.string();
  }
  for (const fs::path& input : inputs) {
    const fs::path path = input / kConfigFile;
    if (!fs::exists(path)) {
      throw std::invalid_argument("merge: " + input.string() +
                                  " is not a results folder (no config.json)");
    }
    const nlohmann::json config = ReadJsonObject(path);
    if (plan.config.is_null()) {
      plan.config = config;
      config_source = input.string();
      continue;
    }
    const std::string conflict = ConfigConflict(plan.config, config, path.string());
    if (!conflict.empty()) {
      throw std::invalid_argument("merge: " + input.string() +
                                  " was made with other settings than " + config_source + ": " +
                                  conflict);
    }
    plan.config = UnionConfig(plan.config, config);
  }
  // Runs: the output's own, then each input's in order.
  std::map<RunKey, RunSource> present = ListRuns(out);
  std::set<RunKey> counted;
  for (const fs::path& input : inputs) {
    for (const auto& [key, source] : ListRuns(input)) {
      auto it = present.find(key);
      if (it == present.end()) {
        present[key] = source;
        plan.copies[key] = source;
        continue;
      }
      if (!source.finished) continue;  // a finished or failed run is already there
      if (!it->second.finished) {      // a finished run replaces a failure
        it->second = source;
        plan.copies[key] = source;
        continue;
      }
      const fs::path a = it->second.folder / kMetricsFile;
      const fs::path b = source.folder / kMetricsFile;
      if (ResultsOf(ReadJsonObject(a)) != ResultsOf(ReadJsonObject(b))) {
        throw std::invalid_argument("merge: " + a.string() + " and " + b.string() +
                                    " hold different results for the same run (other program "
                                    "builds?); remove one of them");
      }
      if (!plan.copies.contains(key) && counted.insert(key).second) ++plan.already_present;
    }
  }
  return plan;
}

void ExecuteFolderMerge(const fs::path& out, const std::vector<fs::path>& inputs,
                        const FolderMerge& plan, MergeReport& report) {
  fs::create_directories(out);
  for (const auto& [key, source] : plan.copies) {
    const fs::path target = out / key;
    if (source.finished) {
      CopyFinishedRun(source.folder, target);
      ++report.runs_copied;
    } else {
      fs::create_directories(target);
      LinkOrCopy(source.folder / kErrorFile, target / kErrorFile);
      ++report.failed_runs_copied;
    }
  }
  report.runs_already_present += plan.already_present;
  for (const fs::path& input : inputs) CopyTruthFiles(input, out);
  WriteFileAtomically(out / kConfigFile, JsonFileText(plan.config));
  WriteSummaryFiles(out);
  ++report.folders;
}

// True when two sweeps have the same parameters and values (numbers compared by value).
bool SameSweep(const std::vector<ExperimentSweep>& a, const std::vector<ExperimentSweep>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i].parameter != b[i].parameter || a[i].values.size() != b[i].values.size()) return false;
    for (std::size_t k = 0; k < a[i].values.size(); ++k) {
      const nlohmann::json& x = a[i].values[k];
      const nlohmann::json& y = b[i].values[k];
      const bool numbers = x.is_number() && y.is_number();
      if (numbers ? x.get<double>() != y.get<double>() : x != y) return false;
    }
  }
  return true;
}

// Every run file of the inputs (and of the output's own runs) read as the summary will read them,
// so that a damaged input is refused, naming its file, before anything is copied.
void CheckEveryFile(const fs::path& out, const std::vector<fs::path>& inputs) {
  for (const fs::path& input : inputs) CheckResultsFolder(input);
  if (fs::exists(out)) CheckResultsFolder(out);
}

nlohmann::json TimingJson(const std::string& started_utc,
                          std::chrono::steady_clock::time_point start,
                          const std::vector<fs::path>& inputs, const MergeReport& report) {
  std::vector<std::string> sources;
  sources.reserve(inputs.size());
  for (const fs::path& input : inputs) sources.push_back(input.string());
  char host[256] = {};
  if (gethostname(host, sizeof(host) - 1) != 0) host[0] = '\0';
  return {{"started_utc", started_utc},
          {"wall_seconds",
           std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()},
          {"host", std::string(host)},
          {"merged_from", sources},
          {"runs_copied", report.runs_copied},
          {"runs_already_present", report.runs_already_present},
          {"failed_runs_copied", report.failed_runs_copied}};
}

void WriteTimingFiles(const fs::path& root,
                      const std::vector<std::pair<fs::path, std::vector<fs::path>>>& folders,
                      const nlohmann::json& timing) {
  for (const auto& [name, unused] : folders) {
    WriteFileAtomically(Under(root, name) / kTimingFile, JsonFileText(timing));
  }
}

MergeReport MergeInto(const fs::path& out, const std::vector<fs::path>& inputs) {
  const auto start = std::chrono::steady_clock::now();
  const std::string started_utc = UtcNow();
  if (inputs.empty()) throw std::invalid_argument("merge: no input folder given");
  for (const fs::path& input : inputs) RequireDistinct(out, input);
  const ResultsLock lock(out);
  MergeReport report;

  const std::vector<ExperimentSweep> first_sweep = ReadSweepFile(inputs.front());
  // (sweep folder name, empty for the root; its inputs)
  std::vector<std::pair<fs::path, std::vector<fs::path>>> folders;
  if (!first_sweep.empty()) {
    for (const fs::path& input : inputs) {
      const std::vector<ExperimentSweep> sweep = ReadSweepFile(input);
      if (sweep.empty()) {
        throw std::invalid_argument("merge: " + inputs.front().string() + " is a sweep but " +
                                    input.string() + " is not (no sweep.json)");
      }
      if (!SameSweep(sweep, first_sweep)) {
        throw std::invalid_argument("merge: " + input.string() + " sweeps other values than " +
                                    inputs.front().string());
      }
    }
    if (const std::vector<ExperimentSweep> existing = ReadSweepFile(out);
        !existing.empty() && !SameSweep(existing, first_sweep)) {
      throw std::invalid_argument("merge: " + out.string() + " sweeps other values");
    }
    for (const SweepPoint& point : SweepPoints(first_sweep)) {
      const std::string name = SweepFolderName(first_sweep, point);
      std::vector<fs::path> sub;
      for (const fs::path& input : inputs) {
        if (fs::exists(input / name / kConfigFile)) sub.push_back(input / name);
      }
      if (!sub.empty()) folders.emplace_back(name, std::move(sub));
    }
  } else {
    for (const fs::path& input : inputs) {
      if (!ReadSweepFile(input).empty()) {
        throw std::invalid_argument("merge: " + input.string() + " is a sweep but " +
                                    inputs.front().string() + " is not");
      }
    }
    folders.emplace_back(fs::path(), inputs);
  }

  std::vector<FolderMerge> plans;
  plans.reserve(folders.size());
  for (const auto& [name, sources] : folders) {
    plans.push_back(PlanFolderMerge(Under(out, name), sources));
  }
  for (const auto& [name, sources] : folders) CheckEveryFile(Under(out, name), sources);

  // All or nothing: the merged folder is built beside `out` (its own files linked in, the
  // inputs' runs added, the summaries written) and only then takes its place.
  const fs::path staged = Beside(out, "merge-staging");
  fs::remove_all(staged);  // left by a merge that was killed; `out` is locked, so none is running
  try {
    MirrorFolder(out, staged);
    for (std::size_t i = 0; i < folders.size(); ++i) {
      ExecuteFolderMerge(Under(staged, folders[i].first), folders[i].second, plans[i], report);
    }
    if (!first_sweep.empty()) WriteSweepFiles(staged, first_sweep);
    WriteTimingFiles(staged, folders, TimingJson(started_utc, start, inputs, report));
    ReplaceFolder(staged, out);
  } catch (...) {
    std::error_code ignored;
    fs::remove_all(staged, ignored);
    throw;
  }
  return report;
}

}  // namespace

MergeReport MergeResults(const fs::path& out, const std::vector<fs::path>& inputs) {
  std::error_code ec;
  const bool new_folder = !fs::exists(out, ec);
  try {
    return MergeInto(out, inputs);
  } catch (...) {
    // A folder this merge created holds nothing but its lock file (the merge was staged beside
    // it): remove it, so that a failed merge into a new folder leaves none.
    if (new_folder) fs::remove_all(out, ec);
    throw;
  }
}

}  // namespace phdslam::validation
