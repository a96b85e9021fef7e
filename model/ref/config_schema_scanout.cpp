// SPDX-License-Identifier: Apache-2.0
// Video timing, DAC and scan-out keys: placeholder until the scan-out stage lands.
#include "config.h"

namespace rastsim {

void add_scanout_params(std::vector<ParamDef>& /*schema*/) {}

}  // namespace rastsim
