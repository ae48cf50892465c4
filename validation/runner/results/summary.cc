#include "validation/runner/results/summary.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "validation/metrics/nees.h"
#include "validation/runner/io/results_io.h"
#include "validation/runner/io/results_layout.h"

namespace phdslam::validation {
namespace {

nlohmann::json ReadJsonFile(const std::filesystem::path& path) {
  const std::string text = ReadTextFile(path);
  nlohmann::json j = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded() || !j.is_object()) {
    throw std::runtime_error(path.string() + ": not a JSON object");
  }
  return j;
}

// Reads the identification fields every run file starts with.
template <typename T>
void ReadIdentity(const nlohmann::json& j, const std::filesystem::path& path, T& run) {
  try {
    run.estimator = j.at("estimator").get<std::string>();
    run.particles = j.at("particles").get<int>();
    run.seed = j.at("seed").get<std::uint64_t>();
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(path.string() +
                             ": fields 'estimator' (string), 'particles' and 'seed' (integers) "
                             "are required: " +
                             e.what());
  }
}

// A numeric column of a steps.csv (`empty` for empty cells); empty when the column is missing
// (results written before the column existed).
std::vector<double> ReadStepColumn(const CsvTable& table, const std::filesystem::path& path,
                                   const std::string& name, double empty) {
  const std::optional<std::size_t> column = table.FindColumn(name);
  if (!column) return {};
  std::vector<double> values;
  values.reserve(table.rows.size());
  for (std::size_t i = 0; i < table.rows.size(); ++i) {
    const std::string& cell = table.rows[i][*column];
    if (cell.empty()) {
      values.push_back(empty);
      continue;
    }
    char* end = nullptr;
    const double value = std::strtod(cell.c_str(), &end);
    if (end != cell.c_str() + cell.size()) {
      throw std::runtime_error(path.string() + ":" + std::to_string(i + 2) + ": " + name + " '" +
                               cell + "' is not a number");
    }
    values.push_back(value);
  }
  return values;
}

// The per-step consistency series of a run, read only where the run's metrics have values.
void ReadStepSeries(const std::filesystem::path& path, RunResult& r) {
  const RunMetrics& m = r.metrics;
  if (m.pose_nees.count == 0 && m.pose_nees_rb.count == 0 && m.nis_count == 0) return;
  if (!std::filesystem::exists(path)) return;
  const CsvTable table = ReadCsvFile(path);
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  if (m.pose_nees.count > 0) r.step_nees = ReadStepColumn(table, path, "nees", kNaN);
  if (m.pose_nees_rb.count > 0) r.step_nees_rb = ReadStepColumn(table, path, "nees_rb", kNaN);
  if (m.nis_count > 0) {
    r.step_nis_sum = ReadStepColumn(table, path, "nis_sum", 0.0);
    r.step_nis_count = ReadStepColumn(table, path, "nis_count", 0.0);
  }
}

double Median(std::vector<double> values) {
  const std::size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(mid), values.end());
  const double upper = values[mid];
  if (values.size() % 2 == 1) return upper;
  return 0.5 * (upper + *std::max_element(values.begin(),
                                          values.begin() + static_cast<std::ptrdiff_t>(mid)));
}

std::optional<double> Fraction(std::size_t inside, std::size_t total) {
  if (total == 0) return std::nullopt;
  return static_cast<double>(inside) / static_cast<double>(total);
}

std::optional<double> StepWeightedMean(const std::vector<const RunResult*>& runs,
                                       std::optional<double> RunMetrics::*field) {
  double weighted = 0.0;
  double steps = 0.0;
  for (const RunResult* r : runs) {
    const std::optional<double>& v = r->metrics.*field;
    if (!v) continue;
    weighted += *v * static_cast<double>(r->metrics.steps);
    steps += static_cast<double>(r->metrics.steps);
  }
  if (steps == 0.0) return std::nullopt;
  return weighted / steps;
}

std::optional<double> Sem(const ErrorMoments& m) {
  const std::optional<double> s = m.Std();
  if (!s) return std::nullopt;
  return *s / std::sqrt(static_cast<double>(m.count));
}

