// SPDX-License-Identifier: Apache-2.0
// The reference texture unit: a textured fragment's sample (texture.h's arithmetic) with
// every texel fetch through the texture cache (ref/memory's SetAssocCache: read-only,
// true LRU), counted (docs/texture.md, "Memory"; docs/stats.md).
//
// Memory: the textures a scene binds are placed in order of first use from
// texture.base, each at a multiple of 4096 bytes with its whole mip chain (also when
// sampled with `mipmap off`), the levels one after another,
// each level at a multiple of 256 bytes from the texture's start; a level's texels by
// texture.layout: linear (row-major), tiled (4 x 4-texel tiles, row-major tiles and
// texels within a tile; ref/memory/surface_layout.h) or morton (Z order over the level
// padded to a power-of-two square: x bit k to address bit 2k, y bit k to bit 2k + 1).
// A fetch is one cache access to line address / line_bytes; a miss reads the whole line
// from DRAM. Without a cache (texture.cache_bytes = 0) every fetch is a miss reading its
// own texel's bytes.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <unordered_map>
#include <vector>

#include "ref/interpolate.h"
#include "ref/memory/cache.h"
#include "ref/texture/texture.h"

namespace rastsim {

// Stats keys texel_fetches, texture_cache_hits, texture_cache_misses, texture_dram_bytes,
// helper_pixels, texture_samples (docs/stats.md).
struct TextureStats {
  uint64_t texel_fetches = 0;
  uint64_t cache_hits = 0, cache_misses = 0;  // texel_fetches = hits + misses
  uint64_t dram_bytes = 0;                    // line fills (no cache: texel bytes)
  uint64_t helper_pixels = 0;                 // quad pixels shaded for derivatives only, never written
  // Level samples (one level's 1 or 4 texels filtered): 1 a nearest or bilinear sample, 2
  // a trilinear one that blends two levels, 1 one whose second weight is 0 (one level
  // read). The texel fetch port's requests (the timed stage's rate term B; not a stats key).
  uint64_t level_samples = 0;
  uint64_t samples[kTexFilters] = {};         // textured fragments, by TexFilter
  uint64_t total_samples() const { return samples[0] + samples[1] + samples[2]; }
};

// Byte offset of texel (i, j) in a level of w x h texels of `bytes` bytes each, from the
// level's start, and the level's footprint (bytes from its start past its last texel).
uint64_t texel_offset(TexLayout layout, int w, int h, int bytes, int i, int j);
uint64_t level_footprint(TexLayout layout, int w, int h, int bytes);

// The 2x2 quads (pixels 2x..2x+1, 2y..2y+1) of one triangle that reached the texture
// stage: each quad's coarse derivatives (QuadDerivatives: its top-left, top-right and
// bottom-left pixel centres by plane equations, extrapolated where not covered),
// computed once, and its helper pixels, the quads' pixels the triangle does not cover:
// 4 a quad less the covered pixels. One a triangle: clear() at the next.
class TriangleQuads {
 public:
  void clear() {
    quads_.clear();
    covered_ = 0;
  }
  // The derivatives of the quad of pixel (px, py) of tri (frac_bits: raster.coord_format's).
  const QuadDerivatives& derivatives(const SetupTriangle& tri, int px, int py, int frac_bits);
  void add_covered(uint64_t pixels) { covered_ += pixels; }
  uint64_t quads() const { return uint64_t(quads_.size()); }
  uint64_t helper_pixels() const { return 4 * quads() - covered_; }

 private:
  std::unordered_map<uint64_t, QuadDerivatives> quads_;  // by top-left pixel: y0 << 32 | x0
  uint64_t covered_ = 0;
};

class TextureUnit {
 public:
  explicit TextureUnit(const TextureParams& p);

  // The fragment f textured by state `ts` (enabled) with its quad's derivatives: the
  // texture colour combined into f's colour; every fetch counted.
  Fragment shade(const Fragment& f, const QuadDerivatives& d, const TextureState& ts, int frac_bits);

  TextureStats& stats() { return stats_; }
  const TextureStats& stats() const { return stats_; }

  // Called at every miss with the DRAM read it makes, in fetch order: the missed line's
  // byte address (line number x line_bytes) and line_bytes; without a cache the texel's
  // own address and bytes. Their bytes sum to stats().dram_bytes. Unset: nothing called
  // (render). The timed model's memory client (timing/texture_memory_port.h) sets it.
  std::function<void(uint64_t address, uint64_t bytes)> on_fill;

  struct Resident {  // one texture in memory, in the configured format
    std::shared_ptr<const TextureImage> image;  // held, so that its address is never reused
    std::vector<MipLevel> levels;      // the whole chain (`mipmap off` samples level 0 only)
    std::vector<uint64_t> level_base;  // byte address of each level
  };
  // ts's texture in memory, placed at its first use (the co-simulation's texel memory
  // and the RTL's level addresses come from here: one placement).
  const Resident& resident(const TextureState& ts);

 private:
  Rgba8 sample_level(const Resident& r, int level, const Fragment& f, const TextureState& ts, int frac_bits);
  void fetch(uint64_t address);

  TextureParams p_;
  std::optional<SetAssocCache> cache_;
  std::map<const TextureImage*, Resident> resident_;
  uint64_t next_base_;
  TextureStats stats_;
};

}  // namespace rastsim
