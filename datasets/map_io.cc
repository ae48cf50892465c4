#include "datasets/map_io.h"

#include <array>
#include <cmath>
#include <fstream>
#include <stdexcept>
#include <string>

#include "datasets/text_fields.h"

namespace phdslam::datasets {
namespace {

enum Column { kX, kY, kWeight, kPxx, kPxy, kPyy, kColumnCount };
constexpr std::array<const char*, kColumnCount> kColumnNames = {"x",   "y",   "weight",
                                                                "pxx", "pxy", "pyy"};

}  // namespace

std::vector<MapPoint> ReadMapCsv(const std::filesystem::path& path, const MapValueLimits& limits) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open map CSV '" + path.string() + "'");
  std::vector<MapPoint> points;
  std::array<int, kColumnCount> field_of{};  // field index of each known column, -1 if absent
  field_of.fill(-1);
  std::size_t field_count = 0;
  bool have_header = false;
  std::string line;
  std::size_t line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    const std::string_view content = text::Trim(line);
    if (content.empty() || content.front() == '#') continue;
    const auto fail = [&](const std::string& what) {
      throw std::runtime_error(text::Where(path, line_number) + ": " + what);
    };
    const auto fields = text::SplitFields(content, ',');
    if (!have_header) {
      for (std::size_t f = 0; f < fields.size(); ++f) {
        for (int c = 0; c < kColumnCount; ++c) {
          if (fields[f] != kColumnNames[c]) continue;
          if (field_of[c] >= 0) {
            fail(std::string("header: column '") + kColumnNames[c] + "' appears twice");
          }
          field_of[c] = static_cast<int>(f);
        }
      }
      for (int c : {kX, kY}) {
        if (field_of[c] < 0) {
          fail(std::string("header: required column '") + kColumnNames[c] +
               "' is missing (header must name x and y)");
        }
      }
      const int cov_columns = (field_of[kPxx] >= 0) + (field_of[kPxy] >= 0) + (field_of[kPyy] >= 0);
      if (cov_columns != 0 && cov_columns != 3) {
        fail(
            "header: the covariance columns pxx, pxy, pyy must appear all together or not at "
            "all");
      }
      field_count = fields.size();
      have_header = true;
      continue;
    }
    if (fields.size() != field_count) {
      fail("expected " + std::to_string(field_count) +
           " comma-separated fields (as in the "
           "header), found " +
           std::to_string(fields.size()));
    }
    std::array<std::optional<double>, kColumnCount> value;
    for (int c = 0; c < kColumnCount; ++c) {
      if (field_of[c] < 0) continue;
      const std::string_view field = fields[static_cast<std::size_t>(field_of[c])];
      const std::string column = std::string("column '") + kColumnNames[c] + "' (field " +
                                 std::to_string(field_of[c] + 1) + ")";
      if (field.empty()) {
        if (c == kX || c == kY) fail(column + " is empty");
        continue;
      }
      value[c] = text::ParseDouble(field);
      if (!value[c]) fail(column + ": '" + text::Printable(field) + "' is not a number");
      if (!std::isfinite(*value[c])) fail(column + " is not finite");
      if (std::abs(*value[c]) > limits.max_abs_value) {
        fail(column + ": " + text::FormatDouble(*value[c]) + " is beyond +-" +
             text::FormatDouble(limits.max_abs_value));
      }
    }
    if (points.size() >= limits.max_points) {
      fail("more than " + std::to_string(limits.max_points) + " landmarks, the map reader's cap");
    }
    MapPoint p;
    p.position = Landmark(*value[kX], *value[kY]);
    p.weight = value[kWeight].value_or(0.0);
    if (p.weight < 0.0 || p.weight > limits.max_weight) {
      fail("column 'weight' (field " + std::to_string(field_of[kWeight] + 1) +
           "): " + text::FormatDouble(p.weight) + " is outside [0, " +
           text::FormatDouble(limits.max_weight) + "]");
    }
    const int cov_values =
        value[kPxx].has_value() + value[kPxy].has_value() + value[kPyy].has_value();
    if (cov_values == 3) {
      const double pxx = *value[kPxx];
      const double pxy = *value[kPxy];
      const double pyy = *value[kPyy];
      if (pxx < 0.0) fail("column 'pxx': the variance " + text::FormatDouble(pxx) + " is negative");
      if (pyy < 0.0) fail("column 'pyy': the variance " + text::FormatDouble(pyy) + " is negative");
      if (pxx * pyy - pxy * pxy < -1e-12 * pxx * pyy - 1e-300) {
        fail("column 'pxy': covariance [pxx pxy; pxy pyy] is not positive semi-definite");
      }
      Mat2 cov;
      cov << pxx, pxy, pxy, pyy;
      p.cov = cov;
    } else if (cov_values != 0) {
      for (int c : {kPxx, kPxy, kPyy}) {
        if (!value[c]) {
          fail(std::string("column '") + kColumnNames[c] +
               "' is empty while other covariance fields are set (give all three or none)");
        }
      }
    }
    points.push_back(p);
  }
  if (in.bad()) throw std::runtime_error("error while reading '" + path.string() + "'");
  if (!have_header) {
    throw std::runtime_error(path.string() + ": no header line (expected e.g. x,y,weight)");
  }
  return points;
}

void WriteMapCsv(const std::filesystem::path& path, const std::vector<MapPoint>& points) {
  for (std::size_t i = 0; i < points.size(); ++i) {
    const MapPoint& p = points[i];
    if (!p.position.allFinite() || !std::isfinite(p.weight) || (p.cov && !p.cov->allFinite())) {
      throw std::invalid_argument("WriteMapCsv('" + path.string() + "'): point " +
                                  std::to_string(i) + " has a NaN/inf value");
    }
  }
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot open '" + path.string() + "' for writing");
  out << "x,y,weight,pxx,pxy,pyy\n";
  for (const MapPoint& p : points) {
    out << text::FormatDouble(p.position(0)) << ',' << text::FormatDouble(p.position(1)) << ','
        << text::FormatDouble(p.weight) << ',';
    if (p.cov) {
      // The file stores one off-diagonal value; the symmetric part is written.
      const double pxy = 0.5 * ((*p.cov)(0, 1) + (*p.cov)(1, 0));
      out << text::FormatDouble((*p.cov)(0, 0)) << ',' << text::FormatDouble(pxy) << ','
          << text::FormatDouble((*p.cov)(1, 1));
    } else {
      out << ",,";
    }
    out << '\n';
  }
  out.flush();
  if (!out) throw std::runtime_error("error while writing '" + path.string() + "'");
}

}  // namespace phdslam::datasets
