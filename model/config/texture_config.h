// SPDX-License-Identifier: Apache-2.0
// TextureParams from the config (config -> typed parameters, one way).
#pragma once

#include "config/config.h"
#include "ref/texture/texture.h"

namespace rastsim {

// The texture unit's parameters (keys texture.*) from a validated config; throws
// ConfigError naming texture.cache_bytes when a cache is not texture.ways x
// texture.line_bytes x a power-of-two number of sets.
TextureParams texture_params_from_config(const Config& cfg);

}  // namespace rastsim
