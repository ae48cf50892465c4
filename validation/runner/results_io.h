// Small writers shared by every results file: number formatting, CSV rows and atomic writes.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace phdslam::validation {

/// "%.10g" of a finite value; the empty string for NaN, infinities and nullopt, which the
/// results files use for "not available".
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

/// Same, with a writer that fills the temporary file itself (for writers that take a path).
void WriteFileAtomically(const std::filesystem::path& path,
                         const std::function<void(const std::filesystem::path&)>& writer,
                         std::string_view tag = "0");

/// The whole content of a text file; throws std::runtime_error naming the file.
std::string ReadTextFile(const std::filesystem::path& path);

}  // namespace phdslam::validation
