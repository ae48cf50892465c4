#pragma once
// Marginal covariances of a Ceres problem that do not depend on where its parameter blocks lie in
// memory.
//
// ceres::Covariance orders the Jacobian's columns by the addresses of the parameter blocks, and
// SuiteSparseQR's fill-reducing ordering, its rounding and its rank decisions follow that order.
// The smoothers keep poses and landmarks in separate std::vectors, whose relative place on the
// heap differs from run to run, so the same problem gave covariances that differed in the last
// digits, and a gate fed by them could decide one association differently on a repeat of the same
// run. OrderedCovariance computes on a mirror of the problem whose blocks lie in one buffer in the
// problem's own order (the order they were added): equal problems give bit-identical covariances.

#include <ceres/ceres.h>

#include <memory>
#include <unordered_map>
#include <utility>
#include <vector>

namespace phdslam::reference {

class OrderedCovariance {
 public:
  using BlockPairs = std::vector<std::pair<const double*, const double*>>;

  explicit OrderedCovariance(const ceres::Covariance::Options& options);

  /// As ceres::Covariance::Compute, with the blocks named by their addresses in `problem`.
  bool Compute(const BlockPairs& blocks, ceres::Problem* problem);

  /// As ceres::Covariance::GetCovarianceBlock (row-major), for blocks of the last Compute.
  bool GetCovarianceBlock(const double* first, const double* second, double* out) const;

 private:
  void Mirror(ceres::Problem* problem);
  const double* MirrorOf(const double* block) const;

  ceres::Covariance::Options options_;
  std::unique_ptr<ceres::Covariance> covariance_;
  std::unique_ptr<ceres::Problem> mirror_;
  std::vector<double> buffer_;
  std::unordered_map<const double*, double*> mirror_of_;
};

}  // namespace phdslam::reference
