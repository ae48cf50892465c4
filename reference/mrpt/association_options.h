// Data-association settings shared by the MRPT baselines, in phdslam's own types so that users of
// the baselines need no MRPT header. They map one to one onto MRPT's TDataAssociationMethod and
// TDataAssociationMetric (mrpt/slam/data_association.h).
#pragma once

#include <string>

namespace phdslam::reference {

enum class AssociationMethod {
  kNearestNeighbour,  ///< mrpt::slam::assocNN: greedy one-to-one, best pair first
  kJcbb,              ///< mrpt::slam::assocJCBB: joint compatibility branch and bound
};

enum class AssociationMetric {
  kMahalanobis,         ///< mrpt::slam::metricMaha: squared Mahalanobis distance
  kMatchingLikelihood,  ///< mrpt::slam::metricML: the Gaussian likelihood of the pairing
};

/// "nn" / "jcbb" and "mahalanobis" / "ml"; the parsers throw std::invalid_argument naming `field`
/// and the accepted values.
std::string ToString(AssociationMethod m);
std::string ToString(AssociationMetric m);
AssociationMethod ParseAssociationMethod(const std::string& s, const std::string& field);
AssociationMetric ParseAssociationMetric(const std::string& s, const std::string& field);

/// Checks an individual-compatibility chi-square quantile: MRPT takes a probability in (0, 1)
/// and gates with chi2inv(quantile, 2). Throws std::invalid_argument naming `field`.
void ValidateChi2Quantile(double quantile, const std::string& field);

}  // namespace phdslam::reference
