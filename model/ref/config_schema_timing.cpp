// SPDX-License-Identifier: Apache-2.0
// Timing keys of the SystemC model (model/sc): placeholder until that model lands.
#include "config.h"

namespace rastsim {

void add_timing_params(std::vector<ParamDef>& /*schema*/) {}

}  // namespace rastsim
