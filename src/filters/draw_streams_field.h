// The `draw_streams` parameter of every filter built on the particle-filter skeleton: one row of
// each filter's parameter table, so `--set NAME:draw_streams=keyed` reaches them all alike.
#pragma once

#include "src/core/keyed_stream.h"
#include "src/core/parameter_table.h"

namespace phdslam::filters {

/// "sequential" (one RandomStream per run, the default) or "keyed" (common random numbers:
/// src/core/keyed_stream.h). P has a member `DrawStreams draw_streams`.
template <typename P>
params::Field<P> DrawStreamsField() {
  return params::EnumField<P, DrawStreams>(
             "draw_streams", [](auto& p) -> auto& { return p.draw_streams; },
             {{DrawStreams::kSequential, "sequential"}, {DrawStreams::kKeyed, "keyed"}})
      .Means(
          "random draws from one sequential stream per run, or keyed per (step, particle, "
          "purpose): common random numbers between versions of the filter");
}

}  // namespace phdslam::filters
