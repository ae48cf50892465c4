// Test helpers: results files with their timing columns and keys removed, for comparing results
// of different invocations (only timing may differ).
#pragma once

#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace phdslam::validation::testing {

inline std::vector<std::string> SplitLines(const std::string& text) {
  std::vector<std::string> lines;
  std::stringstream in(text);
  std::string line;
  while (std::getline(in, line)) lines.push_back(line);
  return lines;
}

inline std::vector<std::string> SplitCells(const std::string& line) {
  std::vector<std::string> cells;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    cells.push_back(line.substr(start, comma - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return cells;
}

/// The CSV text without its timing columns ("ms" and "ms_*").
inline std::string WithoutTimingColumns(const std::string& csv) {
  const std::vector<std::string> lines = SplitLines(csv);
  if (lines.empty()) return "";
  const std::vector<std::string> header = SplitCells(lines[0]);
  std::string out;
  for (const std::string& line : lines) {
    const std::vector<std::string> cells = SplitCells(line);
    for (std::size_t i = 0; i < cells.size() && i < header.size(); ++i) {
      if (header[i] == "ms" || header[i].rfind("ms_", 0) == 0) continue;
      out += cells[i] + ",";
    }
    out += "\n";
  }
  return out;
}

/// The JSON object without its "ms_*" keys.
inline nlohmann::json WithoutTimingKeys(nlohmann::json j) {
  for (auto it = j.begin(); it != j.end();) {
    it = it.key().rfind("ms_", 0) == 0 ? j.erase(it) : std::next(it);
  }
  return j;
}

}  // namespace phdslam::validation::testing
