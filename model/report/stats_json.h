// SPDX-License-Identifier: Apache-2.0
// The stats JSON of the reference model's counters (docs/reference-model.md lists the
// keys). Kept out of model/ref so the golden model links no JSON library.
#pragma once

#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "config/obj_placement.h"
#include "ref/pipeline.h"

namespace rastsim {

// A CRC-32 as the text output prints it: 8 lower-case hex digits ("0a1b2c3d").
std::string crc32_hex(uint32_t crc);

// The triangles of a run for a summary line: "N triangles (all drawn)", or with every
// nonzero reason triangle setup dropped one for (count_setup_outcome), e.g.
// "69666 triangles (57916 not drawn: 34213 out of range, 23703 outside the clip)".
std::string triangles_summary(const RenderStats& s);

// The geometry front end's counters under their public names (docs/stats.md), into `j`.
void add_front_end(nlohmann::json& j, const FrontEndStats& f);

// The memory system's counters under their public names (docs/stats.md): the totals
// dram_bytes_read / _written, rop_*_cache_hits / _misses, fast_clear_blocks,
// depth_compressed_bytes, and each client's set under memory.clients.<name>.
void add_memory(nlohmann::json& j, const MemoryStats& m);

// Every stat under its public name; framebuffer_crc32 as crc32_hex.
nlohmann::json to_json(const RenderStats& s);

// For an OBJ scene, sets j["obj_ignored"] to what its reader read but did not use
// (statement -> count, {} when nothing; scene_io.h obj_ignored_counts) under the placement's
// camera (a perspective camera draws `l` and `p`); a trace adds no key.
void add_obj_ignored(nlohmann::json& j, const std::string& scene_path, ObjCamera camera);

}  // namespace rastsim
