// metrics.json form of RunMetrics: one table of keys (MetricsKeys) writes and reads every key.
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "validation/runner/evaluation/run_metrics.h"

namespace phdslam::validation {
namespace {

nlohmann::json OrNull(const std::optional<double>& v) {
  return v && std::isfinite(*v) ? nlohmann::json(*v) : nlohmann::json(nullptr);
}

template <typename T>
nlohmann::json OrNull(const std::optional<T>& v) {
  return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
}

class JsonReader {
 public:
  JsonReader(const nlohmann::json& j, const std::string& source) : j_(j), source_(source) {
    if (!j_.is_object()) throw std::runtime_error(source_ + ": expected a JSON object");
  }

  const nlohmann::json& Field(const std::string& key) const {
    if (!j_.contains(key)) throw std::runtime_error(source_ + ": missing field '" + key + "'");
    return j_.at(key);
  }
  double Number(const std::string& key) const {
    const nlohmann::json& v = Field(key);
    if (!v.is_number()) Fail(key, "a number");
    return v.get<double>();
  }
  std::optional<double> OptionalNumber(const std::string& key) const {
    const nlohmann::json& v = Field(key);
    if (v.is_null()) return std::nullopt;
    if (!v.is_number()) Fail(key, "a number or null");
    return v.get<double>();
  }
  std::size_t Count(const std::string& key) const {
    const nlohmann::json& v = Field(key);
    if (!v.is_number_unsigned() && !(v.is_number_integer() && v.get<std::int64_t>() >= 0)) {
      Fail(key, "a non-negative integer");
    }
    return v.get<std::size_t>();
  }
  std::optional<std::size_t> OptionalCount(const std::string& key) const {
    if (Field(key).is_null()) return std::nullopt;
    return Count(key);
  }
  [[noreturn]] void Fail(const std::string& key, const std::string& expected) const {
    throw std::runtime_error(source_ + ": field '" + key + "' must be " + expected + ", got " +
                             j_.at(key).dump());
  }

