#include "reference/mrpt/association_options.h"

#include <stdexcept>

namespace phdslam::reference {

std::string ToString(AssociationMethod m) { return m == AssociationMethod::kJcbb ? "jcbb" : "nn"; }

std::string ToString(AssociationMetric m) {
  return m == AssociationMetric::kMatchingLikelihood ? "ml" : "mahalanobis";
}

AssociationMethod ParseAssociationMethod(const std::string& s, const std::string& field) {
  if (s == "nn") return AssociationMethod::kNearestNeighbour;
  if (s == "jcbb") return AssociationMethod::kJcbb;
  throw std::invalid_argument(field + ": expected \"nn\" or \"jcbb\", got \"" + s + "\"");
}

AssociationMetric ParseAssociationMetric(const std::string& s, const std::string& field) {
  if (s == "mahalanobis") return AssociationMetric::kMahalanobis;
  if (s == "ml") return AssociationMetric::kMatchingLikelihood;
  throw std::invalid_argument(field + ": expected \"mahalanobis\" or \"ml\", got \"" + s + "\"");
}

void ValidateChi2Quantile(double quantile, const std::string& field) {
  if (!(quantile > 0.0 && quantile < 1.0)) {
    throw std::invalid_argument(field + ": expected a probability in (0, 1), got " +
                                std::to_string(quantile));
  }
}

}  // namespace phdslam::reference
