// Marginalisation of states out of a factor graph into a Gaussian prior on the states they were
// linked to (the Schur complement of the linearised problem), and marginal covariances of a small
// graph, both with dense linear algebra: they serve the fixed-lag smoother (fixed_lag_smoother.h),
// whose window holds a few hundred variables at most.
//
// Linearisation points (first-estimate Jacobians): every factor is linearised with each of its
// blocks at `fixed_points[block]` when the block has one (a block already in the prior, whose
// linearisation point must not move), otherwise at the block's current value. The prior that
// results is linear in x - xbar with xbar these points; its blocks keep them for as long as they
// stay in a prior. A factor with a robust loss enters with the weight of iteratively reweighted
// least squares, sqrt(rho'(|r|^2)) on its residual and Jacobian, at that point.
#pragma once

#include <ceres/cost_function.h>
#include <ceres/loss_function.h>

#include <Eigen/Core>
#include <map>
#include <memory>
#include <set>
#include <vector>

#include "reference/ceres/linear_prior.h"

namespace phdslam::reference {

/// One factor: a cost function on `blocks`, with an optional robust loss (null: squared loss).
struct GraphFactor {
  std::shared_ptr<ceres::CostFunction> cost;
  std::shared_ptr<ceres::LossFunction> loss;
  std::vector<double*> blocks;
};

using FixedPoints = std::map<const double*, Eigen::VectorXd>;

/// The Gauss-Newton system H = sum J^T J, g = sum J^T r of `factors` over the blocks `order`
/// (in that order; a block of a factor not in `order` is held constant).
struct DenseSystem {
  std::vector<double*> order;
  std::vector<int> offsets;  ///< of each block of `order` in h and g
  std::vector<int> sizes;
  Eigen::MatrixXd h;
  Eigen::VectorXd g;
  /// Number of factors whose evaluation failed (left out of h and g).
  int failed_factors = 0;
};

DenseSystem Linearize(const std::vector<const GraphFactor*>& factors,
                      const std::vector<double*>& order, const FixedPoints& fixed_points);

/// Marginalises the blocks `marginalized` out of `factors` (every factor that touches them, plus
/// the previous prior as a factor when there is one). The result is a prior on every other
/// block the factors touch, except those in `constant`. Its A and b come from the Schur
/// complement H* = H_kk - H_km H_mm^+ H_mk, g* = g_k - H_km H_mm^+ g_m, factored as
/// H* = U diag(l) U^T: A = diag(sqrt l) U^T and b = diag(1 / sqrt l) U^T g* over the eigenvalues
/// above 1e-12 times the largest (the others carry no information), so that
/// 1/2 |A dx + b|^2 = 1/2 dx^T H* dx + dx^T g* + const.
LinearPrior Marginalize(const std::vector<const GraphFactor*>& factors,
                        const std::vector<double*>& marginalized,
                        const std::set<const double*>& constant, const FixedPoints& fixed_points);

/// Marginal covariances of `wanted` in the Gaussian of `factors` linearised at the blocks'
/// current values over every block they touch except `constant` (the inverse of H, by LDLT).
/// Symmetrised; empty when H is singular.
std::vector<Eigen::MatrixXd> MarginalCovariances(const std::vector<const GraphFactor*>& factors,
                                                 const std::set<const double*>& constant,
                                                 const std::vector<const double*>& wanted);

/// Covariances of one block (`anchor`, e.g. the newest pose) and of `wanted` blocks with it, in
/// the Gaussian of MarginalCovariances: anchor = Cov(anchor), marginal[i] = Cov(wanted[i]),
/// cross[i] = Cov(wanted[i], anchor). One factorisation and one solve for the anchor's columns
/// plus one per wanted block. Empty vectors (and an empty anchor) when H is singular.
struct AnchoredCovariances {
  Eigen::MatrixXd anchor;
  std::vector<Eigen::MatrixXd> marginal;
  std::vector<Eigen::MatrixXd> cross;
};
AnchoredCovariances AnchoredMarginalCovariances(const std::vector<const GraphFactor*>& factors,
                                                const std::set<const double*>& constant,
                                                const double* anchor,
                                                const std::vector<const double*>& wanted);

}  // namespace phdslam::reference
