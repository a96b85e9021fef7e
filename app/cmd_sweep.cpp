// SPDX-License-Identifier: Apache-2.0
#include "common.h"
namespace rastsim::app {
void register_sweep(CLI::App&) {}
}  // namespace rastsim::app
