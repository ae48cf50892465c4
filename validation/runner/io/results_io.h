// Small writers shared by every results file: number formatting, CSV rows and atomic writes.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace phdslam::validation {

/// The text of printf's "%.10g" for a finite value; the empty string for NaN, infinities and
/// nullopt, which the results files use for "not available".
std::string FormatNumber(double value);
std::string FormatNumber(const std::optional<double>& value);
std::string FormatInteger(std::int64_t value);

/// Joins cells with commas and ends the row with '\n'. Cells must not contain commas, quotes or
/// newlines (results files hold numbers and simple names only); throws std::invalid_argument if
/// one does.
std::string CsvRow(const std::vector<std::string>& cells);

/// Writes `content` to `path` atomically: it is written to a temporary name in the same folder
/// (`<name>.tmp-<tag>`) and then renamed over `path`, so a reader never sees a partial file.
/// `tag` distinguishes concurrent writers of the same file. Throws std::runtime_error naming the
/// file on failure.
void WriteFileAtomically(const std::filesystem::path& path, std::string_view content,
                         std::string_view tag = "0");

/// `json` as the text of a results file: two-space indentation, a final newline, and any byte of a
/// string that is not UTF-8 (a path's name, say) replaced by U+FFFD rather than thrown on.
std::string JsonFileText(const nlohmann::json& json);

/// Same, with a writer that fills the temporary file itself (for writers that take a path).
void WriteFileAtomically(const std::filesystem::path& path,
                         const std::function<void(const std::filesystem::path&)>& writer,
                         std::string_view tag = "0");

/// Removes every file under `folder` whose name holds ".tmp-" (what WriteFileAtomically writes
/// before its rename): left only by a process that was killed. Call it only while holding the
/// folder's lock (results_lock.h). Returns how many were removed.
std::size_t RemoveLeftoverTemporaries(const std::filesystem::path& folder);

/// The largest file ReadTextFile reads unless told otherwise (1 GiB).
inline constexpr std::uintmax_t kMaxTextFileBytes = std::uintmax_t{1} << 30;

/// The whole content of a text file; throws std::runtime_error naming the file when it cannot be
/// opened, is not a regular file (a device such as /dev/zero, a pipe, a folder) or is larger than
/// `max_bytes`, so that no reader runs without a bound.
std::string ReadTextFile(const std::filesystem::path& path,
                         std::uintmax_t max_bytes = kMaxTextFileBytes);

/// A CSV file as written by CsvRow: a header line and rows of plain cells.
struct CsvTable {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;

  /// Index of the header cell `name`, or nullopt.
  [[nodiscard]] std::optional<std::size_t> FindColumn(std::string_view name) const;
};

/// Parses CsvRow text (no quoting; a leading UTF-8 byte-order mark is skipped). Throws
/// std::runtime_error naming `source` and the line when the text has no header or a row has
/// another number of cells than the header.
CsvTable ParseCsv(std::string_view text, const std::string& source);

/// ParseCsv of a file's content.
CsvTable ReadCsvFile(const std::filesystem::path& path);

}  // namespace phdslam::validation
