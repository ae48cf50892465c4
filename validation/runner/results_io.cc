#include "validation/runner/results_io.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <system_error>

namespace phdslam::validation {

std::string FormatNumber(double value) {
  if (!std::isfinite(value)) return "";
  char buffer[40];
  const int n = std::snprintf(buffer, sizeof(buffer), "%.10g", value);
  return std::string(buffer, static_cast<std::size_t>(n));
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
    std::filesystem::remove(temp, ec);
    throw std::runtime_error("cannot rename " + temp.string() + " to " + path.string() + ": " +
                             ec.message());
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

std::string ReadTextFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open " + path.string() + " for reading");
  std::ostringstream content;
  content << in.rdbuf();
  if (in.bad()) throw std::runtime_error("error reading " + path.string());
  return content.str();
}

}  // namespace phdslam::validation
