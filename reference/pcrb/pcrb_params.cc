#include "reference/pcrb/pcrb_params.h"

namespace phdslam::reference::pcrb {

const params::ParameterTable<PcrbParams>& PcrbParamsTable() {
  using P = PcrbParams;
  static const params::ParameterTable<P> table({
      params::EnumField<P, DetectionModel>(
          "detection_model", [](auto& p) -> auto& { return p.detection_model; },
          {{DetectionModel::kConditioned, "conditioned"}, {DetectionModel::kIrf, "irf"}})
          .Means("conditioned: the information of the detections the simulator produced (the "
                 "default to quote); irf: each potential detection scaled by the information "
                 "reduction factor of pD and clutter (docs/algorithms/pcrb.md section 4)"),
      params::NumberField<P>(
          "gate_sigma", [](auto& p) -> auto& { return p.gate_sigma; }, params::Above(0.0))
          .Means("irf: radius of the clutter disc of the reduction factor, in measurement "
                 "standard deviations")
          .UsedOnlyWith("detection_model", {"irf"}),
      params::IntField<P>(
          "irf_samples", [](auto& p) -> auto& { return p.irf_samples; }, params::AtLeast(1000))
          .Means("irf: Monte Carlo draws of the reduction factor's integral (with clutter only)")
          .UsedOnlyWith("detection_model", {"irf"}),
  });
  return table;
}

}  // namespace phdslam::reference::pcrb
