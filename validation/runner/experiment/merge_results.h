// Merging results folders (shards of one experiment, or runs of one experiment made on different
// machines) into one folder whose summary.csv and runs.csv equal those of a single-machine run.
#pragma once

#include <cstddef>
#include <filesystem>
#include <vector>

namespace phdslam::validation {

struct MergeReport {
  std::size_t runs_copied = 0;           ///< finished runs copied (or hard-linked) into the output
  std::size_t runs_already_present = 0;  ///< finished runs the output (or an earlier input) had
  std::size_t failed_runs_copied = 0;    ///< error.json of runs no input finished
  std::size_t folders = 0;               ///< results folders written (one, or one per sweep value)
};

/// Merges `inputs` into `out` (created if needed; results it already holds are kept), all or
/// nothing: the merged folder is staged beside `out` (.<name>.merge-staging, made of hard links
/// to `out`'s files where the file system allows them) and takes `out`'s place only when it is
/// complete, so that a merge that fails leaves `out` as it was (or absent when it was new). Each
/// input is a results folder (with config.json) or the root of a sweep (with sweep.json), not a
/// mix of both kinds. Before anything is staged it throws std::invalid_argument when an input is
/// missing, is `out`, or was made with settings that conflict with the others' (experiment,
/// scenario, scenario options, metric settings or resolved parameters, as for resuming), or when
/// a run present in two places has different metrics.json (timing keys aside), and
/// std::runtime_error naming the input's file when a file cannot be read or is damaged (every
/// metrics.json, error.json and steps.csv of every input is read first, results_check.h: a
/// truncated file, a steps.csv cut short, an unknown format_version). Finished runs are hard-linked
/// when possible and copied otherwise; a failed run's error.json is copied only when no input
/// finished that run; truth files are copied when absent. The staged folder gets config.json (the
/// union of the configs), summary.csv, runs.csv and timing.json ({"merged_from", counts, host,
/// time}); for sweeps, every sweep folder and then sweep.csv and sweep.json.
MergeReport MergeResults(const std::filesystem::path& out,
                         const std::vector<std::filesystem::path>& inputs);

}  // namespace phdslam::validation
