#include "validation/runner/evaluation/paired_comparison.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "datasets/test_temp_dir.h"
#include "validation/runner/io/results_layout.h"
#include "validation/runner/testing/results_testing.h"

namespace phdslam::validation {
namespace {

// Group a N=1 beats group b N=1 by 1..6 on seeds 1..6 (a - b = 1..6); seed 7 exists in a only.
// b N=1 has no gospa_m on seed 6. Group c N=10 shares no seed with the others.
constexpr const char* kRuns =
    "estimator,particles,seed,gospa_m,pos_rmse_m\n"
    "a,1,1,11,1\n"
    "a,1,2,12,2\n"
    "a,1,3,13,3\n"
    "a,1,4,14,4\n"
    "a,1,5,15,5\n"
    "a,1,6,16,6\n"
    "a,1,7,17,7\n"
    "b,1,1,10,1\n"
    "b,1,2,10,2\n"
    "b,1,3,10,3\n"
    "b,1,4,10,4\n"
    "b,1,5,10,5\n"
    "b,1,6,,6\n"
    "c,10,100,1,1\n";

TEST(ComparePairs, WilcoxonOverCommonSeedsWithValues) {
  const CsvTable runs = ParseCsv(kRuns, "runs.csv");
  const std::vector<PairedComparison> rows = ComparePairs(runs, {"gospa_m", "pos_rmse_m"}, "r");
  ASSERT_EQ(rows.size(), 2u);  // c shares no seed with a or b

  const PairedComparison& gospa = rows[0];
  EXPECT_EQ(gospa.metric, "gospa_m");
  EXPECT_EQ(gospa.estimator_a, "a");
  EXPECT_EQ(gospa.particles_a, 1);
  EXPECT_EQ(gospa.estimator_b, "b");
  EXPECT_EQ(gospa.test.n, 5u);  // seeds 1..5
  EXPECT_DOUBLE_EQ(gospa.median_a, 13.0);
  EXPECT_DOUBLE_EQ(gospa.median_b, 10.0);
  EXPECT_DOUBLE_EQ(gospa.median_difference, 3.0);  // differences 1..5
  EXPECT_EQ(gospa.test.method, WilcoxonMethod::kExact);
  EXPECT_DOUBLE_EQ(gospa.test.w_plus, 15.0);
  EXPECT_DOUBLE_EQ(gospa.test.statistic, 0.0);
  EXPECT_DOUBLE_EQ(*gospa.test.p_value, 2.0 / 32.0);

  const PairedComparison& position = rows[1];
  EXPECT_EQ(position.metric, "pos_rmse_m");
  EXPECT_EQ(position.test.n, 6u);
  EXPECT_EQ(position.test.n_nonzero, 0u);  // equal on every seed
  EXPECT_EQ(position.test.method, WilcoxonMethod::kNone);
  EXPECT_DOUBLE_EQ(position.median_difference, 0.0);
}

TEST(ComparePairs, RejectsUnknownMetricsAndBadCells) {
  const CsvTable runs = ParseCsv(kRuns, "runs.csv");
  try {
    ComparePairs(runs, {"gospa"}, "r/runs.csv");
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("r/runs.csv: no metric column 'gospa'"), std::string::npos) << message;
    EXPECT_NE(message.find("gospa_m, pos_rmse_m"), std::string::npos) << message;
  }
  EXPECT_THROW(ComparePairs(runs, {"seed"}, "r"), std::invalid_argument);
  EXPECT_THROW(ComparePairs(ParseCsv("estimator,particles,seed,m\na,1,x,2\n", "r"), {"m"}, "r"),
               std::runtime_error);
  EXPECT_THROW(ComparePairs(ParseCsv("estimator,particles,seed,m\na,1,1,two\n", "r"), {"m"}, "r"),
               std::runtime_error);
  EXPECT_THROW(ComparePairs(ParseCsv("estimator,seed,m\na,1,2\n", "r"), {"m"}, "r"),
               std::runtime_error);
}

TEST(WriteComparison, WritesComparisonCsv) {
  const std::filesystem::path dir = datasets::testing::FreshTestDir();
  WriteFileAtomically(dir / kRunsTableFile, kRuns);
  WriteComparison(dir, {"gospa_m"});
  const std::vector<std::string> lines = testing::SplitLines(ReadTextFile(dir / kComparisonFile));
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0],
            "metric,estimator_a,particles_a,estimator_b,particles_b,n,n_nonzero,median_a,median_b,"
            "median_difference,w_plus,w_minus,statistic,z,p_value,method");
  EXPECT_EQ(lines[1], "gospa_m,a,1,b,1,5,5,13,10,3,15,0,0,,0.0625,exact");
}

}  // namespace
}  // namespace phdslam::validation