// A column of a CSV file: its header name and how to format one row's value.
template <typename Row>
struct Column {
  std::string name;
  std::function<std::string(const Row&)> value;
};

template <typename Row>
std::string RenderCsv(const std::vector<Column<Row>>& columns, const std::vector<Row>& rows) {
  std::vector<std::string> cells;
  cells.reserve(columns.size());
  for (const auto& c : columns) cells.push_back(c.name);
  std::string text = CsvRow(cells);
  for (const Row& row : rows) {
    cells.clear();
    for (const auto& c : columns) cells.push_back(c.value(row));
    text += CsvRow(cells);
  }
  return text;
}

std::string Num(const std::optional<double>& v) { return FormatNumber(v); }
std::string Count(std::size_t v) { return FormatInteger(static_cast<std::int64_t>(v)); }

// A rate of association counts; empty when not scored or not defined (NaN).
std::string DaRate(const std::optional<AssociationCounts>& counts,
                   double (AssociationCounts::*rate)() const) {
  return counts ? Num(((*counts).*rate)()) : std::string();
}

// Two-sided bound of the mean of M landmark NEES values (2 dof each): chi-square_{2M}(p) / M.
std::string LandmarkBound(const ErrorMoments& nees, double p) {
  if (nees.count == 0) return std::string();
  const double m = static_cast<double>(nees.count);
  return Num(ChiSquareQuantile(p, 2.0 * m) / m);
}

