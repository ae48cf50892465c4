// The options of every scenario as declarative parameter tables (src/core/parameter_table.h):
// one table per options struct gives the keys `scenario_options` and `--scenario-set` accept,
// their checks, and the resolved values config.json records. The step limit (`steps`) and the
// data folder are experiment settings and are not in the tables.
#pragma once

#include "datasets/glmb_simulation.h"
#include "datasets/mrclam.h"
#include "datasets/paper_synthetic.h"
#include "datasets/scenario_generator.h"
#include "datasets/scphd_simulation.h"
#include "datasets/victoria_park.h"
#include "src/core/parameter_table.h"

namespace phdslam::validation {

/// paper-synthetic: the sensor (pD, clutter, field of view, buffers) and the noise covariances.
const params::ParameterTable<datasets::SyntheticOptions>& PaperSyntheticOptionsTable();

/// victoria-park: the artificial clutter, the detection profile, the field of view and the
/// noise covariances the filters assume.
const params::ParameterTable<datasets::VictoriaParkOptions>& VictoriaParkOptionsTable();

/// generated: every generator option (path, landmarks, sensor, noise, initial pose).
const params::ParameterTable<datasets::GeneratorOptions>& GeneratedOptionsTable();

/// scphd-sim: the simulated path and map, the sensor and the noise covariances.
const params::ParameterTable<datasets::ScPhdSimOptions>& ScPhdSimOptionsTable();

/// mrclam: the sub-dataset and robot, whether non-landmark detections are dropped, and the
/// sensor and noise model the filters assume (defaults estimated from dataset 6).
const params::ParameterTable<datasets::MrclamOptions>& MrclamOptionsTable();

/// glmb-sim: the simulated path and map, the sensor, the noise covariances and the data protocol.
const params::ParameterTable<datasets::GlmbSimOptions>& GlmbSimOptionsTable();

}  // namespace phdslam::validation
