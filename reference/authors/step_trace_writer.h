// Writes the inside of every PHD-SLAM step (filters::StepObserver) as the CSV files the authors'
// release writes under reference/authors/octave/ (particles.csv, proposals.csv, states.csv,
// maps.csv, estimate.csv; the columns are described in reference/authors/README.md), so both can
// be compared step by step by compare_traces.py.
#pragma once

#include <fstream>
#include <string>
#include <vector>

#include "src/filters/estimator.h"
#include "src/filters/rb_phd_slam.h"

namespace phdslam::authors {

class StepTraceWriter final : public filters::StepObserver<filters::PhdParticle> {
 public:
  /// Opens the files in `folder` (created if missing). map_every > 0: full maps of every particle
  /// at steps that are multiples of it and at last_step.
  StepTraceWriter(const std::string& folder, int map_every, int last_step);

  void Sampled(int step, int idx, const Pose& mu0, const Mat3& sigma0,
               const filters::PreparedProposal& proposal, const filters::PhdParticle& p) override;
  void Updated(int step, int idx, const filters::PhdParticle& p) override;
  void Resampled(int step, const std::vector<int>& sources) override;
  /// After the filter's step: its estimate, map size and ESS.
  void Estimated(int step, const filters::StepOutput& out, int map_size);

 private:
  std::ofstream particles_;
  std::ofstream proposals_;
  std::ofstream states_;
  std::ofstream maps_;
  std::ofstream estimate_;
  int map_every_;
  int last_step_;
  std::vector<int> sources_;
};

}  // namespace phdslam::authors
