// phdslam_authors_replay: runs phdslam's phd3 or phd1 on one seed of a registered scenario with
// the random draws another implementation recorded (src/core/draw_replay.h) in place of its
// seeded stream, and writes the inside of every step as step-trace CSV files
// (reference/authors/step_trace_writer.h), for reference/authors/compare_traces.py to set beside
// the authors' trace; with --out, also its estimate (trajectory.tum and the final map.csv) in the
// format `phdslam ingest` reads, so that the replayed runs can be scored and compared as any other
// estimator's (reference/authors/README.md, "Replaying the draws in phdslam"). A program, so it
// lives with the programs: it stands on the runner's registries (validation/), which
// reference/ lies below.
//
//   phdslam_authors_replay --draws DRAWS.csv [--trace DIR] [--out DIR] [--scenario paper-synthetic]
//                          --seed S [--steps K] [--variant phd3] [--particles N] [--map-every M]
//                          [--set key=value ...] [--data-dir DIR]
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "datasets/map_io.h"
#include "datasets/trajectory_io.h"
#include "reference/authors/step_trace_writer.h"
#include "src/core/draw_replay.h"
#include "src/filters/phd_slam_family.h"
#include "src/filters/phd_slam_params_json.h"
#include "validation/runner/registry/estimator_registry.h"
#include "validation/runner/registry/scenario_registry.h"

namespace phdslam::apps {
namespace {

constexpr const char* kUsage =
    "usage: phdslam_authors_replay --draws FILE [--trace DIR] [--out DIR] --seed S "
    "[--scenario NAME] [--steps K] [--variant phd3|phd1] [--particles N] [--map-every M] "
    "[--set key=value]... [--data-dir DIR]\n"
    "Runs phd3 (or phd1) with the recorded draws of FILE (step,particle,purpose,index,value) in\n"
    "place of its seeded random stream. --trace DIR: per-step traces into DIR; --out DIR: the\n"
    "estimate as DIR/trajectory.tum and the final map estimate as DIR/map.csv, the files\n"
    "`phdslam ingest --from` reads per seed (one of the two is required;\n"
    "reference/authors/README.md).\n";

struct Options {
  std::string draws;
  std::string trace;
  std::string out;
  std::string scenario = "paper-synthetic";
  std::string variant = "phd3";
  std::uint64_t seed = 0;
  int particles = 1;
  int map_every = 0;
  validation::ScenarioOptions scenario_options;
  nlohmann::json overrides = nlohmann::json::object();
};

nlohmann::json ParseValue(const std::string& text) {
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error&) {
    return text;  // a bare word, e.g. an enum name
  }
}

Options ParseOptions(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--help" || a == "-h") {
      std::cout << kUsage;
      std::exit(0);
    }
    if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
    const std::string v = argv[++i];
    if (a == "--draws") {
      o.draws = v;
    } else if (a == "--trace") {
      o.trace = v;
    } else if (a == "--out") {
      o.out = v;
    } else if (a == "--scenario") {
      o.scenario = v;
    } else if (a == "--variant") {
      o.variant = v;
    } else if (a == "--seed") {
      o.seed = std::stoull(v);
    } else if (a == "--steps") {
      o.scenario_options.steps = std::stoi(v);
    } else if (a == "--particles") {
      o.particles = std::stoi(v);
    } else if (a == "--map-every") {
      o.map_every = std::stoi(v);
    } else if (a == "--data-dir") {
      o.scenario_options.data_dir = v;
    } else if (a == "--set") {
      const auto eq = v.find('=');
      if (eq == std::string::npos)
        throw std::invalid_argument("--set " + v + ": expected key=value");
      o.overrides[v.substr(0, eq)] = ParseValue(v.substr(eq + 1));
    } else {
      throw std::invalid_argument("unknown option " + a);
    }
  }
  if (o.draws.empty() || o.seed == 0) {
    throw std::invalid_argument("--draws and --seed (>= 1) are required");
  }
  if (o.trace.empty() && o.out.empty()) {
    throw std::invalid_argument("--trace DIR or --out DIR (or both) is required");
  }
  if (o.variant != "phd3" && o.variant != "phd1") {
    throw std::invalid_argument("--variant " + o.variant + ": phd3 or phd1");
  }
  if (o.particles < 1) throw std::invalid_argument("--particles must be >= 1");
  return o;
}

