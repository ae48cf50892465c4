// k-best assignments of a cost matrix whose rows split into independent blocks (rows linked by a
// shared finite column). Each block is ranked with Murty's method and the per-block lists are
// combined exactly; for the sparse gated matrices of PHD-SLAM this is far cheaper than ranking
// the whole matrix, and it gives the same list up to the order of equal-cost assignments.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "src/assignment/linear_assignment.h"

namespace phdslam::assignment {

/// Same contract as MurtyKBest(cost, k, max_cost_gap): at most k assignments in non-decreasing
/// cost order, every one within max_cost_gap of the best (the early stop of
/// docs/algorithms/phd-slam.md section 4.4 keeps exactly these), every row assigned, rows <= cols,
/// +inf forbidden. Every column index in the result refers to `cost`.
std::vector<Assignment> BlockMurtyKBest(const Eigen::MatrixXd& cost, int k, double max_cost_gap);

}  // namespace phdslam::assignment