const std::vector<Column<GroupSummary>>& SummaryColumns() {
  using G = GroupSummary;
  static const std::vector<Column<G>> columns = {
      {"estimator", [](const G& g) { return g.estimator; }},
      {"particles", [](const G& g) { return FormatInteger(g.particles); }},
      {"runs", [](const G& g) { return Count(g.runs); }},
      {"steps", [](const G& g) { return Num(g.steps); }},
      {"pos_rmse_m", [](const G& g) { return Num(g.position_m.Rms()); }},
      {"heading_rmse_deg", [](const G& g) { return Num(g.heading_deg.Rms()); }},
      {"gospa_mean_m", [](const G& g) { return Num(g.gospa_m.Mean()); }},
      {"gospa_std_m", [](const G& g) { return Num(g.gospa_m.Std()); }},
      {"ess_pct", [](const G& g) { return Num(g.ess_pct); }},
      {"resampling_pct", [](const G& g) { return Num(g.resampling_pct); }},
      {"ms_per_step_mean", [](const G& g) { return Num(g.step_ms.Mean()); }},
      {"pos_rmse_std_m", [](const G& g) { return Num(g.position_m.Std()); }},
      {"heading_rmse_std_deg", [](const G& g) { return Num(g.heading_deg.Std()); }},
      {"gospa_sem_m", [](const G& g) { return Num(Sem(g.gospa_m)); }},
      {"gospa_localisation_mean_mp",
       [](const G& g) { return Num(g.gospa_localisation_mp.Mean()); }},
      {"gospa_missed_mean_mp", [](const G& g) { return Num(g.gospa_missed_mp.Mean()); }},
      {"gospa_false_mean_mp", [](const G& g) { return Num(g.gospa_false_mp.Mean()); }},
      {"n_missed_mean", [](const G& g) { return Num(g.n_missed.Mean()); }},
      {"n_false_mean", [](const G& g) { return Num(g.n_false.Mean()); }},
      {"map_size_mean", [](const G& g) { return Num(g.map_size.Mean()); }},
      {"hypotheses_mean", [](const G& g) { return Num(g.hypotheses_mean); }},
      {"map_components_mean", [](const G& g) { return Num(g.map_components_mean); }},
      {"pose_nees_mean", [](const G& g) { return Num(g.pose_nees.Mean()); }},
      {"landmark_nees_mean", [](const G& g) { return Num(g.landmark_nees.Mean()); }},
      {"pos_err_count", [](const G& g) { return Count(g.position_m.count); }},
      {"failed_runs", [](const G& g) { return Count(g.failed_runs); }},
      {"ms_per_step_std", [](const G& g) { return Num(g.step_ms.Std()); }},
      {"ms_run_mean", [](const G& g) { return Num(g.run_ms.Mean()); }},
      {"nees_mean", [](const G& g) { return g.nees ? Num(g.nees->mean) : std::string(); }},
      {"nees_lower_95", [](const G& g) { return g.nees ? Num(g.nees->lower) : std::string(); }},
      {"nees_upper_95", [](const G& g) { return g.nees ? Num(g.nees->upper) : std::string(); }},
      {"nees_fraction_inside",
       [](const G& g) { return g.nees ? Num(g.nees->fraction_inside) : std::string(); }},
      {"nees_steps", [](const G& g) { return g.nees ? Count(g.nees->steps) : std::string(); }},
      {"da_tpr", [](const G& g) { return DaRate(g.association, &AssociationCounts::tpr); }},
      {"da_tnr", [](const G& g) { return DaRate(g.association, &AssociationCounts::tnr); }},
      {"da_positives",
       [](const G& g) {
         return g.association
                    ? Count(static_cast<std::size_t>(g.association->tp + g.association->fn))
                    : std::string();
       }},
      {"da_negatives",
       [](const G& g) {
         return g.association
                    ? Count(static_cast<std::size_t>(g.association->tn + g.association->fp))
                    : std::string();
       }},
      {"solver_iterations_mean", [](const G& g) { return Num(g.solver_iterations.Mean()); }},
      {"solver_unconverged_runs",
       [](const G& g) {
         return g.solver_runs > 0 ? Count(g.solver_unconverged_runs) : std::string();
       }},
      {"nees_median", [](const G& g) { return g.nees ? Num(g.nees->median) : std::string(); }},
      {"coverage", [](const G& g) { return Num(g.coverage); }},
      {"nees_rb_mean", [](const G& g) { return g.nees_rb ? Num(g.nees_rb->mean) : std::string(); }},
      {"nees_rb_median",
       [](const G& g) { return g.nees_rb ? Num(g.nees_rb->median) : std::string(); }},
      {"nees_rb_lower_95",
       [](const G& g) { return g.nees_rb ? Num(g.nees_rb->lower) : std::string(); }},
      {"nees_rb_upper_95",
       [](const G& g) { return g.nees_rb ? Num(g.nees_rb->upper) : std::string(); }},
      {"nees_rb_fraction_inside",
       [](const G& g) { return g.nees_rb ? Num(g.nees_rb->fraction_inside) : std::string(); }},
      {"nees_rb_steps",
       [](const G& g) { return g.nees_rb ? Count(g.nees_rb->steps) : std::string(); }},
      {"pose_nees_rb_mean", [](const G& g) { return Num(g.pose_nees_rb.Mean()); }},
      {"coverage_rb", [](const G& g) { return Num(g.coverage_rb); }},
      {"nis_mean", [](const G& g) { return g.nis ? Num(g.nis->mean) : std::string(); }},
      {"nis_median", [](const G& g) { return g.nis ? Num(g.nis->median) : std::string(); }},
      {"nis_fraction_inside",
       [](const G& g) { return g.nis ? Num(g.nis->fraction_inside) : std::string(); }},
      {"nis_steps", [](const G& g) { return g.nis ? Count(g.nis->steps) : std::string(); }},
      {"landmark_nees_lower_95", [](const G& g) { return LandmarkBound(g.landmark_nees, 0.025); }},
      {"landmark_nees_upper_95", [](const G& g) { return LandmarkBound(g.landmark_nees, 0.975); }},
      {"gps_nees_rb_mean", [](const G& g) { return Num(g.gps_nees_rb.Mean()); }},
      {"gps_coverage_rb", [](const G& g) { return Num(g.gps_coverage_rb); }},
  };
  return columns;
}

