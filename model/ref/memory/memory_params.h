// SPDX-License-Identifier: Apache-2.0
// The functional memory system's parameters (keys memory.* and rop.*_cache_*,
// rop.fast_clear*, rop.depth_compression; config/memory_config.h builds them from the
// config). Every value comes from the config; the initialisers are neutral, not defaults.
#pragma once

#include <cstdint>

namespace rastsim {

// memory.fb_layout: how a surface's pixels lie in memory (surface_layout.h).
enum class FbLayout { Linear, Tiled };
// rop.depth_compression: how a depth block is stored (depth_compression.h).
enum class DepthCompression { None, Plane };

// One ROP cache (rop.color_cache_* / rop.depth_cache_*). bytes = 0: no cache.
struct CacheParams {
  uint64_t bytes = 0;  // capacity, bytes: sets x ways x line_bytes, sets a power of two
  int ways = 1;
  int line_bytes = 64;  // a power of two
};

struct MemoryParams {
  // memory.model != "fixed": the functional counts are made (render --stats keys
  // dram_bytes_*, rop_*_cache_*, memory.clients.*). Off: no access is modelled.
  bool enabled = false;
  FbLayout layout = FbLayout::Linear;
  int tile_width = 1, tile_height = 1;  // px, powers of two (memory.fb_tile_*; tiled layout)
  uint64_t color_base = 0, depth_base = 0;  // bytes, multiples of 4096 (memory.*_base)
  CacheParams color_cache, depth_cache;
  bool fast_clear = false;
  int block_width = 1, block_height = 1;  // px, powers of two: fast-clear and compression block
  DepthCompression depth_compression = DepthCompression::None;
};

}  // namespace rastsim
