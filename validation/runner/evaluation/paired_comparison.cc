#include "validation/runner/evaluation/paired_comparison.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <map>
#include <optional>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "validation/runner/io/results_layout.h"

namespace phdslam::validation {
namespace {

using GroupKey = std::pair<std::string, int>;

std::size_t RequireColumn(const CsvTable& table, const std::string& name,
                          const std::string& source) {
  const std::optional<std::size_t> column = table.FindColumn(name);
  if (!column) throw std::runtime_error(source + ": no column '" + name + "'");
  return *column;
}

std::optional<double> Cell(const std::string& text, const std::string& source,
                           const std::string& column, std::size_t row) {
  if (text.empty()) return std::nullopt;
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size()) {
    throw std::runtime_error(source + ":" + std::to_string(row + 2) + ": " + column + " '" + text +
                             "' is not a number");
  }
  if (!std::isfinite(value)) {
    throw std::runtime_error(source + ":" + std::to_string(row + 2) + ": column '" + column +
                             "': '" + text + "' is not a finite number");
  }
  return value;
}

template <typename T>
T IntegerCell(const std::string& text, const std::string& source, const std::string& column,
              std::size_t row) {
  T value{};
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size()) {
    throw std::runtime_error(source + ":" + std::to_string(row + 2) + ": " + column + " '" + text +
                             "' is not an integer");
  }
  return value;
}

const char* MethodName(WilcoxonMethod m) {
  switch (m) {
    case WilcoxonMethod::kExact:
      return "exact";
    case WilcoxonMethod::kNormal:
      return "normal";
    case WilcoxonMethod::kNone:
      break;
  }
  return "none";
}

}  // namespace

std::vector<PairedComparison> ComparePairs(const CsvTable& runs,
                                           const std::vector<std::string>& metrics,
                                           const std::string& source) {
  const std::size_t estimator_column = RequireColumn(runs, "estimator", source);
  const std::size_t particles_column = RequireColumn(runs, "particles", source);
  const std::size_t seed_column = RequireColumn(runs, "seed", source);
  std::vector<std::size_t> metric_columns;
  for (const std::string& metric : metrics) {
    const std::optional<std::size_t> column = runs.FindColumn(metric);
    if (!column || *column == estimator_column || *column == particles_column ||
        *column == seed_column) {
      std::string known;
      for (const std::string& h : runs.header) {
        if (h == "estimator" || h == "particles" || h == "seed") continue;
        if (!known.empty()) known += ", ";
        known += h;
      }
      throw std::invalid_argument(source + ": no metric column '" + metric +
                                  "' (columns: " + known + ")");
    }
    metric_columns.push_back(*column);
  }

  std::vector<PairedComparison> comparisons;
  for (std::size_t m = 0; m < metrics.size(); ++m) {
    // group -> seed -> value
    std::map<GroupKey, std::map<std::uint64_t, double>> values;
    for (std::size_t r = 0; r < runs.rows.size(); ++r) {
      const std::vector<std::string>& row = runs.rows[r];
      const int particles = IntegerCell<int>(row[particles_column], source, "particles", r);
      const auto seed = IntegerCell<std::uint64_t>(row[seed_column], source, "seed", r);
      auto& group = values[GroupKey{row[estimator_column], particles}];
      const std::optional<double> v = Cell(row[metric_columns[m]], source, metrics[m], r);
      if (v) group[seed] = *v;
    }
    for (auto a = values.begin(); a != values.end(); ++a) {
      for (auto b = std::next(a); b != values.end(); ++b) {
        std::vector<double> va;
        std::vector<double> vb;
        std::vector<double> differences;
        for (const auto& [seed, value] : a->second) {
          const auto other = b->second.find(seed);
          if (other == b->second.end()) continue;
          va.push_back(value);
          vb.push_back(other->second);
          differences.push_back(value - other->second);
          if (!std::isfinite(differences.back())) {
            throw std::runtime_error(source + ": column '" + metrics[m] + "', seed " +
                                     std::to_string(seed) + ": " + a->first.first +
                                     " N=" + std::to_string(a->first.second) + " minus " +
                                     b->first.first + " N=" + std::to_string(b->first.second) +
                                     " (" + FormatNumber(value) + " - " +
                                     FormatNumber(other->second) + ") is not a finite number");
          }
        }
        if (differences.empty()) continue;
        PairedComparison c;
        c.metric = metrics[m];
        std::tie(c.estimator_a, c.particles_a) = a->first;
        std::tie(c.estimator_b, c.particles_b) = b->first;
        c.median_a = Median(va);
        c.median_b = Median(vb);
        c.median_difference = Median(differences);
        c.test = WilcoxonSignedRank(differences);
        comparisons.push_back(std::move(c));
      }
    }
  }
  return comparisons;
}

std::string ComparisonCsv(const std::vector<PairedComparison>& comparisons) {
  std::string text = CsvRow({"metric", "estimator_a", "particles_a", "estimator_b", "particles_b",
                             "n", "n_nonzero", "median_a", "median_b", "median_difference",
                             "w_plus", "w_minus", "statistic", "z", "p_value", "method"});
  for (const PairedComparison& c : comparisons) {
    const bool tested = c.test.method != WilcoxonMethod::kNone;
    text += CsvRow(
        {c.metric, c.estimator_a, FormatInteger(c.particles_a), c.estimator_b,
         FormatInteger(c.particles_b), FormatInteger(static_cast<std::int64_t>(c.test.n)),
         FormatInteger(static_cast<std::int64_t>(c.test.n_nonzero)), FormatNumber(c.median_a),
         FormatNumber(c.median_b), FormatNumber(c.median_difference),
         tested ? FormatNumber(c.test.w_plus) : std::string(),
         tested ? FormatNumber(c.test.w_minus) : std::string(),
         tested ? FormatNumber(c.test.statistic) : std::string(), FormatNumber(c.test.z),
         FormatNumber(c.test.p_value), MethodName(c.test.method)});
  }
  return text;
}

std::vector<PairedComparison> WriteComparison(const std::filesystem::path& folder,
                                              const std::vector<std::string>& metrics) {
  const std::filesystem::path runs = folder / kRunsTableFile;
  std::vector<PairedComparison> comparisons =
      ComparePairs(ReadCsvFile(runs), metrics, runs.string());
  WriteFileAtomically(folder / kComparisonFile, ComparisonCsv(comparisons));
  return comparisons;
}

}  // namespace phdslam::validation
