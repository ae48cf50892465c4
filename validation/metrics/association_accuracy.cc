#include "validation/metrics/association_accuracy.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "datasets/scenario.h"

namespace phdslam::validation {
namespace {

double Ratio(long num, long den) {
  if (den == 0) return std::numeric_limits<double>::quiet_NaN();
  return static_cast<double>(num) / static_cast<double>(den);
}

// True when the association is reported; throws on a half-NaN or infinite mean.
bool IsAssociated(const Landmark& a, std::size_t j) {
  const bool nan_x = std::isnan(a(0));
  const bool nan_y = std::isnan(a(1));
  if (nan_x && nan_y) return false;
  if (nan_x || nan_y || !a.allFinite()) {
    throw std::invalid_argument("AccumulateAssociation: association " + std::to_string(j) + " = (" +
                                std::to_string(a(0)) + ", " + std::to_string(a(1)) +
                                "); expected a finite landmark mean or NaN in both coordinates");
  }
  return true;
}

// Index of the true landmark nearest to p (first on ties).
std::size_t Nearest(const std::vector<Landmark>& truth, const Landmark& p) {
  std::size_t best = 0;
  double best_d2 = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const double d2 = (truth[i] - p).squaredNorm();
    if (d2 < best_d2) {
      best_d2 = d2;
      best = i;
    }
  }
  return best;
}

}  // namespace

double AssociationCounts::tpr() const { return Ratio(tp, tp + fn); }

double AssociationCounts::tnr() const { return Ratio(tn, tn + fp); }

AssociationCounts& AssociationCounts::operator+=(const AssociationCounts& other) {
  tp += other.tp;
  fn += other.fn;
  tn += other.tn;
  fp += other.fp;
  first_sightings += other.first_sightings;
  first_sightings_associated += other.first_sightings_associated;
  unreported += other.unreported;
  return *this;
}

void AccumulateAssociation(const std::vector<int>& origins,
                           const std::vector<Landmark>& association,
                           const std::vector<Landmark>& truth, std::vector<bool>& seen_before,
                           double max_distance, AssociationCounts& counts) {
  if (!(max_distance > 0.0)) {
    throw std::invalid_argument(
        "AccumulateAssociation: max_distance = " + std::to_string(max_distance) + "; expected > 0");
  }
  if (!association.empty() && association.size() != origins.size()) {
    throw std::invalid_argument("AccumulateAssociation: " + std::to_string(association.size()) +
                                " associations for " + std::to_string(origins.size()) +
                                " origin labels; expected one per measurement (or none)");
  }
  if (seen_before.empty()) seen_before.assign(truth.size(), false);
  if (seen_before.size() != truth.size()) {
    throw std::invalid_argument("AccumulateAssociation: seen_before has " +
                                std::to_string(seen_before.size()) + " entries for " +
                                std::to_string(truth.size()) + " true landmarks");
  }
  // Validate every label before counting, so a bad step leaves `counts` unchanged.
  for (std::size_t j = 0; j < origins.size(); ++j) {
    const int o = origins[j];
    if (o < datasets::kClutter || o >= static_cast<int>(truth.size())) {
      throw std::invalid_argument(
          "AccumulateAssociation: origin label " + std::to_string(o) + " of measurement " +
          std::to_string(j) + "; expected clutter (-1) or a landmark index in [0, " +
          std::to_string(truth.size()) + ") (real data without known origins cannot be scored)");
    }
  }
  AssociationCounts step;
  if (association.empty()) step.unreported = static_cast<long>(origins.size());
  for (std::size_t j = 0; j < association.size(); ++j) {
    const int o = origins[j];
    const bool associated = IsAssociated(association[j], j);
    if (o == datasets::kClutter) {
      ++(associated ? step.fp : step.tn);
      continue;
    }
    const auto i = static_cast<std::size_t>(o);
    if (!seen_before[i]) {
      ++step.first_sightings;
      if (associated) ++step.first_sightings_associated;
      continue;
    }
    const bool correct = associated && Nearest(truth, association[j]) == i &&
                         (association[j] - truth[i]).norm() <= max_distance;
    ++(correct ? step.tp : step.fn);
  }
  for (int o : origins) {
    if (o >= 0) seen_before[static_cast<std::size_t>(o)] = true;
  }
  counts += step;
}

}  // namespace phdslam::validation
