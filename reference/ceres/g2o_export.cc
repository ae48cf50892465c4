#include "reference/ceres/g2o_export.h"

#include <Eigen/LU>
#include <fstream>
#include <iomanip>
#include <stdexcept>
#include <string>

#include "reference/ceres/batch_smoother.h"
#include "src/models/range_bearing_model.h"

namespace phdslam::reference {
namespace {

void WriteUpperTriangle3(std::ostream& os, const Mat3& info) {
  os << ' ' << info(0, 0) << ' ' << info(0, 1) << ' ' << info(0, 2) << ' ' << info(1, 1) << ' '
     << info(1, 2) << ' ' << info(2, 2);
}

}  // namespace

void ExportG2o(const std::filesystem::path& path, const datasets::Scenario& scenario,
               const datasets::BatchResult& solution,
               const std::vector<std::vector<int>>& association, const OdometryNoiseFloor& floor) {
  const std::size_t steps = scenario.steps.size();
  const std::size_t landmarks = solution.map.means.size();
  if (solution.poses.size() != steps) {
    throw std::invalid_argument("ExportG2o: solution has " + std::to_string(solution.poses.size()) +
                                " poses, scenario has " + std::to_string(steps) + " steps");
  }
  if (association.size() != steps) {
    throw std::invalid_argument("ExportG2o: association has " + std::to_string(association.size()) +
                                " steps, expected " + std::to_string(steps));
  }
  for (std::size_t k = 0; k < steps; ++k) {
    if (association[k].size() != scenario.steps[k].data.measurements.size()) {
      throw std::invalid_argument("ExportG2o: association[" + std::to_string(k) + "] has " +
                                  std::to_string(association[k].size()) + " entries, expected " +
                                  std::to_string(scenario.steps[k].data.measurements.size()));
    }
    for (int i : association[k]) {
      if (i < -1 || i >= static_cast<int>(landmarks)) {
        throw std::invalid_argument("ExportG2o: association[" + std::to_string(k) +
                                    "] refers to landmark " + std::to_string(i) + " of " +
                                    std::to_string(landmarks));
      }
    }
  }

  const std::vector<OdometryIncrement> increments = ScenarioOdometry(scenario, floor);
  const bool anchored = steps > 0 && increments[0].propagated;
  const std::size_t anchor_id = steps + landmarks;
  const Mat2 r = scenario.sensor.noise_cov;

  std::ofstream os(path);
  if (!os) throw std::runtime_error("ExportG2o: cannot open " + path.string() + " for writing");
  os << std::setprecision(17);
  os << "# phdslam Ceres batch smoother problem, g2o format (reference/ceres/README.md).\n"
     << "# scenario: " << scenario.name << ", seed " << scenario.seed << ", " << steps << " steps, "
     << landmarks << " landmarks.\n"
     << "# Units: m and rad. Headings are not wrapped.\n"
     << "# VERTEX_SE2 0.." << (steps == 0 ? 0 : steps - 1)
     << ": the pose at each step (estimated values); VERTEX_XY " << steps << ".."
     << (steps + landmarks == 0 ? 0 : steps + landmarks - 1) << ": the landmarks.\n";
  if (anchored) {
    os << "# VERTEX_SE2 " << anchor_id << ": the known initial pose (fixed), linked to pose 0 by "
       << "step 0's odometry.\n";
  }
  os << "# EDGE_SE2 i j dx dy dtheta + upper triangle of the information: odometry of step j,\n"
     << "#   the motion model composed from the origin over the step's sub-intervals, information\n"
     << "#   = inverse of the propagated control-noise covariance plus the floor diag("
     << floor.position_std << "^2, " << floor.position_std << "^2, " << floor.heading_std
     << "^2).\n"
     << "# EDGE_SE2_XY i j dx dy I11 I12 I22: a range-bearing measurement (r, phi) at pose i,\n"
     << "#   converted to the landmark position in the frame of pose i, r (cos phi, sin phi),\n"
     << "#   with information (G R G^T)^-1, G = [cos phi, -r sin phi; sin phi, r cos phi],\n"
     << "#   R = [" << r(0, 0) << ", " << r(0, 1) << "; " << r(1, 0) << ", " << r(1, 1) << "].\n";

  for (std::size_t k = 0; k < steps; ++k) {
    const Pose& x = solution.poses[k];
    os << "VERTEX_SE2 " << k << ' ' << x(0) << ' ' << x(1) << ' ' << x(2) << '\n';
  }
  for (std::size_t i = 0; i < landmarks; ++i) {
    const Landmark& m = solution.map.means[i];
    os << "VERTEX_XY " << steps + i << ' ' << m(0) << ' ' << m(1) << '\n';
  }
  if (anchored) {
    const Pose& x = scenario.initial_pose;
    os << "VERTEX_SE2 " << anchor_id << ' ' << x(0) << ' ' << x(1) << ' ' << x(2) << '\n';
    os << "FIX " << anchor_id << '\n';
  } else if (steps > 0) {
    os << "FIX 0\n";
  }
  for (std::size_t k = 0; k < steps; ++k) {
    const OdometryIncrement& inc = increments[k];
    if (k == 0 && !anchored) continue;
    const std::size_t from = k == 0 ? anchor_id : k - 1;
    const Mat3 info = inc.covariance.inverse();
    os << "EDGE_SE2 " << from << ' ' << k << ' ' << inc.delta(0) << ' ' << inc.delta(1) << ' '
       << inc.delta(2);
    WriteUpperTriangle3(os, 0.5 * (info + info.transpose()));
    os << '\n';
  }
  for (std::size_t k = 0; k < steps; ++k) {
    const std::vector<Measurement>& zs = scenario.steps[k].data.measurements;
    for (std::size_t j = 0; j < zs.size(); ++j) {
      const int i = association[k][j];
      if (i < 0) continue;
      const Landmark d = models::InverseMeasurement(Pose::Zero(), zs[j]);
      Mat2 info = models::BirthCovariance(Pose::Zero(), zs[j], r).inverse();
      info = 0.5 * (info + info.transpose());
      os << "EDGE_SE2_XY " << k << ' ' << steps + static_cast<std::size_t>(i) << ' ' << d(0) << ' '
         << d(1) << ' ' << info(0, 0) << ' ' << info(0, 1) << ' ' << info(1, 1) << '\n';
    }
  }
  if (!os) throw std::runtime_error("ExportG2o: write to " + path.string() + " failed");
}

}  // namespace phdslam::reference
