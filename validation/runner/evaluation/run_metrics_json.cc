// metrics.json form of RunMetrics.
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
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

// Writes the sufficient statistics of `m` under `<prefix>_count`, `<prefix>_sum<unit>` and
// `<prefix>_sq_sum<unit>2`.
void PutMoments(nlohmann::json& j, const std::string& prefix, const std::string& unit,
                const ErrorMoments& m) {
  j[prefix + "_count"] = m.count;
  j[prefix + "_sum" + unit] = m.sum;
  j[prefix + "_sq_sum" + unit + (unit.empty() ? "" : "2")] = m.sum_sq;
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
  ErrorMoments Moments(const std::string& prefix, const std::string& unit) const {
    ErrorMoments m;
    m.count = Count(prefix + "_count");
    m.sum = Number(prefix + "_sum" + unit);
    m.sum_sq = Number(prefix + "_sq_sum" + unit + (unit.empty() ? "" : "2"));
    return m;
  }

 private:
  [[noreturn]] void Fail(const std::string& key, const std::string& expected) const {
    throw std::runtime_error(source_ + ": field '" + key + "' must be " + expected + ", got " +
                             j_.at(key).dump());
  }
  const nlohmann::json& j_;
  const std::string& source_;
};

// metrics.json keys of the association counts; all null when the run was not scored.
const std::vector<std::pair<std::string, long AssociationCounts::*>>& AssociationFields() {
  static const std::vector<std::pair<std::string, long AssociationCounts::*>> fields = {
      {"da_tp", &AssociationCounts::tp},
      {"da_fn", &AssociationCounts::fn},
      {"da_tn", &AssociationCounts::tn},
      {"da_fp", &AssociationCounts::fp},
      {"da_first_sightings", &AssociationCounts::first_sightings},
      {"da_first_sightings_associated", &AssociationCounts::first_sightings_associated},
      {"da_unreported", &AssociationCounts::unreported},
  };
  return fields;
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
  for (const char* key : kRequiredStatistics) {
    if (j.contains(key) && j.at(key).is_null()) return key;
  }
  return "";
}

nlohmann::json ToJson(const RunMetrics& m) {
  nlohmann::json j = nlohmann::json::object();
  j["steps"] = m.steps;
  j["pos_rmse_m"] = OrNull(m.position_m.Rms());
  j["pos_err_std_m"] = OrNull(m.position_m.Std());
  PutMoments(j, "pos_err", "_m", m.position_m);
  j["heading_rmse_deg"] = OrNull(m.heading_deg.Rms());
  j["heading_err_std_deg"] = OrNull(m.heading_deg.Std());
  PutMoments(j, "heading_err", "_deg", m.heading_deg);
  const auto gospa_part = [&](auto member) {
    return m.gospa ? nlohmann::json((*m.gospa).*member) : nlohmann::json(nullptr);
  };
  j["gospa_m"] = gospa_part(&FinalMapGospa::gospa);
  j["gospa_localisation_mp"] = gospa_part(&FinalMapGospa::localisation);
  j["gospa_missed_mp"] = gospa_part(&FinalMapGospa::missed);
  j["gospa_false_mp"] = gospa_part(&FinalMapGospa::false_);
  j["n_missed"] = gospa_part(&FinalMapGospa::n_missed);
  j["n_false"] = gospa_part(&FinalMapGospa::n_false);
  j["gospa_c"] = m.gospa_c;
  j["gospa_p"] = m.gospa_p;
  j["map_size"] = m.map_size;
  j["truth_map_size"] = OrNull(m.truth_map_size);
  j["ess_pct"] = OrNull(m.ess_pct);
  j["resampling_pct"] = OrNull(m.resampling_pct);
  j["hypotheses_mean"] = OrNull(m.hypotheses_mean);
  j["map_components_mean"] = OrNull(m.map_components_mean);
  j["pose_nees_mean"] = OrNull(m.pose_nees.Mean());
  j["pose_nees_count"] = m.pose_nees.count;
  j["pose_nees_sum"] = m.pose_nees.sum;
  j["landmark_nees_mean"] = OrNull(m.landmark_nees.Mean());
  j["landmark_nees_count"] = m.landmark_nees.count;
  j["landmark_nees_sum"] = m.landmark_nees.sum;
  j["pose_coverage_inside"] = m.pose_coverage_inside;
  j["pose_nees_rb_mean"] = OrNull(m.pose_nees_rb.Mean());
  j["pose_nees_rb_count"] = m.pose_nees_rb.count;
  j["pose_nees_rb_sum"] = m.pose_nees_rb.sum;
  j["pose_coverage_rb_inside"] = m.pose_coverage_rb_inside;
  j["gps_nees_rb_mean"] = OrNull(m.gps_nees_rb.Mean());
  j["gps_nees_rb_count"] = m.gps_nees_rb.count;
  j["gps_nees_rb_sum"] = m.gps_nees_rb.sum;
  j["gps_coverage_rb_inside"] = m.gps_coverage_rb_inside;
  j["nis_sum"] = m.nis_sum;
  j["nis_count"] = m.nis_count;
  j["nis_mean"] =
      OrNull(m.nis_count > 0 ? std::optional<double>(m.nis_sum / static_cast<double>(m.nis_count))
                             : std::nullopt);
  const std::optional<AssociationCounts>& da = m.association;
  const auto da_count = [&](long AssociationCounts::*member) {
    return da ? nlohmann::json((*da).*member) : nlohmann::json(nullptr);
  };
  for (const auto& [key, member] : AssociationFields()) j[key] = da_count(member);
  j["da_tpr"] = OrNull(da ? std::optional<double>(da->tpr()) : std::nullopt);
  j["da_tnr"] = OrNull(da ? std::optional<double>(da->tnr()) : std::nullopt);
  j["gps_matched_steps"] = OrNull(m.gps_matched_steps);
  j["solver_iterations"] = OrNull(m.solver_iterations);
  j["solver_converged"] =
      m.solver_converged ? nlohmann::json(*m.solver_converged) : nlohmann::json(nullptr);
  j["solves"] = OrNull(m.solves);
  j["unconverged_solves"] = OrNull(m.unconverged_solves);
  j["ms_per_step_mean"] = OrNull(m.step_ms.Mean());
  j["ms_per_step_std"] = OrNull(m.step_ms.Std());
  j["ms_count"] = m.step_ms.count;
  j["ms_sum"] = m.step_ms.sum;
  j["ms_sq_sum"] = m.step_ms.sum_sq;
  j["ms_total"] = m.total_ms;
  return j;
}