 private:
  const nlohmann::json& j_;
  const std::string& source_;
};

// Format versions from which a key is required (MetricsKey::required_from): keys added while
// version 1 was current, while version 2 was, and while version 3 was.
constexpr int kFromV2 = 2;
constexpr int kFromV3 = 3;
constexpr int kFromV4 = 4;

// One metrics.json key: how it is written from RunMetrics and read back. The keys are written in
// one object (sorted by name in the file) and read in table order, so a group's leading key
// (gospa_m, da_tp) is read before the keys that depend on it.
struct MetricsKey {
  std::string name;
  std::function<nlohmann::json(const RunMetrics&)> write;
  /// Reads the value into the metrics; empty for derived keys (RMSE, std, means, rates), written
  /// for readers and recomputed from the sufficient statistics.
  std::function<void(const JsonReader&, const std::string&, RunMetrics&)> read;
  /// The first format version that requires the key. A file of an earlier version (version 1: no
  /// format_version) may lack it, having been written before the key existed; the metric then
  /// keeps its default (none).
  int required_from = 1;
};

using Metrics = RunMetrics;
using Reader = JsonReader;

// Keys of one ErrorMoments member: <prefix>_count, <prefix>_sum<unit>, <prefix>_sq_sum<unit>2.
std::vector<MetricsKey> MomentKeys(const std::string& prefix, const std::string& unit,
                                   ErrorMoments RunMetrics::*member) {
  const std::string sq = prefix + "_sq_sum" + unit + (unit.empty() ? "" : "2");
  return {
      {prefix + "_count", [member](const Metrics& m) { return nlohmann::json((m.*member).count); },
       [member](const Reader& r, const std::string& k, Metrics& m) {
         (m.*member).count = r.Count(k);
       }},
      {prefix + "_sum" + unit,
       [member](const Metrics& m) { return nlohmann::json((m.*member).sum); },
       [member](const Reader& r, const std::string& k, Metrics& m) {
         (m.*member).sum = r.Number(k);
       }},
      {sq, [member](const Metrics& m) { return nlohmann::json((m.*member).sum_sq); },
       [member](const Reader& r, const std::string& k, Metrics& m) {
         (m.*member).sum_sq = r.Number(k);
       }},
  };
}

// Keys of a NEES-like statistic: <prefix>_mean (derived), <prefix>_count and <prefix>_sum. The
// values are finite and non-negative, so a sum written as null overflowed: it reads as +infinity
// (e.g. collapsed particles without resampling, where single values reach 1e300).
std::vector<MetricsKey> NeesKeys(const std::string& prefix, ErrorMoments RunMetrics::*member,
                                 int required_from) {
  return {
      {prefix + "_mean",
       [member](const Metrics& m) { return OrNull((m.*member).Mean()); },
       {},
       required_from},
      {prefix + "_count", [member](const Metrics& m) { return nlohmann::json((m.*member).count); },
       [member](const Reader& r, const std::string& k, Metrics& m) {
         (m.*member).count = r.Count(k);
       },
       required_from},
      {prefix + "_sum", [member](const Metrics& m) { return nlohmann::json((m.*member).sum); },
       [member](const Reader& r, const std::string& k, Metrics& m) {
         (m.*member).sum = r.OptionalNumber(k).value_or(std::numeric_limits<double>::infinity());
       },
       required_from},
  };
}

// A part of the final-map GOSPA, null without a true map; read when gospa_m was not null.
template <typename T>
MetricsKey GospaKey(const std::string& name, T FinalMapGospa::*member) {
  return {name,
          [member](const Metrics& m) {
            return m.gospa ? nlohmann::json((*m.gospa).*member) : nlohmann::json(nullptr);
          },
          [member](const Reader& r, const std::string& k, Metrics& m) {
            if (!m.gospa) return;
            if constexpr (std::is_same_v<T, int>) {
              (*m.gospa).*member = static_cast<int>(r.Count(k));
            } else {
              (*m.gospa).*member = r.Number(k);
            }
          }};
}

// An association count, null when not scored; read when da_tp was not null.
MetricsKey AssociationKey(const std::string& name, long AssociationCounts::*member) {
  return {name,
          [member](const Metrics& m) {
            return m.association ? nlohmann::json((*m.association).*member)
                                 : nlohmann::json(nullptr);
          },
          [member](const Reader& r, const std::string& k, Metrics& m) {
            if (m.association) (*m.association).*member = static_cast<long>(r.Count(k));
          },
          kFromV2};
}

// An optional number (null when not available).
MetricsKey OptionalNumberKey(const std::string& name, std::optional<double> RunMetrics::*member,
                             int required_from = 1) {
  return {name, [member](const Metrics& m) { return OrNull(m.*member); },
          [member](const Reader& r, const std::string& k, Metrics& m) {
            m.*member = r.OptionalNumber(k);
          },
          required_from};
}

// A count stored in a std::size_t member; optional counts are null when not available.
MetricsKey CountKey(const std::string& name, std::size_t RunMetrics::*member,
                    int required_from = 1) {
  return {name, [member](const Metrics& m) { return nlohmann::json(m.*member); },
          [member](const Reader& r, const std::string& k, Metrics& m) { m.*member = r.Count(k); },
          required_from};
}
MetricsKey OptionalCountKey(const std::string& name, std::optional<std::size_t> RunMetrics::*member,
                            int required_from = 1) {
  return {name, [member](const Metrics& m) { return OrNull(m.*member); },
          [member](const Reader& r, const std::string& k, Metrics& m) {
            m.*member = r.OptionalCount(k);
          },
          required_from};
}

// A number stored in a double member.
MetricsKey NumberKey(const std::string& name, double RunMetrics::*member) {
  return {name, [member](const Metrics& m) { return nlohmann::json(m.*member); },
          [member](const Reader& r, const std::string& k, Metrics& m) { m.*member = r.Number(k); }};
}

// A value written for readers only, from the metrics.
MetricsKey Derived(const std::string& name, std::function<nlohmann::json(const Metrics&)> write,
                   int required_from = 1) {
  return {name, std::move(write), {}, required_from};
}

std::optional<double> DaRate(const Metrics& m, double (AssociationCounts::*rate)() const) {
  return m.association ? std::optional<double>(((*m.association).*rate)()) : std::nullopt;
}

// The keys of metrics.json after the identity (validation/README.md, "metrics.json"), in reading
// order: the one place that names them.
const std::vector<MetricsKey>& MetricsKeys() {
  static const std::vector<MetricsKey> keys = [] {
    std::vector<MetricsKey> table;
    const auto add = [&table](std::vector<MetricsKey> more) {
      for (MetricsKey& key : more) table.push_back(std::move(key));
    };
    add({CountKey("steps", &Metrics::steps),
         Derived("pos_rmse_m", [](const Metrics& m) { return OrNull(m.position_m.Rms()); }),
         Derived("pos_err_std_m", [](const Metrics& m) { return OrNull(m.position_m.Std()); })});
    add(MomentKeys("pos_err", "_m", &Metrics::position_m));
    add({Derived("heading_rmse_deg", [](const Metrics& m) { return OrNull(m.heading_deg.Rms()); }),
         Derived("heading_err_std_deg",
                 [](const Metrics& m) { return OrNull(m.heading_deg.Std()); })});
    add(MomentKeys("heading_err", "_deg", &Metrics::heading_deg));
    add({{"gospa_m",
          [](const Metrics& m) {
            return m.gospa ? nlohmann::json(m.gospa->gospa) : nlohmann::json(nullptr);
          },
          [](const Reader& r, const std::string& k, Metrics& m) {
            if (const std::optional<double> g = r.OptionalNumber(k)) {
              m.gospa = FinalMapGospa{};
              m.gospa->gospa = *g;
            }
          }},
         GospaKey("gospa_localisation_mp", &FinalMapGospa::localisation),
         GospaKey("gospa_missed_mp", &FinalMapGospa::missed),
         GospaKey("gospa_false_mp", &FinalMapGospa::false_),
         GospaKey("n_missed", &FinalMapGospa::n_missed),
         GospaKey("n_false", &FinalMapGospa::n_false),
         NumberKey("gospa_c", &Metrics::gospa_c),
         NumberKey("gospa_p", &Metrics::gospa_p),
         CountKey("map_size", &Metrics::map_size),
         OptionalCountKey("truth_map_size", &Metrics::truth_map_size),
         OptionalNumberKey("ess_pct", &Metrics::ess_pct),
         OptionalNumberKey("resampling_pct", &Metrics::resampling_pct),
         OptionalNumberKey("hypotheses_mean", &Metrics::hypotheses_mean),
         OptionalNumberKey("map_components_mean", &Metrics::map_components_mean)});
    add(NeesKeys("pose_nees", &Metrics::pose_nees, 1));
    add(NeesKeys("landmark_nees", &Metrics::landmark_nees, 1));
    add({CountKey("pose_coverage_inside", &Metrics::pose_coverage_inside, kFromV2)});
    add(NeesKeys("pose_nees_rb", &Metrics::pose_nees_rb, kFromV2));
    add({CountKey("pose_coverage_rb_inside", &Metrics::pose_coverage_rb_inside, kFromV2)});
    add(NeesKeys("gps_nees_rb", &Metrics::gps_nees_rb, kFromV2));
    add({CountKey("gps_coverage_rb_inside", &Metrics::gps_coverage_rb_inside, kFromV2),
         {"nis_sum", [](const Metrics& m) { return nlohmann::json(m.nis_sum); },
          [](const Reader& r, const std::string& k, Metrics& m) {
            m.nis_sum = r.OptionalNumber(k).value_or(std::numeric_limits<double>::infinity());
          },
          kFromV2},
         CountKey("nis_count", &Metrics::nis_count, kFromV2),
         Derived(
             "nis_mean",
             [](const Metrics& m) {
               return OrNull(m.nis_count > 0 ? std::optional<double>(
                                                   m.nis_sum / static_cast<double>(m.nis_count))
                                             : std::nullopt);
             },
             kFromV2),
         {"da_tp",
          [](const Metrics& m) {
            return m.association ? nlohmann::json(m.association->tp) : nlohmann::json(nullptr);
          },
          [](const Reader& r, const std::string& k, Metrics& m) {
            if (r.Field(k).is_null()) return;
            m.association = AssociationCounts{};
            m.association->tp = static_cast<long>(r.Count(k));
          },
          kFromV2},
         AssociationKey("da_fn", &AssociationCounts::fn),
         AssociationKey("da_tn", &AssociationCounts::tn),
         AssociationKey("da_fp", &AssociationCounts::fp),
         AssociationKey("da_first_sightings", &AssociationCounts::first_sightings),
         AssociationKey("da_first_sightings_associated",
                        &AssociationCounts::first_sightings_associated),
         AssociationKey("da_unreported", &AssociationCounts::unreported),
         Derived(
             "da_tpr", [](const Metrics& m) { return OrNull(DaRate(m, &AssociationCounts::tpr)); },
             kFromV2),
         Derived(
             "da_tnr", [](const Metrics& m) { return OrNull(DaRate(m, &AssociationCounts::tnr)); },
             kFromV2),
         OptionalCountKey("gps_matched_steps", &Metrics::gps_matched_steps),
         OptionalCountKey("solver_iterations", &Metrics::solver_iterations, kFromV2),
         {"solver_converged", [](const Metrics& m) { return OrNull(m.solver_converged); },
          [](const Reader& r, const std::string& k, Metrics& m) {
            const nlohmann::json& v = r.Field(k);
            if (v.is_null()) return;
            if (!v.is_boolean()) r.Fail(k, "true, false or null");
            m.solver_converged = v.get<bool>();
          },
          kFromV2},
         OptionalCountKey("solves", &Metrics::solves, kFromV2),
         OptionalCountKey("unconverged_solves", &Metrics::unconverged_solves, kFromV2),
         OptionalCountKey("relocalisations", &Metrics::relocalisations, kFromV3),
         OptionalNumberKey("neg_log_posterior", &Metrics::neg_log_posterior, kFromV4),
         Derived("ms_per_step_mean", [](const Metrics& m) { return OrNull(m.step_ms.Mean()); }),
         Derived("ms_per_step_std", [](const Metrics& m) { return OrNull(m.step_ms.Std()); })});
    // The timing statistics are ms_count, ms_sum, ms_sq_sum (unit-less prefix "ms").
    add(MomentKeys("ms", "", &Metrics::step_ms));
    add({NumberKey("ms_total", &Metrics::total_ms)});
    return table;
  }();
  return keys;
}

// The error-statistic fields every metrics.json holds as numbers.
constexpr const char* kRequiredStatistics[] = {"pos_err_sum_m", "pos_err_sq_sum_m2",
                                               "heading_err_sum_deg", "heading_err_sq_sum_deg2"};

std::string NonFiniteMoments(const std::string& what, const ErrorMoments& m) {
  if (std::isfinite(m.sum) && std::isfinite(m.sum_sq)) return "";
  return what + " is not finite (sum " + std::to_string(m.sum) + ", sum of squares " +
         std::to_string(m.sum_sq) + " over " + std::to_string(m.count) +
         " steps): the estimate diverged or an error overflowed";
}

}  // namespace

std::string NonFiniteMetrics(const RunMetrics& m) {
  std::string why = NonFiniteMoments("the position error", m.position_m);
  if (why.empty()) why = NonFiniteMoments("the heading error", m.heading_deg);
  if (why.empty() && m.gospa && !std::isfinite(m.gospa->gospa)) {
    why = "the final map's GOSPA is not finite";
  }
  return why;
}

std::string OverflowedMetricsField(const nlohmann::json& j) {
  if (j.contains(kFormatVersionKey)) return "";
  for (const char* key : kRequiredStatistics) {
    if (j.contains(key) && j.at(key).is_null()) return key;
  }
  return "";
}

int MetricsFormatVersion(const nlohmann::json& j, const std::string& source) {
  if (!j.contains(kFormatVersionKey)) return 1;
  const nlohmann::json& v = j.at(kFormatVersionKey);
  if (!v.is_number_integer()) {
    throw std::runtime_error(source + ": field '" + std::string(kFormatVersionKey) +
                             "' must be an integer, got " + v.dump());
  }
  const std::int64_t version = v.get<std::int64_t>();
  if (version < 1 || version > kMetricsFormatVersion) {
    throw std::runtime_error(source + ": metrics.json format_version " + std::to_string(version) +
                             " is unknown to this program, which reads versions 1 to " +
                             std::to_string(kMetricsFormatVersion) +
                             " (validation/README.md, metrics.json); written by a newer phdslam?");
  }
  return static_cast<int>(version);
}

nlohmann::json ToJson(const RunMetrics& m) {
  nlohmann::json j = nlohmann::json::object();
  j[kFormatVersionKey] = kMetricsFormatVersion;
  for (const MetricsKey& key : MetricsKeys()) j[key.name] = key.write(m);
  return j;
}

RunMetrics RunMetricsFromJson(const nlohmann::json& j, const std::string& source) {
  const JsonReader r(j, source);
  const int version = MetricsFormatVersion(j, source);
  RunMetrics m;
  for (const MetricsKey& key : MetricsKeys()) {
    if (!key.read) continue;
    if (version < key.required_from && !j.contains(key.name)) continue;
    key.read(r, key.name, m);
  }
  return m;
}

}  // namespace phdslam::validation
