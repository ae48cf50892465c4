#include "reference/ceres/ordered_covariance.h"

#include <algorithm>
#include <cstddef>
#include <unordered_set>

namespace phdslam::reference {

OrderedCovariance::OrderedCovariance(const ceres::Covariance::Options& options)
    : options_(options) {}

namespace {

/// The parameter blocks in the order the residual blocks first use them (the residual blocks are
/// kept in the order they were added), then the blocks no residual uses.
/// Problem::GetParameterBlocks itself lists them by address.
std::vector<double*> BlocksInProblemOrder(const ceres::Problem& problem) {
  std::vector<ceres::ResidualBlockId> residuals;
  problem.GetResidualBlocks(&residuals);
  std::vector<double*> order;
  std::unordered_set<const double*> seen;
  std::vector<double*> parameters;
  for (ceres::ResidualBlockId id : residuals) {
    problem.GetParameterBlocksForResidualBlock(id, &parameters);
    for (double* p : parameters) {
      if (seen.insert(p).second) order.push_back(p);
    }
  }
  std::vector<double*> all;
  problem.GetParameterBlocks(&all);
  for (double* p : all) {
    if (!seen.contains(p)) order.push_back(p);  // unused: left out of the Jacobian by Ceres
  }
  return order;
}

}  // namespace

void OrderedCovariance::Mirror(ceres::Problem* problem) {
  const std::vector<double*> blocks = BlocksInProblemOrder(*problem);
  std::size_t total = 0;
  for (double* block : blocks) {
    total += static_cast<std::size_t>(problem->ParameterBlockSize(block));
  }
  buffer_.assign(total, 0.0);  // one buffer: addresses increase in the problem's order
  mirror_of_.clear();

  ceres::Problem::Options options;
  options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  mirror_ = std::make_unique<ceres::Problem>(options);
  std::size_t offset = 0;
  for (double* block : blocks) {
    const int size = problem->ParameterBlockSize(block);
    double* copy = buffer_.data() + offset;
    std::copy(block, block + size, copy);
    offset += static_cast<std::size_t>(size);
    mirror_->AddParameterBlock(copy, size,
                               const_cast<ceres::Manifold*>(problem->GetManifold(block)));
    if (problem->IsParameterBlockConstant(block)) mirror_->SetParameterBlockConstant(copy);
    mirror_of_.emplace(block, copy);
  }

  std::vector<ceres::ResidualBlockId> residuals;
  problem->GetResidualBlocks(&residuals);
  std::vector<double*> parameters;
  for (ceres::ResidualBlockId id : residuals) {
    problem->GetParameterBlocksForResidualBlock(id, &parameters);
    for (double*& p : parameters) p = mirror_of_.at(p);
    mirror_->AddResidualBlock(
        const_cast<ceres::CostFunction*>(problem->GetCostFunctionForResidualBlock(id)),
        const_cast<ceres::LossFunction*>(problem->GetLossFunctionForResidualBlock(id)), parameters);
  }
}

const double* OrderedCovariance::MirrorOf(const double* block) const {
  const auto found = mirror_of_.find(block);
  return found == mirror_of_.end() ? nullptr : found->second;
}

bool OrderedCovariance::Compute(const BlockPairs& blocks, ceres::Problem* problem) {
  Mirror(problem);
  BlockPairs mirrored;
  mirrored.reserve(blocks.size());
  for (const auto& [first, second] : blocks) {
    const double* a = MirrorOf(first);
    const double* b = MirrorOf(second);
    if (a == nullptr || b == nullptr) return false;
    mirrored.emplace_back(a, b);
  }
  covariance_ = std::make_unique<ceres::Covariance>(options_);
  return covariance_->Compute(mirrored, mirror_.get());
}

bool OrderedCovariance::GetCovarianceBlock(const double* first, const double* second,
                                           double* out) const {
  const double* a = MirrorOf(first);
  const double* b = MirrorOf(second);
  if (covariance_ == nullptr || a == nullptr || b == nullptr) return false;
  return covariance_->GetCovarianceBlock(a, b, out);
}

}  // namespace phdslam::reference
