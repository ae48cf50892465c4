// Landmark maps as CSV: a header line naming the columns, then one landmark per line.
// Required columns x, y (m); optional weight (0 when absent) and the covariance pxx, pxy, pyy
// (m^2; all three or none). Columns may appear in any order; other columns are ignored.
#pragma once

#include <cstddef>
#include <filesystem>
#include <limits>
#include <optional>
#include <vector>

#include "src/core/types.h"

namespace phdslam::datasets {

struct MapPoint {
  Landmark position = Landmark::Zero();
  double weight = 0.0;
  std::optional<Mat2> cov;
};

/// Largest number of landmarks a map CSV may hold (the generators' landmark cap).
inline constexpr std::size_t kMaxMapCsvPoints = 1'000'000;

/// The values a map CSV reader accepts beyond finiteness.
struct MapValueLimits {
  double max_weight = std::numeric_limits<double>::infinity();     ///< weights are always >= 0
  double max_abs_value = std::numeric_limits<double>::infinity();  ///< |x|, |y|, covariances
  std::size_t max_points = kMaxMapCsvPoints;
};

/// Reads a map CSV. Blank lines and lines starting with '#' are skipped; the first other line
/// is the header. In a data line an empty weight means 0 and empty pxx, pxy, pyy (all three)
/// mean no covariance. Throws std::runtime_error naming the file, the line and the column for
/// a missing x/y column, a duplicated column, a covariance column without its partners, a wrong
/// field count, a field that is not a number, a NaN/inf value, a negative weight, a value beyond
/// `limits`, more than limits.max_points landmarks, or a covariance that is not positive
/// semi-definite; and naming the file when it cannot be opened.
std::vector<MapPoint> ReadMapCsv(const std::filesystem::path& path,
                                 const MapValueLimits& limits = {});

/// Writes the header "x,y,weight,pxx,pxy,pyy" and one line per point (empty covariance fields
/// when a point has none), each number in the shortest text that reads back exactly. Throws
/// std::invalid_argument naming the point index when a value is NaN/inf, std::runtime_error
/// naming the file when it cannot be written.
void WriteMapCsv(const std::filesystem::path& path, const std::vector<MapPoint>& points);

}  // namespace phdslam::datasets
