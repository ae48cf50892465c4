#include "reference/ceres/g2o_export.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "reference/ceres/batch_smoother.h"
#include "reference/ceres/test_scenario.h"
#include "src/models/range_bearing_model.h"

namespace phdslam::reference {
namespace {

/// A parsed g2o file: numeric fields of each record, by tag, in file order.
struct G2oFile {
  std::map<std::string, std::vector<std::vector<double>>> records;
  int comments = 0;
};

/// Parses the subset of g2o written by ExportG2o, failing the test on any malformed line.
G2oFile Parse(const std::filesystem::path& path) {
  const std::map<std::string, std::size_t> fields = {
      {"VERTEX_SE2", 4}, {"VERTEX_XY", 3}, {"FIX", 1}, {"EDGE_SE2", 11}, {"EDGE_SE2_XY", 7}};
  G2oFile out;
  std::ifstream is(path);
  EXPECT_TRUE(is.good()) << path;
  std::string line;
  int number = 0;
  while (std::getline(is, line)) {
    ++number;
    if (line.empty()) continue;
    if (line[0] == '#') {
      ++out.comments;
      continue;
    }
    std::istringstream ls(line);
    std::string tag;
    ls >> tag;
    const auto it = fields.find(tag);
    if (it == fields.end()) {
      ADD_FAILURE() << "line " << number << ": unknown tag " << tag;
      continue;
    }
    std::vector<double> values;
    double v = 0.0;
    while (ls >> v) values.push_back(v);
    EXPECT_TRUE(ls.eof()) << "line " << number << ": non-numeric field in: " << line;
    EXPECT_EQ(values.size(), it->second) << "line " << number << ": " << line;
    out.records[tag].push_back(values);
  }
  return out;
}

std::filesystem::path TempFile(const std::string& name) {
  return std::filesystem::path(::testing::TempDir()) / name;
}

TEST(ExportG2o, WritesEveryVertexAndEdgeAndParsesBack) {
  testing::CircleScenarioOptions c;
  c.clutter_rate = 2.0;
  const datasets::Scenario s = testing::MakeCircleScenario(c);
  SmootherOptions o;
  o.compute_covariances = false;
  BatchSmoother smoother(o);
  const datasets::BatchResult r = smoother.Solve(s);
  const auto path = TempFile("circle.g2o");
  ExportG2o(path, s, r, smoother.association());
  const G2oFile g = Parse(path);

  std::size_t associated = 0;
  for (const auto& step : smoother.association()) {
    for (int i : step) associated += i >= 0 ? 1 : 0;
  }
  const std::size_t k = s.steps.size();
  const std::size_t m = r.map.means.size();
  EXPECT_GT(g.comments, 5);
  ASSERT_EQ(g.records.at("VERTEX_SE2").size(), k);
  ASSERT_EQ(g.records.at("VERTEX_XY").size(), m);
  ASSERT_EQ(g.records.at("FIX").size(), 1u);
  EXPECT_EQ(g.records.at("FIX")[0][0], 0.0);
  ASSERT_EQ(g.records.at("EDGE_SE2").size(), k - 1);
  ASSERT_EQ(g.records.at("EDGE_SE2_XY").size(), associated);
  EXPECT_LT(associated, [&] {
    std::size_t all = 0;
    for (const auto& step : s.steps) all += step.data.measurements.size();
    return all;
  }());  // clutter is not exported

  // Vertex values are the solution, at full precision.
  const auto& v7 = g.records.at("VERTEX_SE2")[7];
  EXPECT_EQ(v7[0], 7.0);
  EXPECT_EQ(Pose(v7[1], v7[2], v7[3]), r.poses[7]);
  const auto& l3 = g.records.at("VERTEX_XY")[3];
  EXPECT_EQ(l3[0], double(k + 3));
  EXPECT_EQ(Landmark(l3[1], l3[2]), r.map.means[3]);

  // The first odometry edge links poses 0 and 1 with step 1's increment and an SPD information.
  const auto& e = g.records.at("EDGE_SE2")[0];
  EXPECT_EQ(e[0], 0.0);
  EXPECT_EQ(e[1], 1.0);
  const OdometryIncrement inc = ScenarioOdometry(s, {})[1];
  EXPECT_NEAR(e[2], inc.delta(0), 1e-12);
  EXPECT_NEAR(e[4], inc.delta(2), 1e-12);
  Mat3 info;
  info << e[5], e[6], e[7], e[6], e[8], e[9], e[7], e[9], e[10];
  EXPECT_LT((info * inc.covariance - Mat3::Identity()).cwiseAbs().maxCoeff(), 1e-6);

  // The first range-bearing edge: the inverse model in the frame of its pose, and (G R G^T)^-1.
  std::size_t step = 0;
  std::size_t j = 0;
  [&] {
    for (step = 0; step < k; ++step) {
      for (j = 0; j < smoother.association()[step].size(); ++j) {
        if (smoother.association()[step][j] >= 0) return;
      }
    }
  }();
  ASSERT_LT(step, k);
  const auto& b = g.records.at("EDGE_SE2_XY")[0];
  const Measurement z = s.steps[step].data.measurements[j];
  EXPECT_EQ(b[0], double(step));
  EXPECT_EQ(b[1], double(k + static_cast<std::size_t>(smoother.association()[step][j])));
  EXPECT_NEAR(b[2], z(0) * std::cos(z(1)), 1e-12);
  EXPECT_NEAR(b[3], z(0) * std::sin(z(1)), 1e-12);
  Mat2 bi;
  bi << b[4], b[5], b[5], b[6];
  const Mat2 cov = models::BirthCovariance(Pose::Zero(), z, s.sensor.noise_cov);
  EXPECT_LT((bi * cov - Mat2::Identity()).cwiseAbs().maxCoeff(), 1e-6);
}

TEST(ExportG2o, AnchorsAPropagatingFirstStepToTheFixedInitialPose) {
  testing::CircleScenarioOptions c;
  c.first_step_propagates = true;
  c.steps = 30;
  const datasets::Scenario s = testing::MakeCircleScenario(c);
  SmootherOptions o;
  o.compute_covariances = false;
  BatchSmoother smoother(o);
  const datasets::BatchResult r = smoother.Solve(s);
  const auto path = TempFile("anchored.g2o");
  ExportG2o(path, s, r, smoother.association());
  const G2oFile g = Parse(path);
  const double anchor = double(s.steps.size() + r.map.means.size());
  ASSERT_EQ(g.records.at("VERTEX_SE2").size(), s.steps.size() + 1);
  EXPECT_EQ(g.records.at("VERTEX_SE2").back()[0], anchor);
  EXPECT_EQ(g.records.at("FIX")[0][0], anchor);
  ASSERT_EQ(g.records.at("EDGE_SE2").size(), s.steps.size());
  EXPECT_EQ(g.records.at("EDGE_SE2")[0][0], anchor);
  EXPECT_EQ(g.records.at("EDGE_SE2")[0][1], 0.0);
}

TEST(ExportG2o, RejectsMismatchedInputs) {
  const datasets::Scenario s = testing::MakeCircleScenario({});
  SmootherOptions o;
  o.compute_covariances = false;
  BatchSmoother smoother(o);
  const datasets::BatchResult r = smoother.Solve(s);
  auto association = smoother.association();
  association[2].push_back(0);
  EXPECT_THROW(ExportG2o(TempFile("bad.g2o"), s, r, association), std::invalid_argument);
  association = smoother.association();
  association[2][0] = static_cast<int>(r.map.means.size());
  EXPECT_THROW(ExportG2o(TempFile("bad.g2o"), s, r, association), std::invalid_argument);
  EXPECT_THROW(ExportG2o("/nonexistent-dir/x.g2o", s, r, smoother.association()),
               std::runtime_error);
}

}  // namespace
}  // namespace phdslam::reference
