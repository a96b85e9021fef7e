// SPDX-License-Identifier: Apache-2.0
// The stats JSON of the reference model's counters (docs/reference-model.md lists the
// keys). Kept out of model/ref so the golden model links no JSON library.
#pragma once

#include <nlohmann/json.hpp>

#include "ref/pipeline.h"

namespace rastsim {

// Every stat under its public name.
nlohmann::json to_json(const RenderStats& s);

}  // namespace rastsim
