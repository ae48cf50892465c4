#include "src/glmb/birth.h"

#include "src/models/range_bearing_model.h"

namespace phdslam::glmb {

double BirthProbability(const BirthSettings& settings, double r_u, bool gates_best_prior) {
  switch (settings.rule) {
    case BirthRule::kThresholded:
      return r_u < settings.assigned_threshold ? settings.new_probability
                                               : settings.existing_probability;
    case BirthRule::kGatesBest:
      return gates_best_prior ? settings.existing_probability : settings.new_probability;
    case BirthRule::kContinuous:
      return settings.existing_probability * (2.0 - r_u);
  }
  return settings.new_probability;
}

std::vector<BirthTrack> MakeBirths(const Pose& x, std::span<const Measurement> measurements,
                                   const Mat2& noise_cov, const UpdateResult& update,
                                   const BirthSettings& settings, int label_step,
                                   std::uint64_t& next_id) {
  std::vector<BirthTrack> births;
  births.reserve(measurements.size());
  for (int j = 0; j < static_cast<int>(measurements.size()); ++j) {
    const double r_u = j < static_cast<int>(update.measurement_assigned.size())
                           ? update.measurement_assigned[j]
                           : 0.0;
    const bool gates = j < static_cast<int>(update.measurement_gates_best_prior.size()) &&
                       update.measurement_gates_best_prior[j] != 0;
    const Landmark mean = models::InverseMeasurement(x, measurements[j]);
    const Mat2 cov = models::BirthCovariance(x, measurements[j], noise_cov);
    births.push_back(BirthTrack{MakeTrack(next_id++, Label{label_step, j}, mean, cov),
                                BirthProbability(settings, r_u, gates)});
  }
  return births;
}

}  // namespace phdslam::glmb
