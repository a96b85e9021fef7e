// SPDX-License-Identifier: Apache-2.0
// `rastsim simulate --tolerance P`: the cheapest fidelity level whose error bound is
// within P (docs/fidelity.md, "Tolerance").
#pragma once

#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "config/arch_params.h"
#include "ref/scene.h"

namespace rastsim::fidelity {

// The sampled level's relative error bound: the interval's farther end from the estimate.
double sampled_error(const nlohmann::json& sampled_stats);

// Analytic if its bounds are within tol (a fraction) of their midpoint; else sampled (a
// pilot at F = 0.1, then the F its variance predicts, each in a forked child) if its
// interval is; on a scene of kFrameSampledMinFrames frames or more (frame_sampled.h)
// frame-sampled instead of sampled (a pilot at F = 0.05, then the predicted F, <= 0.5);
// else run_full = true, reason says why, and the caller runs the full
// SystemC model (in its own process: nothing here elaborates SystemC in the caller).
// Returns the answering level's stats: fidelity_level, cycles, cycles_error_bound,
// fidelity_reason, wall_seconds.
nlohmann::json choose_level(const Scene& scene, const ArchParams& arch, double tol, uint64_t seed, bool& run_full,
                            std::string& reason);

}  // namespace rastsim::fidelity
