#include "reference/pcrb/pcrb_params.h"

namespace phdslam::reference::pcrb {

const params::ParameterTable<PcrbParams>& PcrbParamsTable() {
  using P = PcrbParams;
  static const params::ParameterTable<P> table({
      params::EnumField<P, DetectionModel>(
          "detection_model", [](auto& p) -> auto& { return p.detection_model; },
          {{DetectionModel::kConditioned, "conditioned"}, {DetectionModel::kIrf, "irf"}}),
      params::NumberField<P>(
          "gate_sigma", [](auto& p) -> auto& { return p.gate_sigma; }, params::Above(0.0)),
      params::IntField<P>(
          "irf_samples", [](auto& p) -> auto& { return p.irf_samples; }, params::AtLeast(1000)),
  });
  return table;
}

}  // namespace phdslam::reference::pcrb
