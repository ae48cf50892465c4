// Registers the example estimator beside phdslam's own and runs the Monte Carlo runner on one of
// the suite's scenarios, into a results folder that `phdslam compare`, `merge` and the report
// read like any other:
//   nearest_landmark_slam --out DIR [--scenario paper-synthetic] [--seeds 1-5] [--steps 500]
//                         [--estimators nearest-landmark,odometry,phd3] [--particles 1]
#include <cstring>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "nearest_landmark_estimator.h"
#include "validation/runner/experiment/experiment_runner.h"
#include "validation/runner/io/list_arguments.h"
#include "validation/runner/registry/estimator_registry.h"
#include "validation/runner/results/summary.h"

namespace {

namespace v = phdslam::validation;

v::EstimatorEntry NearestLandmarkEntry() {
  v::EstimatorEntry e;
  e.name = "nearest-landmark";
  e.description = "example: dead reckoning and a nearest-landmark averaged map (out of tree)";
  e.parameters = example::NearestLandmarkParamsTable().Descriptions();
  e.resolved_parameters = [](const v::EstimatorRequest& r) {
    v::RequireSingleParticle(r);
    return example::NearestLandmarkParamsTable().ToJson(
        v::ResolveParameters(r, example::NearestLandmarkParamsTable()));
  };
  e.make_online = [](const v::EstimatorRequest& r) {
    return std::make_unique<example::NearestLandmarkEstimator>(
        v::RequireContext(r), v::ResolveParameters(r, example::NearestLandmarkParamsTable()));
  };
  return e;
}

std::string Option(int argc, char** argv, const char* name, const std::string& fallback) {
  for (int i = 1; i + 1 < argc; ++i) {
    if (std::strcmp(argv[i], name) == 0) return argv[i + 1];
  }
  return fallback;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const std::string out = Option(argc, argv, "--out", "");
    if (out.empty()) {
      std::cerr << "usage: nearest_landmark_slam --out DIR [--scenario S] [--seeds A-B] "
                   "[--steps N] [--estimators a,b] [--particles N] [--jobs N]\n"
                   "  --jobs: worker threads (default 0 = one per hardware thread); results do "
                   "not depend on it\n";
      return 2;
    }
    // The registry: phdslam's estimators plus this one.
    std::vector<v::EstimatorEntry> table = v::EstimatorTable();
    table.push_back(NearestLandmarkEntry());

    v::Experiment x;
    x.name = "cpp-example";
    x.scenario = Option(argc, argv, "--scenario", "paper-synthetic");
    x.seeds = v::ParseSeedList(Option(argc, argv, "--seeds", "1-5"));
    x.steps = std::stoi(Option(argc, argv, "--steps", "500"));
    x.particles = v::ParseParticleList(Option(argc, argv, "--particles", "1"));
    const int jobs = std::stoi(Option(argc, argv, "--jobs", "0"));
    if (jobs < 0 || jobs > 1024) throw std::invalid_argument("--jobs must be 0 to 1024");
    x.jobs = jobs;
    for (const std::string& name : v::ParseNameList(
             Option(argc, argv, "--estimators", "nearest-landmark,odometry"), "estimator")) {
      x.estimators.push_back({name});
    }
    v::ExperimentSettings settings;
    settings.out = out;
    settings.show_progress = false;
    const v::ExperimentReport report = v::RunExperiment(x, settings, table);
    std::cout << v::FormatSummaryTable(v::SummariseGroups(v::ReadResults(out)));
    std::size_t failed = 0;
    for (const v::MonteCarloReport& r : report.reports) failed += r.failures.size();
    return failed == 0 ? 0 : 1;
  } catch (const std::exception& e) {
    std::cerr << "nearest_landmark_slam: " << e.what() << "\n";
    return 1;
  }
}
