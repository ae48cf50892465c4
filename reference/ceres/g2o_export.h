// Export of a smoother problem and its solution in the g2o text format (README.md, "g2o export").
//
//   # comment header (what the file holds, units, vertex numbering, the edge conversions)
//   VERTEX_SE2 id x y theta                        one per step (ids 0..K-1), then the anchor
//   VERTEX_XY id x y                               one per landmark (ids K..K+M-1)
//   FIX id                                         the gauge: pose 0, or the anchor
//   EDGE_SE2 i j dx dy dtheta I11 I12 I13 I22 I23 I33
//   EDGE_SE2_XY i j dx dy I11 I12 I22
//
// EDGE_SE2 is step j's odometry increment in the frame of pose i with information Sigma^-1
// (odometry_increment.h). EDGE_SE2_XY is a range-bearing measurement converted by the inverse
// model in the frame of pose i, d = r [cos phi, sin phi], with covariance G R G^T,
// G = [cos phi, -r sin phi; sin phi, r cos phi] (g2o has no standard 2-D range-bearing edge).
#pragma once

#include <filesystem>
#include <vector>

#include "datasets/batch_estimator.h"
#include "datasets/scenario.h"
#include "reference/ceres/odometry_increment.h"
#include "src/filters/estimator.h"

namespace phdslam::reference {

/// Writes `scenario`'s factor graph under `association` (per step, per measurement: an index
/// into solution.map, or -1) with vertex values from `solution`. Throws std::invalid_argument
/// when the sizes disagree and std::runtime_error when the file cannot be written.
void ExportG2o(const std::filesystem::path& path, const datasets::Scenario& scenario,
               const datasets::BatchResult& solution,
               const std::vector<std::vector<int>>& association,
               const OdometryNoiseFloor& floor = {});

}  // namespace phdslam::reference