/// The estimate in the files `phdslam ingest --from` reads per seed (validation/EXPORT_FORMAT.md):
/// one pose per step at the step's time stamp, and the final map estimate with its covariances.
/// The weights are left out (written as 0, "none"), as in the authors' map.csv: the ingest format's
/// weight is a probability in [0, 1], a PHD component's weight can exceed 1, and the scores use
/// the means and covariances only.
void WriteIngestFiles(const std::filesystem::path& folder,
                      const std::vector<datasets::StampedPose>& poses,
                      const filters::MapEstimate& map) {
  std::filesystem::create_directories(folder);
  datasets::WriteTumTrajectory(folder / "trajectory.tum", poses);
  std::vector<datasets::MapPoint> points;
  points.reserve(map.size());
  for (std::size_t i = 0; i < map.size(); ++i) {
    datasets::MapPoint p;
    p.position = map.means[i];
    if (i < map.covs.size() && map.covs[i].allFinite()) p.cov = map.covs[i];
    points.push_back(p);
  }
  datasets::WriteMapCsv(folder / "map.csv", points);
}

int Run(const Options& o) {
  const datasets::Scenario scenario =
      validation::MakeScenario(o.scenario, o.seed, o.scenario_options);
  const filters::EstimatorContext context = scenario.PublicContext();
  validation::EstimatorRequest request;
  request.name = o.variant;
  request.particles = o.particles;
  request.scenario_name = o.scenario;
  request.overrides = o.overrides;
  request.context = &context;
  const filters::PhdSlamParams params =
      validation::ResolveParameters(request, filters::PhdSlamParamsTable());
  std::unique_ptr<filters::RbPhdSlam> filter = filters::MakePhdSlam(o.variant, context, params, 0);
  auto replay = std::make_shared<DrawReplay>(DrawReplay::ReadCsv(o.draws));
  filter->ReplayDraws(replay);
  const int steps = static_cast<int>(scenario.steps.size());
  std::optional<authors::StepTraceWriter> writer;
  if (!o.trace.empty()) {
    writer.emplace(o.trace, o.map_every, steps - 1);
    filter->SetObserver(&*writer);
  }
  std::vector<datasets::StampedPose> poses;
  poses.reserve(scenario.steps.size());
  for (int k = 0; k < steps; ++k) {
    const filters::StepOutput out = filter->Step(scenario.steps[k].data);
    if (writer) writer->Estimated(k, out, static_cast<int>(filter->Map().means.size()));
    poses.push_back({scenario.StepTime(static_cast<std::size_t>(k)), out.pose});
  }
  if (replay->consumed() != replay->size()) {
    std::cerr << "phdslam_authors_replay: " << o.draws << ": "
              << replay->size() - replay->consumed() << " recorded draws left unused after "
              << steps << " steps\n";
    return 1;
  }
  if (!o.out.empty()) WriteIngestFiles(o.out, poses, filter->Map());
  return 0;
}

}  // namespace
}  // namespace phdslam::apps

int main(int argc, char** argv) {
  phdslam::apps::Options options;
  try {
    options = phdslam::apps::ParseOptions(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "phdslam_authors_replay: " << e.what() << "\n" << phdslam::apps::kUsage;
    return 2;
  }
  try {
    return phdslam::apps::Run(options);
  } catch (const std::exception& e) {
    std::cerr << "phdslam_authors_replay: " << e.what() << '\n';
    return 1;
  }
}
