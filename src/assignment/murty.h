// Murty's k-best ranking of rectangular linear assignments.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "src/assignment/linear_assignment.h"

namespace phdslam::assignment {

/// The k best assignments (every row assigned, rows <= cols, +inf forbidden) in non-decreasing
/// cost order, at most k of them (fewer when fewer feasible assignments exist; none when there is
/// no feasible one). Exact: Murty's partitioning with the Miller-Stone-Cox optimisations (each
/// subproblem inherits its parent's solution and duals and needs one augmenting path; partitions
/// ordered by a dual lower bound; children solved lazily from a priority queue keyed by it).
/// Throws std::invalid_argument when rows > cols, an entry is NaN or -inf, or k < 0.
std::vector<Assignment> MurtyKBest(const Eigen::MatrixXd& cost, int k);

/// Same, with the PHD-SLAM 3.0 early stop (docs/algorithms/phd-slam.md section 4.4): after
/// generating hypothesis t >= 2, if its cost exceeds the best cost by more than `max_cost_gap`,
/// generation stops and that hypothesis is discarded. Throws std::invalid_argument also when
/// max_cost_gap is NaN.
std::vector<Assignment> MurtyKBest(const Eigen::MatrixXd& cost, int k, double max_cost_gap);

}  // namespace phdslam::assignment
