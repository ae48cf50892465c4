#include "reference/pcrb/information_reduction.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace phdslam::reference::pcrb {
namespace {

TEST(InformationReduction, IsTheDetectionProbabilityWithoutClutter) {
  EXPECT_EQ(InformationReductionFactor({0.7, 0.0, 5.0, 1000}, 1), 0.7);
  EXPECT_EQ(InformationReductionFactor({1.0, 0.0, 5.0, 1000}, 1), 1.0);
}

TEST(InformationReduction, FallsWithTheClutterDensity) {
  double previous = 1.0;
  for (double beta : {1e-3, 1e-2, 5e-2, 0.2}) {
    const double q = InformationReductionFactor({1.0, beta, 5.0, 40000}, 3);
    EXPECT_LT(q, previous) << "beta " << beta;
    EXPECT_GT(q, 0.0);
    previous = q;
  }
  // Sparse clutter barely matters; dense clutter (about 16 points in the disc) costs much.
  EXPECT_GT(InformationReductionFactor({1.0, 1e-3, 5.0, 40000}, 3), 0.97);
  EXPECT_LT(InformationReductionFactor({1.0, 0.2, 5.0, 40000}, 3), 0.8);
}

// A miss competes with every clutter point through the (1 - pD) beta term, so the factor falls
// faster than pD itself once there is clutter.
TEST(InformationReduction, WithClutterFallsWithTheDetectionProbability) {
  const double q60 = InformationReductionFactor({0.6, 0.05, 5.0, 40000}, 5);
  const double q90 = InformationReductionFactor({0.9, 0.05, 5.0, 40000}, 5);
  const double q100 = InformationReductionFactor({1.0, 0.05, 5.0, 40000}, 5);
  EXPECT_GT(q60, 0.0);
  EXPECT_LT(q60, 0.6 * q100);
  EXPECT_LT(q60, q90);
  EXPECT_LT(q90, q100);
}

TEST(InformationReduction, ConvergesWithTheNumberOfSamples) {
  const double a = InformationReductionFactor({0.9, 0.05, 5.0, 200000}, 11);
  const double b = InformationReductionFactor({0.9, 0.05, 5.0, 200000}, 12);
  EXPECT_NEAR(a, b, 0.01);
}

TEST(InformationReduction, RefusesSettingsOutOfRange) {
  EXPECT_THROW(InformationReductionFactor({0.0, 0.0, 5.0, 1000}, 1), std::invalid_argument);
  EXPECT_THROW(InformationReductionFactor({1.2, 0.0, 5.0, 1000}, 1), std::invalid_argument);
  EXPECT_THROW(InformationReductionFactor({0.9, -1.0, 5.0, 1000}, 1), std::invalid_argument);
  EXPECT_THROW(InformationReductionFactor({0.9, 0.1, 0.0, 1000}, 1), std::invalid_argument);
}

}  // namespace
}  // namespace phdslam::reference::pcrb