RunMetrics RunMetricsFromJson(const nlohmann::json& j, const std::string& source) {
  const JsonReader r(j, source);
  RunMetrics m;
  m.steps = r.Count("steps");
  m.position_m = r.Moments("pos_err", "_m");
  m.heading_deg = r.Moments("heading_err", "_deg");
  if (const std::optional<double> g = r.OptionalNumber("gospa_m")) {
    FinalMapGospa gospa;
    gospa.gospa = *g;
    gospa.localisation = r.Number("gospa_localisation_mp");
    gospa.missed = r.Number("gospa_missed_mp");
    gospa.false_ = r.Number("gospa_false_mp");
    gospa.n_missed = static_cast<int>(r.Count("n_missed"));
    gospa.n_false = static_cast<int>(r.Count("n_false"));
    m.gospa = gospa;
  }
  m.gospa_c = r.Number("gospa_c");
  m.gospa_p = r.Number("gospa_p");
  m.map_size = r.Count("map_size");
  m.truth_map_size = r.OptionalCount("truth_map_size");
  m.ess_pct = r.OptionalNumber("ess_pct");
  m.resampling_pct = r.OptionalNumber("resampling_pct");
  m.hypotheses_mean = r.OptionalNumber("hypotheses_mean");
  m.map_components_mean = r.OptionalNumber("map_components_mean");
  // NEES values are finite and non-negative, so a sum written as null overflowed: +infinity
  // (e.g. collapsed particles without resampling, where single values reach 1e300).
  const auto nees_sum = [&](const std::string& key) {
    return r.OptionalNumber(key).value_or(std::numeric_limits<double>::infinity());
  };
  m.pose_nees.count = r.Count("pose_nees_count");
  m.pose_nees.sum = nees_sum("pose_nees_sum");
  m.landmark_nees.count = r.Count("landmark_nees_count");
  m.landmark_nees.sum = nees_sum("landmark_nees_sum");
  // Consistency fields: absent in folders written before they existed (read as none).
  if (j.contains("pose_nees_rb_count")) {
    m.pose_coverage_inside = r.Count("pose_coverage_inside");
    m.pose_nees_rb.count = r.Count("pose_nees_rb_count");
    m.pose_nees_rb.sum = nees_sum("pose_nees_rb_sum");
    m.pose_coverage_rb_inside = r.Count("pose_coverage_rb_inside");
    m.gps_nees_rb.count = r.Count("gps_nees_rb_count");
    m.gps_nees_rb.sum = nees_sum("gps_nees_rb_sum");
    m.gps_coverage_rb_inside = r.Count("gps_coverage_rb_inside");
    m.nis_sum = nees_sum("nis_sum");
    m.nis_count = r.Count("nis_count");
  }
  // Association counts: absent in folders written before they existed, null when not scored.
  if (j.contains("da_tp") && !j.at("da_tp").is_null()) {
    AssociationCounts da;
    for (const auto& [key, member] : AssociationFields()) {
      da.*member = static_cast<long>(r.Count(key));
    }
    m.association = da;
  }
  m.gps_matched_steps = r.OptionalCount("gps_matched_steps");
  // Absent in folders written before it existed.
  if (j.contains("solver_iterations")) m.solver_iterations = r.OptionalCount("solver_iterations");
  if (j.contains("solver_converged") && !j.at("solver_converged").is_null()) {
    if (!j.at("solver_converged").is_boolean()) {
      throw std::runtime_error(source +
                               ": field 'solver_converged' must be true, false or null, got " +
                               j.at("solver_converged").dump());
    }
    m.solver_converged = j.at("solver_converged").get<bool>();
  }
  if (j.contains("solves")) m.solves = r.OptionalCount("solves");
  if (j.contains("unconverged_solves"))
    m.unconverged_solves = r.OptionalCount("unconverged_solves");
  m.step_ms.count = r.Count("ms_count");
  m.step_ms.sum = r.Number("ms_sum");
  m.step_ms.sum_sq = r.Number("ms_sq_sum");
  m.total_ms = r.Number("ms_total");
  return m;
}

}  // namespace phdslam::validation
