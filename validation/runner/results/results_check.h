// A check of every run file of a results folder, as the summary reads them, for the commands that
// place another folder's files into a results folder (merge): a damaged input is refused, naming
// its file, before anything is copied.
#pragma once

#include <filesystem>

namespace phdslam::validation {

/// Reads every metrics.json (a JSON object of a known format_version with the required fields)
/// and error.json of `folder`'s runs, and every finished run's steps.csv: each line holds as many
/// cells as the header and there is one row per step of metrics.json's "steps". Throws
/// std::runtime_error "<file>[:<line>]: ..." on the first damaged file.
void CheckResultsFolder(const std::filesystem::path& folder);

}  // namespace phdslam::validation
