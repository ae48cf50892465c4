// Chi-square distribution function and quantiles (regularised incomplete gamma), for NEES bounds.
#pragma once

namespace phdslam::validation {

/// P(X <= x) for X ~ chi-square with `dof` > 0 degrees of freedom (x <= 0 gives 0).
/// Throws std::invalid_argument when dof is not a finite positive number or x is NaN.
double ChiSquareCdf(double x, double dof);

/// The x with ChiSquareCdf(x, dof) = probability, to about 1e-12 relative (limited in the far
/// upper tail by the rounding of `probability` itself). probability 0 gives 0 and 1 gives +inf.
/// Throws std::invalid_argument unless 0 <= probability <= 1 and dof is finite and positive.
double ChiSquareQuantile(double probability, double dof);

}  // namespace phdslam::validation