const std::vector<Column<RunResult>>& RunColumns() {
  using R = RunResult;
  const auto gospa = [](double FinalMapGospa::*member) {
    return [member](const R& r) {
      return r.metrics.gospa ? FormatNumber((*r.metrics.gospa).*member) : std::string();
    };
  };
  const auto gospa_count = [](int FinalMapGospa::*member) {
    return [member](const R& r) {
      return r.metrics.gospa ? FormatInteger((*r.metrics.gospa).*member) : std::string();
    };
  };
  static const std::vector<Column<R>> columns = {
      {"estimator", [](const R& r) { return r.estimator; }},
      {"particles", [](const R& r) { return FormatInteger(r.particles); }},
      {"seed", [](const R& r) { return std::to_string(r.seed); }},
      {"steps", [](const R& r) { return Count(r.metrics.steps); }},
      {"pos_rmse_m", [](const R& r) { return Num(r.metrics.position_m.Rms()); }},
      {"heading_rmse_deg", [](const R& r) { return Num(r.metrics.heading_deg.Rms()); }},
      {"gospa_m", gospa(&FinalMapGospa::gospa)},
      {"ess_pct", [](const R& r) { return Num(r.metrics.ess_pct); }},
      {"resampling_pct", [](const R& r) { return Num(r.metrics.resampling_pct); }},
      {"ms_per_step_mean", [](const R& r) { return Num(r.metrics.step_ms.Mean()); }},
      {"pos_rmse_std_m", [](const R& r) { return Num(r.metrics.position_m.Std()); }},
      {"heading_rmse_std_deg", [](const R& r) { return Num(r.metrics.heading_deg.Std()); }},
      {"gospa_localisation_mp", gospa(&FinalMapGospa::localisation)},
      {"gospa_missed_mp", gospa(&FinalMapGospa::missed)},
      {"gospa_false_mp", gospa(&FinalMapGospa::false_)},
      {"n_missed", gospa_count(&FinalMapGospa::n_missed)},
      {"n_false", gospa_count(&FinalMapGospa::n_false)},
      {"map_size", [](const R& r) { return Count(r.metrics.map_size); }},
      {"truth_map_size",
       [](const R& r) {
         return r.metrics.truth_map_size ? Count(*r.metrics.truth_map_size) : std::string();
       }},
      {"hypotheses_mean", [](const R& r) { return Num(r.metrics.hypotheses_mean); }},
      {"map_components_mean", [](const R& r) { return Num(r.metrics.map_components_mean); }},
      {"pose_nees_mean", [](const R& r) { return Num(r.metrics.pose_nees.Mean()); }},
      {"landmark_nees_mean", [](const R& r) { return Num(r.metrics.landmark_nees.Mean()); }},
      {"pos_err_count", [](const R& r) { return Count(r.metrics.position_m.count); }},
      {"ms_per_step_std", [](const R& r) { return Num(r.metrics.step_ms.Std()); }},
      {"ms_run", [](const R& r) { return Num(r.metrics.total_ms); }},
      {"da_tpr", [](const R& r) { return DaRate(r.metrics.association, &AssociationCounts::tpr); }},
      {"da_tnr", [](const R& r) { return DaRate(r.metrics.association, &AssociationCounts::tnr); }},
      {"solver_iterations",
       [](const R& r) {
         return r.metrics.solver_iterations ? Count(*r.metrics.solver_iterations) : std::string();
       }},
      {"solver_converged",
       [](const R& r) {
         if (!r.metrics.solver_converged) return std::string();
         return std::string(*r.metrics.solver_converged ? "1" : "0");
       }},
      {"coverage",
       [](const R& r) {
         return Num(Fraction(r.metrics.pose_coverage_inside, r.metrics.pose_nees.count));
       }},
      {"pose_nees_rb_mean", [](const R& r) { return Num(r.metrics.pose_nees_rb.Mean()); }},
      {"coverage_rb",
       [](const R& r) {
         return Num(Fraction(r.metrics.pose_coverage_rb_inside, r.metrics.pose_nees_rb.count));
       }},
      {"nis_mean",
       [](const R& r) {
         return r.metrics.nis_count > 0
                    ? Num(r.metrics.nis_sum / static_cast<double>(r.metrics.nis_count))
                    : std::string();
       }},
      {"nis_count", [](const R& r) { return Count(r.metrics.nis_count); }},
      {"gps_nees_rb_mean", [](const R& r) { return Num(r.metrics.gps_nees_rb.Mean()); }},
      {"gps_coverage_rb",
       [](const R& r) {
         return Num(Fraction(r.metrics.gps_coverage_rb_inside, r.metrics.gps_nees_rb.count));
       }},
      {"unconverged_solves",
       [](const R& r) {
         return r.metrics.unconverged_solves ? Count(*r.metrics.unconverged_solves) : std::string();
       }},
      {"relocalisations",
       [](const R& r) {
         return r.metrics.relocalisations ? Count(*r.metrics.relocalisations) : std::string();
       }},
      {"neg_log_posterior", [](const R& r) { return Num(r.metrics.neg_log_posterior); }},
  };
  return columns;
}

}  // namespace

