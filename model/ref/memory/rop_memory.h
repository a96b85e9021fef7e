// SPDX-License-Identifier: Apache-2.0
// The ROP's memory clients: the colour surface (client rop_color) and the depth surface
// (client rop_depth), each a SurfaceClient with its own cache, over one framebuffer. The
// reference ROP (ref/rop.h) calls depth_read / depth_write / color_write for every sample
// it tests and writes, clear_color / clear_depth for the clears, and finish() at the end
// of the scene (docs/memory.md says what each counts).
#pragma once

#include <cstdint>

#include "ref/memory/memory_params.h"
#include "ref/memory/surface_client.h"

namespace rastsim {

class Framebuffer;

// The memory stats of a run: one counter set a client (names: memory_client_names).
struct MemoryStats {
  bool enabled = false;  // memory.model != fixed: the counts below were made
  MemoryClientStats rop_color, rop_depth;
  // pipeline.mode = binned: the ROP writes the tile buffer (rop_color, rop_depth stay 0);
  // the parameter buffer and the bins' loads and stores (ref/memory/bin_memory.h).
  bool binned = false;
  MemoryClientStats binning, tile_store;
};

// The clients' public names (stats keys memory.clients.<name>), in MemoryStats' order.
inline constexpr const char* kRopColorClient = "rop_color";
inline constexpr const char* kRopDepthClient = "rop_depth";

class RopMemory {
 public:
  // The surfaces of fb's size and sample count; `fb` is read at write-back by depth
  // compression and must outlive this object.
  RopMemory(const MemoryParams& p, const Framebuffer& fb, int depth_bits);

  void depth_read(int x, int y, int s) { depth.access(x, y, s, false); }
  void depth_write(int x, int y, int s) { depth.access(x, y, s, true); }
  void color_write(int x, int y, int s) { color.access(x, y, s, true); }
  void clear_color() { color.clear(); }
  void clear_depth() { depth.clear(); }

  // The end of the scene: with S > 1 the resolve reads every sample through the colour
  // cache (pixels row-major, samples in order), then every dirty line of both caches is
  // written back, then the resolved image (W H 4 bytes) is written past the cache.
  void finish();

  MemoryStats stats() const { return {true, color.stats(), depth.stats()}; }
  // Both surfaces' state from `from` (SurfaceClient::take_state; the same config's).
  void take_state(const RopMemory& from) {
    color.take_state(from.color);
    depth.take_state(from.depth);
  }

  SurfaceClient color, depth;

 private:
  int width_, height_, samples_;
};

// The surface layouts of a framebuffer of width x height x samples with these
// parameters (a compressed depth surface is tiled by the compression block), and the
// depth cache as it runs (with plane compression one line is one block). Inline: the
// config's checks use them (config/memory_config.cpp).
inline SurfaceLayout color_surface_layout(const MemoryParams& p, int width, int height, int samples) {
  return SurfaceLayout(p.layout, p.tile_width, p.tile_height, p.color_base, width, height, samples,
                       kColorBytesPerSample);
}

inline SurfaceLayout depth_surface_layout(const MemoryParams& p, int width, int height, int samples, int depth_bits) {
  const int bpp = depth_bytes_per_sample(depth_bits);
  if (p.depth_compression == DepthCompression::Plane)
    return SurfaceLayout(FbLayout::Tiled, p.block_width, p.block_height, p.depth_base, width, height, samples, bpp);
  return SurfaceLayout(p.layout, p.tile_width, p.tile_height, p.depth_base, width, height, samples, bpp);
}

inline CacheParams depth_cache_params(const MemoryParams& p, int samples, int depth_bits) {
  CacheParams c = p.depth_cache;
  if (p.depth_compression == DepthCompression::Plane)
    c.line_bytes = p.block_width * p.block_height * samples * depth_bytes_per_sample(depth_bits);
  return c;
}

}  // namespace rastsim
