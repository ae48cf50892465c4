#include "reference/ceres/particle_lineage.h"

#include <stdexcept>
#include <string>

namespace phdslam::reference {

void ParticleLineage::AddParticle(int step, int idx, const Pose& pose, double log_weight) {
  const auto s = static_cast<std::size_t>(step);
  if (step < 0 || idx < 0 || s + 1 < poses_.size() || s > poses_.size()) {
    throw std::invalid_argument("ParticleLineage: particle " + std::to_string(idx) + " of step " +
                                std::to_string(step) + " after step " +
                                std::to_string(static_cast<long>(poses_.size()) - 1));
  }
  if (s == poses_.size()) {
    poses_.emplace_back();
    log_weights_.emplace_back();
    sources_.emplace_back();
  }
  if (static_cast<std::size_t>(idx) != poses_[s].size()) {
    throw std::invalid_argument("ParticleLineage: particle " + std::to_string(idx) + " of step " +
                                std::to_string(step) + " after " +
                                std::to_string(poses_[s].size()) + " particles");
  }
  poses_[s].push_back(pose);
  log_weights_[s].push_back(log_weight);
}

void ParticleLineage::AddResampling(int step, const std::vector<int>& sources) {
  if (poses_.empty() || step != static_cast<int>(poses_.size()) - 1) {
    throw std::invalid_argument("ParticleLineage: resampling of step " + std::to_string(step) +
                                " is not for the last recorded step");
  }
  const std::size_t n = poses_.back().size();
  for (int s : sources) {
    if (s < 0 || static_cast<std::size_t>(s) >= n) {
      throw std::invalid_argument("ParticleLineage: resampling source " + std::to_string(s) +
                                  " outside the " + std::to_string(n) + " particles of step " +
                                  std::to_string(step));
    }
  }
  sources_.back() = sources;
}

std::vector<Pose> ParticleLineage::BestFinalPath() const {
  std::vector<Pose> path(poses_.size());
  if (poses_.empty()) return path;
  const std::vector<double>& last = log_weights_.back();
  if (last.empty()) throw std::logic_error("ParticleLineage: the last step has no particles");
  std::size_t j = 0;
  for (std::size_t i = 1; i < last.size(); ++i) {
    if (last[i] > last[j]) j = i;
  }
  for (std::size_t k = poses_.size(); k-- > 0;) {
    if (j >= poses_[k].size()) {
      throw std::logic_error("ParticleLineage: step " + std::to_string(k) + " has " +
                             std::to_string(poses_[k].size()) + " particles, its successor " +
                             std::to_string(j + 1) + " or more");
    }
    path[k] = poses_[k][j];
    // Particle j of step k descends from particle j after step k-1's resampling.
    if (k > 0 && !sources_[k - 1].empty()) {
      if (j >= sources_[k - 1].size()) {
        throw std::logic_error("ParticleLineage: step " + std::to_string(k - 1) +
                               " resampled into " + std::to_string(sources_[k - 1].size()) +
                               " particles, fewer than step " + std::to_string(k) + " has");
      }
      j = static_cast<std::size_t>(sources_[k - 1][j]);
    }
  }
  return path;
}

}  // namespace phdslam::reference