ResultsInventory ReadResults(const std::filesystem::path& out) {
  ResultsInventory inventory;
  const std::filesystem::path runs_dir = out / kRunsFolder;
  if (!std::filesystem::is_directory(runs_dir)) return inventory;
  for (const auto& group : std::filesystem::directory_iterator(runs_dir)) {
    if (!group.is_directory()) continue;
    for (const auto& run : std::filesystem::directory_iterator(group.path())) {
      if (!run.is_directory()) continue;
      const std::filesystem::path metrics_path = run.path() / kMetricsFile;
      const std::filesystem::path error_path = run.path() / kErrorFile;
      if (std::filesystem::exists(metrics_path)) {
        const nlohmann::json j = ReadJsonFile(metrics_path);
        if (const std::string field = OverflowedMetricsField(j); !field.empty()) {
          FailedRun f;  // written before overflowed errors were recorded as failures
          ReadIdentity(j, metrics_path, f);
          f.error = metrics_path.string() + ": field '" + field +
                    "' is null (an error that overflowed); counted as a failed run";
          inventory.failed.push_back(std::move(f));
          continue;
        }
        RunResult r;
        ReadIdentity(j, metrics_path, r);
        r.metrics = RunMetricsFromJson(j, metrics_path.string());
        ReadStepSeries(run.path() / kStepsFile, r);
        inventory.runs.push_back(std::move(r));
      } else if (std::filesystem::exists(error_path)) {
        const nlohmann::json j = ReadJsonFile(error_path);
        FailedRun f;
        ReadIdentity(j, error_path, f);
        f.error = j.value("error", std::string());
        inventory.failed.push_back(std::move(f));
      }
    }
  }
  const auto key = [](const auto& r) { return std::tie(r.estimator, r.particles, r.seed); };
  std::sort(inventory.runs.begin(), inventory.runs.end(),
            [&](const RunResult& a, const RunResult& b) { return key(a) < key(b); });
  std::sort(inventory.failed.begin(), inventory.failed.end(),
            [&](const FailedRun& a, const FailedRun& b) { return key(a) < key(b); });
  return inventory;
}

std::optional<GroupNees> SummariseGroupNees(const std::vector<const std::vector<double>*>& runs) {
  if (runs.empty()) return std::nullopt;
  std::size_t steps = std::numeric_limits<std::size_t>::max();
  for (const std::vector<double>* r : runs) steps = std::min(steps, r->size());
  std::vector<double> averaged;
  for (std::size_t k = 0; k < steps; ++k) {
    double sum = 0.0;
    bool complete = true;
    for (const std::vector<double>* r : runs) {
      const double v = (*r)[k];
      if (!std::isfinite(v)) {
        complete = false;
        break;
      }
      sum += v;
    }
    if (complete) averaged.push_back(sum / static_cast<double>(runs.size()));
  }
  if (averaged.empty()) return std::nullopt;
  const NeesBounds bounds = AveragedNeesBounds(3, static_cast<int>(runs.size()), 0.05);
  GroupNees g;
  g.lower = bounds.lower;
  g.upper = bounds.upper;
  g.steps = averaged.size();
  std::size_t inside = 0;
  double total = 0.0;
  for (double a : averaged) {
    total += a;
    if (a >= bounds.lower && a <= bounds.upper) ++inside;
  }
  g.mean = total / static_cast<double>(averaged.size());
  g.fraction_inside = static_cast<double>(inside) / static_cast<double>(averaged.size());
  g.median = Median(std::move(averaged));
  return g;
}

