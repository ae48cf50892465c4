#include "validation/metrics/chi_square.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace phdslam::validation {
namespace {

// Reference quantiles computed to 20 digits with an arbitrary-precision library (mpmath).
struct TableValue {
  double probability;
  double dof;
  double quantile;
};

TEST(ChiSquareQuantile, MatchesTableValues) {
  const TableValue table[] = {
      {0.975, 3, 9.3484036044961458456},    {0.025, 3, 0.21579528262389787679},
      {0.975, 300, 349.8744688299152572},   {0.025, 300, 253.9123226024897287},
      {0.5, 300, 299.33359734921803531},    {0.95, 2, 5.9914645471079802105},
      {0.999, 1, 10.827566170662730649},    {0.01, 1, 0.00015708785790970198404},
      {0.5, 0.5, 0.087347604705746820734},  {0.5, 1, 0.45493642311957275194},
      {0.9, 10, 15.987179172105261648},     {0.995, 1000, 1118.9480663231916378},
      {0.005, 1000, 888.56352318146832413}, {0.025, 4, 0.4844185570879298204},
      {0.975, 4, 11.143286781877795099},    {0.005, 20, 7.4338442629342350571},
      {0.995, 20, 39.996846312938643766},   {1e-6, 2, 2.0000010000006665767e-6},
  };
  for (const auto& t : table) {
    EXPECT_NEAR(ChiSquareQuantile(t.probability, t.dof), t.quantile, 1e-12 * t.quantile)
        << "p = " << t.probability << ", dof = " << t.dof;
  }
}

TEST(ChiSquareQuantile, FarUpperTail) {
  // chi2_2 has Q(x) = exp(-x / 2): the 1 - 1e-9 quantile is 2 ln(1e9) = 41.4465316738928...; the
  // rounding of 1 - 1e-9 to a double alone moves it by about 4e-9 relative.
  EXPECT_NEAR(ChiSquareQuantile(1.0 - 1e-9, 2.0), 41.446531673892822312, 1e-8 * 41.45);
  const double q = 1.0 - 1e-9;
  EXPECT_NEAR(ChiSquareQuantile(q, 2.0), -2.0 * std::log1p(-q), 1e-12 * 41.45);
  EXPECT_EQ(ChiSquareQuantile(0.0, 3.0), 0.0);
  EXPECT_EQ(ChiSquareQuantile(1.0, 3.0), INFINITY);
}

TEST(ChiSquareCdf, KnownValuesAndRoundTrip) {
  EXPECT_NEAR(ChiSquareCdf(7.5, 3), 0.94244154802736359303, 1e-14);
  EXPECT_NEAR(ChiSquareCdf(250, 300), 0.016197049792355001222, 1e-12 * 0.0162);
  EXPECT_NEAR(1.0 - ChiSquareCdf(60, 1), 9.4857375710738483885e-15, 1e-16);
  EXPECT_EQ(ChiSquareCdf(-1.0, 2.0), 0.0);
  for (const double dof : {0.7, 1.0, 2.0, 3.0, 17.0, 300.0}) {
    for (const double p : {1e-8, 0.001, 0.2, 0.5, 0.8, 0.999, 1.0 - 1e-7}) {
      const double x = ChiSquareQuantile(p, dof);
      EXPECT_NEAR(ChiSquareCdf(x, dof), p, 1e-12 * std::min(p, 1.0 - p) + 1e-15)
          << "p = " << p << ", dof = " << dof;
    }
  }
}

TEST(ChiSquareQuantile, RejectsBadInput) {
  EXPECT_THROW(ChiSquareQuantile(1.5, 2.0), std::invalid_argument);
  EXPECT_THROW(ChiSquareQuantile(-0.1, 2.0), std::invalid_argument);
  EXPECT_THROW(ChiSquareQuantile(std::nan(""), 2.0), std::invalid_argument);
  EXPECT_THROW(ChiSquareQuantile(0.5, 0.0), std::invalid_argument);
  EXPECT_THROW(ChiSquareCdf(1.0, -2.0), std::invalid_argument);
}

}  // namespace
}  // namespace phdslam::validation
