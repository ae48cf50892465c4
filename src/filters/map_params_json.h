// The parameter table of the GM-PHD map options (phd::MapParams), embedded in the parameter
// tables of every filter that carries GM-PHD maps.
#pragma once

#include "src/core/parameter_table.h"
#include "src/phd/map_params.h"

namespace phdslam::filters {

const params::ParameterTable<phd::MapParams>& MapParamsTable();

}  // namespace phdslam::filters