std::optional<GroupNis> SummariseGroupNis(const std::vector<const std::vector<double>*>& sums,
                                          const std::vector<const std::vector<double>*>& counts) {
  std::size_t steps = 0;
  for (const std::vector<double>* c : counts) steps = std::max(steps, c->size());
  const auto at = [](const std::vector<double>* v, std::size_t k) {
    return k < v->size() ? (*v)[k] : 0.0;
  };
  std::vector<double> averaged;
  double total_sum = 0.0;
  double total_count = 0.0;
  std::size_t inside = 0;
  // The 95 % band of the mean NIS by measurement count: the counts repeat from step to step, and
  // each band costs two chi-square quantiles.
  std::map<double, std::pair<double, double>> band_of_count;
  for (std::size_t k = 0; k < steps; ++k) {
    double sum = 0.0;
    double count = 0.0;
    for (std::size_t r = 0; r < sums.size() && r < counts.size(); ++r) {
      sum += at(sums[r], k);
      count += at(counts[r], k);
    }
    if (count <= 0.0) continue;
    const double a = sum / count;
    auto band = band_of_count.find(count);
    if (band == band_of_count.end()) {
      band = band_of_count
                 .emplace(count, std::pair{ChiSquareQuantile(0.025, 2.0 * count) / count,
                                           ChiSquareQuantile(0.975, 2.0 * count) / count})
                 .first;
    }
    const auto [lower, upper] = band->second;
    if (a >= lower && a <= upper) ++inside;
    averaged.push_back(a);
    total_sum += sum;
    total_count += count;
  }
  if (averaged.empty()) return std::nullopt;
  GroupNis g;
  g.mean = total_sum / total_count;
  g.steps = averaged.size();
  g.fraction_inside = static_cast<double>(inside) / static_cast<double>(averaged.size());
  g.median = Median(std::move(averaged));
  return g;
}

namespace {

// The Rao-Blackwellised NEES, NIS and coverage of a group.
void SummariseConsistency(const std::vector<const RunResult*>& runs, GroupSummary& g) {
  std::size_t inside = 0;
  std::size_t inside_rb = 0;
  std::size_t inside_gps = 0;
  for (const RunResult* r : runs) {
    inside += r->metrics.pose_coverage_inside;
    inside_rb += r->metrics.pose_coverage_rb_inside;
    inside_gps += r->metrics.gps_coverage_rb_inside;
  }
  g.coverage = Fraction(inside, g.pose_nees.count);
  g.coverage_rb = Fraction(inside_rb, g.pose_nees_rb.count);
  g.gps_coverage_rb = Fraction(inside_gps, g.gps_nees_rb.count);
  if (g.pose_nees_rb.count > 0) {
    std::vector<const std::vector<double>*> nees;
    nees.reserve(runs.size());
    for (const RunResult* r : runs) nees.push_back(&r->step_nees_rb);
    g.nees_rb = SummariseGroupNees(nees);
  }
  std::vector<const std::vector<double>*> sums;
  std::vector<const std::vector<double>*> counts;
  for (const RunResult* r : runs) {
    sums.push_back(&r->step_nis_sum);
    counts.push_back(&r->step_nis_count);
  }
  g.nis = SummariseGroupNis(sums, counts);
}

}  // namespace

