#include "validation/runner/io/results_io.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <system_error>

namespace phdslam::validation {

std::string FormatNumber(double value) {
  if (!std::isfinite(value)) return "";
  // The text of printf's "%.10g", several times faster than snprintf (whose %g goes through
  // multi-precision arithmetic): the results files hold tens of thousands of numbers per run.
  char buffer[40];
  const auto [end, ec] =
      std::to_chars(buffer, buffer + sizeof(buffer), value, std::chars_format::general, 10);
  if (ec != std::errc()) throw std::logic_error("FormatNumber: 40 bytes are too few");
  return std::string(buffer, end);
}

std::string FormatNumber(const std::optional<double>& value) {
  return value ? FormatNumber(*value) : std::string();
}

std::string FormatInteger(std::int64_t value) { return std::to_string(value); }

std::string CsvRow(const std::vector<std::string>& cells) {
  std::string row;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (cells[i].find_first_of(",\"\n\r") != std::string::npos) {
      throw std::invalid_argument("CSV cell '" + cells[i] + "' contains a comma, quote or newline");
    }
    if (i > 0) row += ',';
    row += cells[i];
  }
  row += '\n';
  return row;
}

std::string JsonFileText(const nlohmann::json& json) {
  return json.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

void WriteFileAtomically(const std::filesystem::path& path,
                         const std::function<void(const std::filesystem::path&)>& writer,
                         std::string_view tag) {
  std::filesystem::path temp = path;
  temp += ".tmp-" + std::string(tag);
  try {
    writer(temp);
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(temp, ignored);
    throw;
  }
  std::error_code ec;
  std::filesystem::rename(temp, path, ec);
  if (ec) {
    const std::string reason = ec.message();  // before remove() overwrites ec
    std::filesystem::remove(temp, ec);
    throw std::runtime_error("cannot rename " + temp.string() + " to " + path.string() + ": " +
                             reason);
  }
}

void WriteFileAtomically(const std::filesystem::path& path, std::string_view content,
                         std::string_view tag) {
  WriteFileAtomically(
      path,
      [&](const std::filesystem::path& temp) {
        std::ofstream out(temp, std::ios::binary | std::ios::trunc);
        if (!out) throw std::runtime_error("cannot open " + temp.string() + " for writing");
        out.write(content.data(), static_cast<std::streamsize>(content.size()));
        out.close();
        if (!out) throw std::runtime_error("error writing " + temp.string());
      },
      tag);
}

std::size_t RemoveLeftoverTemporaries(const std::filesystem::path& folder) {
  std::error_code ec;
  if (!std::filesystem::is_directory(folder, ec)) return 0;
  std::vector<std::filesystem::path> leftovers;
  for (auto it = std::filesystem::recursive_directory_iterator(folder, ec);
       !ec && it != std::filesystem::recursive_directory_iterator(); it.increment(ec)) {
    if (it->is_regular_file(ec) &&
        it->path().filename().string().find(".tmp-") != std::string::npos) {
      leftovers.push_back(it->path());
    }
  }
  std::size_t removed = 0;
  for (const std::filesystem::path& path : leftovers) {
    if (std::filesystem::remove(path, ec)) ++removed;
  }
  return removed;
}

namespace {

// Throws unless `path` names a regular file of at most `max_bytes` bytes.
std::uintmax_t RequireBoundedRegularFile(const std::filesystem::path& path,
                                         std::uintmax_t max_bytes) {
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) {
    throw std::runtime_error("cannot open " + path.string() + " for reading");
  }
  if (!std::filesystem::is_regular_file(status)) {
    throw std::runtime_error(path.string() +
                             ": not a regular file (a device, pipe or folder); give a file");
  }
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) throw std::runtime_error("cannot read the size of " + path.string());
  if (size > max_bytes) {
    throw std::runtime_error(path.string() + ": " + std::to_string(size) +
                             " bytes, more than the " + std::to_string(max_bytes) +
                             " this reader accepts");
  }
  return size;
}

}  // namespace

std::string ReadTextFile(const std::filesystem::path& path, std::uintmax_t max_bytes) {
  const std::uintmax_t size = RequireBoundedRegularFile(path, max_bytes);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open " + path.string() + " for reading");
  std::string content(static_cast<std::size_t>(size), '\0');
  in.read(content.data(), static_cast<std::streamsize>(content.size()));
  if (in.bad()) throw std::runtime_error("error reading " + path.string());
  content.resize(static_cast<std::size_t>(in.gcount()));
  if (in && in.peek() != std::char_traits<char>::eof()) {
    throw std::runtime_error(path.string() + ": grew past " + std::to_string(max_bytes) +
                             " bytes while being read");
  }
  return content;
}

std::optional<std::size_t> CsvTable::FindColumn(std::string_view name) const {
  for (std::size_t i = 0; i < header.size(); ++i) {
    if (header[i] == name) return i;
  }
  return std::nullopt;
}

CsvTable ParseCsv(std::string_view text, const std::string& source) {
  CsvTable table;
  // A byte-order mark (some editors write one) is not part of the first column's name, as the
  // experiment files and the report's reader take it.
  if (text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3);
  std::size_t line_number = 0;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(start, end - start);
    start = end + 1;
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (line.empty() && line_number > 1) continue;
    std::vector<std::string> cells;
    std::size_t cell_start = 0;
    while (true) {
      const std::size_t comma = line.find(',', cell_start);
      cells.emplace_back(line.substr(cell_start, comma - cell_start));
      if (comma == std::string_view::npos) break;
      cell_start = comma + 1;
    }
    if (line_number == 1) {
      table.header = std::move(cells);
    } else if (cells.size() != table.header.size()) {
      throw std::runtime_error(source + ":" + std::to_string(line_number) + ": " +
                               std::to_string(cells.size()) + " cells, the header has " +
                               std::to_string(table.header.size()));
    } else {
      table.rows.push_back(std::move(cells));
    }
  }
  if (table.header.empty() || (table.header.size() == 1 && table.header[0].empty())) {
    throw std::runtime_error(source + ": no header line");
  }
  return table;
}

CsvTable ReadCsvFile(const std::filesystem::path& path) {
  return ParseCsv(ReadTextFile(path), path.string());
}

}  // namespace phdslam::validation
