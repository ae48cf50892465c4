#include "validation/metrics/association_accuracy.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "datasets/scenario.h"

namespace phdslam::validation {
namespace {

constexpr int kC = datasets::kClutter;
const Landmark kNone = Landmark::Constant(std::numeric_limits<double>::quiet_NaN());

const std::vector<Landmark>& Truth() {
  static const std::vector<Landmark> truth = {Landmark(0.0, 0.0), Landmark(10.0, 0.0),
                                              Landmark(0.0, 10.0), Landmark(30.0, 30.0)};
  return truth;
}

TEST(AssociationAccuracy, CountsEachOutcomeOfAHandMadeSequence) {
  std::vector<bool> seen;  // sized on first use
  AssociationCounts c;
  // Step 0: landmarks 0 and 1 are first sightings (one of them wrongly associated); two clutter
  // points, one associated (FP) and one not (TN).
  AccumulateAssociation({0, 1, kC, kC}, {kNone, Landmark(0.5, 0.2), kNone, Landmark(9.0, 1.0)},
                        Truth(), seen, 5.0, c);
  EXPECT_EQ(seen, std::vector<bool>({true, true, false, false}));
  EXPECT_EQ(c.first_sightings, 2);
  EXPECT_EQ(c.first_sightings_associated, 1);
  EXPECT_EQ(c.tn, 1);
  EXPECT_EQ(c.fp, 1);
  EXPECT_EQ(c.tp + c.fn, 0);

  // Step 1: landmark 0 associated near its truth (TP); landmark 1 not associated (FN);
  // landmark 2 first sighting; clutter not associated (TN).
  AccumulateAssociation({0, 1, 2, kC}, {Landmark(0.4, -0.3), kNone, kNone, kNone}, Truth(), seen,
                        5.0, c);
  EXPECT_EQ(c.tp, 1);
  EXPECT_EQ(c.fn, 1);
  EXPECT_EQ(c.tn, 2);
  EXPECT_EQ(c.first_sightings, 3);

  // Step 2: landmark 1 associated with landmark 0's component (FN: wrong landmark); landmark 2
  // associated with a mean whose nearest truth is landmark 2 but 6 m away (FN: too far);
  // landmark 0 at 4.9 m (TP).
  AccumulateAssociation({1, 2, 0}, {Landmark(1.0, 0.0), Landmark(0.0, 16.0), Landmark(4.9, 0.0)},
                        Truth(), seen, 5.0, c);
  EXPECT_EQ(c.tp, 2);
  EXPECT_EQ(c.fn, 3);
  EXPECT_EQ(c.first_sightings, 3);
  EXPECT_EQ(c.first_sightings_associated, 1);
  EXPECT_EQ(seen, std::vector<bool>({true, true, true, false}));
  EXPECT_DOUBLE_EQ(c.tpr(), 2.0 / 5.0);
  EXPECT_DOUBLE_EQ(c.tnr(), 2.0 / 3.0);
}

TEST(AssociationAccuracy, LandmarkMeasuredTwiceInItsFirstStepIsTwoFirstSightings) {
  std::vector<bool> seen(4, false);
  AssociationCounts c;
  AccumulateAssociation({3, 3}, {kNone, Landmark(30.0, 30.0)}, Truth(), seen, 5.0, c);
  EXPECT_EQ(c.first_sightings, 2);
  EXPECT_EQ(c.first_sightings_associated, 1);
  EXPECT_EQ(c.tp + c.fn + c.tn + c.fp, 0);
  EXPECT_TRUE(seen[3]);
}

TEST(AssociationAccuracy, RatesAndPooling) {
  AssociationCounts a;
  EXPECT_TRUE(std::isnan(a.tpr()));
  EXPECT_TRUE(std::isnan(a.tnr()));
  a.tp = 9;
  a.fn = 1;
  a.tn = 0;
  a.fp = 4;
  EXPECT_DOUBLE_EQ(a.tpr(), 0.9);
  EXPECT_DOUBLE_EQ(a.tnr(), 0.0);
  AssociationCounts b;
  b.tp = 1;
  b.fn = 9;
  b.tn = 6;
  b.first_sightings = 3;
  a += b;
  EXPECT_EQ(a.tp, 10);
  EXPECT_EQ(a.fn, 10);
  EXPECT_EQ(a.tn, 6);
  EXPECT_EQ(a.fp, 4);
  EXPECT_EQ(a.first_sightings, 3);
  EXPECT_DOUBLE_EQ(a.tpr(), 0.5);
  EXPECT_DOUBLE_EQ(a.tnr(), 0.6);
}

TEST(AssociationAccuracy, AStepWithoutReportedAssociationIsCountedAsUnreported) {
  std::vector<bool> seen;
  AssociationCounts c;
  AccumulateAssociation({}, {}, Truth(), seen, 5.0, c);
  EXPECT_EQ(seen.size(), 4u);
  EXPECT_EQ(c.tp + c.fn + c.tn + c.fp + c.first_sightings + c.unreported, 0);
  // An estimator that reports no association: nothing is scored, the landmarks become seen.
  AccumulateAssociation({0, kC, 1}, {}, Truth(), seen, 5.0, c);
  EXPECT_EQ(c.unreported, 3);
  EXPECT_EQ(c.tp + c.fn + c.tn + c.fp + c.first_sightings, 0);
  EXPECT_EQ(seen, std::vector<bool>({true, true, false, false}));
  EXPECT_TRUE(std::isnan(c.tpr()));
  EXPECT_TRUE(std::isnan(c.tnr()));
  // The next reported step scores landmark 0 as a positive (seen at the unreported step).
  AccumulateAssociation({0, kC}, {Landmark(0.1, 0.1), kNone}, Truth(), seen, 5.0, c);
  EXPECT_EQ(c.tp, 1);
  EXPECT_EQ(c.tn, 1);
  EXPECT_EQ(c.unreported, 3);
  AssociationCounts pooled;
  pooled += c;
  EXPECT_EQ(pooled.unreported, 3);
}

TEST(AssociationAccuracy, InfiniteMaxDistanceScoresTheLandmarkIdentityAlone) {
  std::vector<bool> seen(4, true);
  AssociationCounts c;
  // 8 m from landmark 3 but still nearest to it: FN at 5 m, TP without a distance limit.
  AccumulateAssociation({3}, {Landmark(30.0, 22.0)}, Truth(), seen, 5.0, c);
  EXPECT_EQ(c.fn, 1);
  AccumulateAssociation({3}, {Landmark(30.0, 22.0)}, Truth(), seen,
                        std::numeric_limits<double>::infinity(), c);
  EXPECT_EQ(c.tp, 1);
}

TEST(AssociationAccuracy, RejectsBadInputWithoutChangingState) {
  std::vector<bool> seen(4, false);
  seen[0] = true;
  AssociationCounts c;
  const std::vector<Landmark> one = {Landmark(0.0, 0.0)};
  EXPECT_THROW(AccumulateAssociation({0, 1}, one, Truth(), seen, 5.0, c), std::invalid_argument);
  EXPECT_THROW(AccumulateAssociation({-2}, {kNone}, Truth(), seen, 5.0, c),
               std::invalid_argument);  // unknown origin (real data)
  EXPECT_THROW(AccumulateAssociation({4}, {kNone}, Truth(), seen, 5.0, c), std::invalid_argument);
  EXPECT_THROW(AccumulateAssociation({0}, one, Truth(), seen, 0.0, c), std::invalid_argument);
  EXPECT_THROW(AccumulateAssociation({0, 1}, {Landmark(0.0, 0.0), Landmark(std::nan(""), 1.0)},
                                     Truth(), seen, 5.0, c),
               std::invalid_argument);
  EXPECT_THROW(AccumulateAssociation({0}, {Landmark(std::numeric_limits<double>::infinity(), 0.0)},
                                     Truth(), seen, 5.0, c),
               std::invalid_argument);
  std::vector<bool> wrong_size(3, false);
  EXPECT_THROW(AccumulateAssociation({0}, one, Truth(), wrong_size, 5.0, c), std::invalid_argument);
  EXPECT_EQ(c.tp + c.fn + c.tn + c.fp + c.first_sightings, 0);
  EXPECT_EQ(seen, std::vector<bool>({true, false, false, false}));
}

}  // namespace
}  // namespace phdslam::validation