std::vector<GroupSummary> SummariseGroups(const ResultsInventory& inventory) {
  std::map<std::pair<std::string, int>, std::vector<const RunResult*>> runs_by_group;
  std::map<std::pair<std::string, int>, std::size_t> failures_by_group;
  for (const RunResult& r : inventory.runs) runs_by_group[{r.estimator, r.particles}].push_back(&r);
  for (const FailedRun& f : inventory.failed) {
    runs_by_group[{f.estimator, f.particles}];
    ++failures_by_group[{f.estimator, f.particles}];
  }
  std::vector<GroupSummary> groups;
  for (const auto& [key, runs] : runs_by_group) {
    GroupSummary g;
    g.estimator = key.first;
    g.particles = key.second;
    g.runs = runs.size();
    g.failed_runs = failures_by_group[key];
    ErrorMoments steps;
    for (const RunResult* r : runs) {
      const RunMetrics& m = r->metrics;
      steps.Add(static_cast<double>(m.steps));
      g.position_m.Merge(m.position_m);
      g.heading_deg.Merge(m.heading_deg);
      if (m.gospa) {
        g.gospa_m.Add(m.gospa->gospa);
        g.gospa_localisation_mp.Add(m.gospa->localisation);
        g.gospa_missed_mp.Add(m.gospa->missed);
        g.gospa_false_mp.Add(m.gospa->false_);
        g.n_missed.Add(m.gospa->n_missed);
        g.n_false.Add(m.gospa->n_false);
      }
      g.map_size.Add(static_cast<double>(m.map_size));
      g.pose_nees.Merge(m.pose_nees);
      g.pose_nees_rb.Merge(m.pose_nees_rb);
      g.gps_nees_rb.Merge(m.gps_nees_rb);
      g.landmark_nees.Merge(m.landmark_nees);
      if (m.association) {
        if (!g.association) g.association = AssociationCounts{};
        *g.association += *m.association;
      }
      g.step_ms.Merge(m.step_ms);
      g.run_ms.Add(m.total_ms);
      if (m.solver_iterations) g.solver_iterations.Add(static_cast<double>(*m.solver_iterations));
      if (m.solver_converged) {
        ++g.solver_runs;
        if (!*m.solver_converged) ++g.solver_unconverged_runs;
      }
    }
    g.steps = steps.Mean();
    g.ess_pct = StepWeightedMean(runs, &RunMetrics::ess_pct);
    g.resampling_pct = StepWeightedMean(runs, &RunMetrics::resampling_pct);
    g.hypotheses_mean = StepWeightedMean(runs, &RunMetrics::hypotheses_mean);
    g.map_components_mean = StepWeightedMean(runs, &RunMetrics::map_components_mean);
    if (g.pose_nees.count > 0) {
      std::vector<const std::vector<double>*> nees;
      for (const RunResult* r : runs) nees.push_back(&r->step_nees);
      g.nees = SummariseGroupNees(nees);
    }
    SummariseConsistency(runs, g);
    groups.push_back(std::move(g));
  }
  return groups;
}

std::string SummaryCsv(const std::vector<GroupSummary>& groups) {
  return RenderCsv(SummaryColumns(), groups);
}

std::string RunsCsv(const std::vector<RunResult>& runs) { return RenderCsv(RunColumns(), runs); }

std::string FormatSummaryTable(const std::vector<GroupSummary>& groups) {
  const auto fixed = [](const std::optional<double>& v, int decimals) {
    if (!v || !std::isfinite(*v)) return std::string("-");
    char buffer[64];
    std::snprintf(buffer, sizeof(buffer), "%.*f", decimals, *v);
    return std::string(buffer);
  };
  std::size_t name_width = 9;
  for (const GroupSummary& g : groups) name_width = std::max(name_width, g.estimator.size());
  std::string text;
  char line[512];
  std::snprintf(line, sizeof(line), "%-*s %6s %5s %6s %10s %9s %17s %7s %7s %10s\n",
                static_cast<int>(name_width), "estimator", "N", "runs", "failed", "pos RMSE m",
                "head deg", "GOSPA m (std)", "ESS %", "resamp%", "ms/step");
  text += line;
  for (const GroupSummary& g : groups) {
    const std::string gospa =
        g.gospa_m.count == 0 ? "-"
                             : fixed(g.gospa_m.Mean(), 2) + " (" + fixed(g.gospa_m.Std(), 2) + ")";
    std::snprintf(line, sizeof(line), "%-*s %6d %5zu %6zu %10s %9s %17s %7s %7s %10s\n",
                  static_cast<int>(name_width), g.estimator.c_str(), g.particles, g.runs,
                  g.failed_runs, fixed(g.position_m.Rms(), 3).c_str(),
                  fixed(g.heading_deg.Rms(), 3).c_str(), gospa.c_str(), fixed(g.ess_pct, 2).c_str(),
                  fixed(g.resampling_pct, 2).c_str(), fixed(g.step_ms.Mean(), 3).c_str());
    text += line;
  }
  return text;
}

std::vector<GroupSummary> WriteSummaryFiles(const std::filesystem::path& out) {
  const ResultsInventory inventory = ReadResults(out);
  std::vector<GroupSummary> groups = SummariseGroups(inventory);
  WriteFileAtomically(out / kSummaryFile, SummaryCsv(groups));
  WriteFileAtomically(out / kRunsTableFile, RunsCsv(inventory.runs));
  return groups;
}

}  // namespace phdslam::validation
