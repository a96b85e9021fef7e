// SPDX-License-Identifier: Apache-2.0
// Test harness of the SystemC model.
//
// SystemC elaborates once per process, so every simulation runs in a forked child
// (run_isolated): the child elaborates, simulates, checks against the reference model
// and sends a JSON summary back through a pipe. The test process itself never
// elaborates, so one test may run many simulations and the binary also works when run
// by hand without a --gtest_filter.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "config/config.h"
#include "ref/scene.h"
#include "sc/raster_pipeline.h"

namespace rastsim::sctest {

// Runs fn in a forked child; returns its JSON, or {"error": ...} if it threw or died
// (fidelity::run_in_child_or_error, model/fidelity/run_child.h).
nlohmann::json run_isolated(const std::function<nlohmann::json()>& fn);

// In a child: simulates `scene` and renders it with the reference model; returns
// {"crc_ref", "crc_sim", "fragments_ref", "fragments_sim", "first_mismatch" (index of
// the first differing fragment-trace line, -1 if none), "mismatch" (the two lines),
// "stats" (SimResult::to_json)}.
nlohmann::json compare_with_reference(const Scene& scene, const Config& cfg, const sc::SimOptions& opts = {});

// Checks a compare_with_reference() summary with gtest: same image, depth, fragments,
// counters, and sane timing (cycles >= bound; busy + stalled + starved = cycles per
// stage).
void expect_matches_reference(const nlohmann::json& r);

// Call in a child (run_isolated): renders `scene` with the reference and its memory
// system (memory_params_from_config; compare_with_reference renders without it) and
// simulates it; returns {"diff": {key: [reference, simulate]} of the render stats that
// differ (wall time aside), "ref": the reference's stats}.
nlohmann::json diff_render_stats_with_memory(const Scene& scene, const Config& cfg);

// In a child: render's stats with the config's memory settings ("ref"), simulate's
// render counters ("sim"; both without wall_seconds) and its whole stats ("stats").
nlohmann::json render_and_simulate(const Scene& scene, const Config& cfg);

// In a child: the stats of one simulation (SimResult::to_json).
nlohmann::json simulate_stats(const Scene& scene, const Config& cfg, const sc::SimOptions& opts = {});

// A seeded random scene in a W x H viewport: lists, strips and fans of random size and
// colour, depth, mid-stream clears, a scissor and a viewport change.
Scene random_scene(uint64_t seed, int width, int height, int triangles);

// `copies` copies of a scene's commands, one after another.
Scene repeat_scene(const Scene& s, int copies);

// The shipped traces (traces/*.trace), sorted.
std::vector<std::string> shipped_traces();

// A config of defaults with the given overrides ("key=value").
Config make_config(const std::vector<std::string>& overrides);

}  // namespace rastsim::sctest
