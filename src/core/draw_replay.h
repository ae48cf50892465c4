// Replayed random draws: a recorded sequence of the uniforms and standard normals a particle
// filter consumes, each tagged by step, particle, purpose and index, served in place of a seeded
// RandomStream. With the draws another implementation made (reference/authors/ records those of
// the authors' PHD-SLAM release), two filters run on the same random numbers and can be compared
// step by step. Each draw is checked against the tag the filter asks for, so a filter that
// consumes draws in another order or number (e.g. resamples at another step) stops with an error
// naming the draw instead of silently using the wrong number.
#pragma once

#include <cstddef>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace phdslam {

/// What a draw is used for.
enum class DrawPurpose {
  kComponent,  ///< the uniform that picks a proposal component, one per particle and step
  kPose,       ///< the standard normals of the pose draw, three per particle and step
  kResample,   ///< the uniforms of the stratified resampling walk (particle = slot)
};

inline const char* DrawPurposeName(DrawPurpose p) {
  switch (p) {
    case DrawPurpose::kComponent:
      return "component";
    case DrawPurpose::kPose:
      return "pose";
    case DrawPurpose::kResample:
      return "resample";
  }
  return "?";
}

struct RecordedDraw {
  int step = 0;
  int particle = 0;
  DrawPurpose purpose = DrawPurpose::kComponent;
  int index = 0;
  double value = 0.0;
};

class DrawReplay {
 public:
  explicit DrawReplay(std::vector<RecordedDraw> draws, std::string source = "draws")
      : draws_(std::move(draws)), source_(std::move(source)) {}

  /// Reads `step,particle,purpose,index,value` rows (header line first; purpose as named by
  /// DrawPurposeName). Throws std::runtime_error naming the file and line of a malformed row.
  static DrawReplay ReadCsv(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path + ": cannot read the draws file");
    std::string line;
    if (!std::getline(in, line) || line.rfind("step,particle,purpose,index,value", 0) != 0) {
      throw std::runtime_error(path + ":1: expected the header step,particle,purpose,index,value");
    }
    std::vector<RecordedDraw> draws;
    int line_no = 1;
    while (std::getline(in, line)) {
      ++line_no;
      if (line.empty()) continue;
      draws.push_back(ParseRow(line, path, line_no));
    }
    return DrawReplay(std::move(draws), path);
  }

  /// The next draw; throws std::runtime_error when it is not tagged (step, particle, purpose,
  /// index) or the recording has ended.
  double Next(int step, int particle, DrawPurpose purpose, int index) {
    const std::string wanted = Tag(step, particle, purpose, index);
    if (cursor_ >= draws_.size()) {
      throw std::runtime_error(source_ + ": the recorded draws end before " + wanted);
    }
    const RecordedDraw& d = draws_[cursor_];
    if (d.step != step || d.particle != particle || d.purpose != purpose || d.index != index) {
      throw std::runtime_error(source_ + ": draw " + std::to_string(cursor_) + " is " +
                               Tag(d.step, d.particle, d.purpose, d.index) +
                               ", the filter asks for " + wanted);
    }
    ++cursor_;
    return d.value;
  }

  [[nodiscard]] std::size_t consumed() const { return cursor_; }
  [[nodiscard]] std::size_t size() const { return draws_.size(); }

 private:
  static std::string Tag(int step, int particle, DrawPurpose purpose, int index) {
    return "(step " + std::to_string(step) + ", particle " + std::to_string(particle) + ", " +
           DrawPurposeName(purpose) + " " + std::to_string(index) + ")";
  }

  static RecordedDraw ParseRow(const std::string& line, const std::string& path, int line_no) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) cells.push_back(cell);
    const std::string where = path + ":" + std::to_string(line_no) + ": ";
    if (cells.size() != 5) throw std::runtime_error(where + "expected 5 columns");
    RecordedDraw d;
    try {
      std::size_t used = 0;
      d.step = std::stoi(cells[0], &used);
      d.particle = std::stoi(cells[1]);
      d.index = std::stoi(cells[3]);
      d.value = std::stod(cells[4], &used);
      if (used != cells[4].size()) throw std::invalid_argument("trailing text");
    } catch (const std::exception&) {
      throw std::runtime_error(where + "not a number in '" + line + "'");
    }
    if (cells[2] == "component") {
      d.purpose = DrawPurpose::kComponent;
    } else if (cells[2] == "pose") {
      d.purpose = DrawPurpose::kPose;
    } else if (cells[2] == "resample") {
      d.purpose = DrawPurpose::kResample;
    } else {
      throw std::runtime_error(where + "unknown purpose '" + cells[2] +
                               "' (component, pose or resample)");
    }
    if (d.step < 0 || d.particle < 0 || d.index < 0 || !(d.value == d.value)) {
      throw std::runtime_error(where + "negative step, particle or index, or NaN value");
    }
    return d;
  }

  std::vector<RecordedDraw> draws_;
  std::string source_;
  std::size_t cursor_ = 0;
};

}  // namespace phdslam
