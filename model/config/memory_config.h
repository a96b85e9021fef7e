// SPDX-License-Identifier: Apache-2.0
// MemoryParams from the config (config -> typed parameters, one way).
#pragma once

#include "config/config.h"
#include "ref/memory/memory_params.h"

namespace rastsim {

// The functional memory system's parameters from a validated config; throws ConfigError
// naming the keys when the caches' geometry does not hold (ways x line_bytes x a power of
// two; with plane compression, of the block's bytes) or the surfaces overlap.
MemoryParams memory_params_from_config(const Config& cfg);

}  // namespace rastsim
