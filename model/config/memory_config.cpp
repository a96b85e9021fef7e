// SPDX-License-Identifier: Apache-2.0
#include "config/memory_config.h"

#include <bit>

#include "ref/memory/rop_memory.h"

namespace rastsim {

namespace {

CacheParams cache_from_config(const Config& cfg, const std::string& surface) {
  const std::string pre = "rop." + surface + "_cache_";
  return {uint64_t(cfg.get_int(pre + "bytes")), int(cfg.get_int(pre + "ways")), int(cfg.get_int(pre + "line_bytes"))};
}

// A cache that exists must be ways x line x a power-of-two number of sets; `line_why`
// says where a line size other than the key's comes from.
void check_cache(const Config& cfg, const std::string& surface, const CacheParams& c, const std::string& line_why) {
  if (c.bytes == 0) return;
  const std::string pre = "rop." + surface + "_cache_";
  const uint64_t way_bytes = uint64_t(c.ways) * uint64_t(c.line_bytes);
  if (c.bytes % way_bytes == 0 && std::has_single_bit(c.bytes / way_bytes)) return;
  throw ConfigError(cfg.origin(pre + "bytes") + ": " + pre + "bytes = " + std::to_string(c.bytes) +
                    " is not " + pre + "ways (" + std::to_string(c.ways) + ") x the line (" +
                    std::to_string(c.line_bytes) + " bytes" + line_why + ") x a power-of-two number of sets");
}

// The colour and depth surfaces must not share a byte (the resolved image of a
// multisampled run is counted in bytes only, at no address).
void check_overlap(const Config& cfg, const MemoryParams& p) {
  const int w = int(cfg.get_int("display.width")), h = int(cfg.get_int("display.height"));
  const int samples = int(cfg.get_int("raster.samples")), depth_bits = int(cfg.get_int("raster.depth_bits"));
  const SurfaceLayout c = color_surface_layout(p, w, h, samples), d = depth_surface_layout(p, w, h, samples, depth_bits);
  if (c.base() + c.footprint_bytes() <= d.base() || d.base() + d.footprint_bytes() <= c.base()) return;
  throw ConfigError(cfg.origin("memory.depth_base") + ": the colour surface (memory.color_base = " +
                    std::to_string(c.base()) + ", " + std::to_string(c.footprint_bytes()) +
                    " bytes) and the depth surface (memory.depth_base = " + std::to_string(d.base()) + ", " +
                    std::to_string(d.footprint_bytes()) + " bytes) overlap: move one of them");
}

// pipeline.mode = binned: the parameter buffer (ref/memory/bin_memory.h) must not share a
// byte with either surface.
void check_parameter_buffer(const Config& cfg, const MemoryParams& p) {
  if (cfg.get_string("pipeline.mode") != "binned") return;
  const int w = int(cfg.get_int("display.width")), h = int(cfg.get_int("display.height"));
  const int samples = int(cfg.get_int("raster.samples")), depth_bits = int(cfg.get_int("raster.depth_bits"));
  const uint64_t base = uint64_t(cfg.get_int("bin.parameter_buffer_base"));
  const uint64_t end = base + uint64_t(cfg.get_int("bin.parameter_buffer_bytes"));
  for (const SurfaceLayout& s : {color_surface_layout(p, w, h, samples), depth_surface_layout(p, w, h, samples, depth_bits)}) {
    if (end <= s.base() || s.base() + s.footprint_bytes() <= base) continue;
    throw ConfigError(cfg.origin("bin.parameter_buffer_base") + ": the parameter buffer (bin.parameter_buffer_base = " +
                      std::to_string(base) + ", " + std::to_string(end - base) + " bytes) overlaps the " +
                      (s.base() == p.color_base ? "colour" : "depth") + " surface at " + std::to_string(s.base()) +
                      " (" + std::to_string(s.footprint_bytes()) + " bytes): move it (docs/binning.md)");
  }
}

}  // namespace

MemoryParams memory_params_from_config(const Config& cfg) {
  MemoryParams p;
  p.enabled = cfg.get_string("memory.model") != "fixed";
  p.layout = cfg.get_string("memory.fb_layout") == "tiled" ? FbLayout::Tiled : FbLayout::Linear;
  p.tile_width = int(cfg.get_int("memory.fb_tile_width"));
  p.tile_height = int(cfg.get_int("memory.fb_tile_height"));
  p.color_base = uint64_t(cfg.get_int("memory.color_base"));
  p.depth_base = uint64_t(cfg.get_int("memory.depth_base"));
  p.color_cache = cache_from_config(cfg, "color");
  p.depth_cache = cache_from_config(cfg, "depth");
  p.fast_clear = cfg.get_bool("rop.fast_clear");
  p.block_width = int(cfg.get_int("rop.fast_clear_block_width"));
  p.block_height = int(cfg.get_int("rop.fast_clear_block_height"));
  p.depth_compression = cfg.get_string("rop.depth_compression") == "plane" ? DepthCompression::Plane
                                                                           : DepthCompression::None;
  check_cache(cfg, "color", p.color_cache, "");
  if (p.depth_compression == DepthCompression::Plane) {
    if (p.depth_cache.bytes == 0)
      throw ConfigError(cfg.origin("rop.depth_compression") +
                        ": rop.depth_compression = plane needs a depth cache (its lines are the compressed blocks), "
                        "but rop.depth_cache_bytes = 0 (" + cfg.origin("rop.depth_cache_bytes") + ")");
    const CacheParams run = depth_cache_params(p, int(cfg.get_int("raster.samples")), int(cfg.get_int("raster.depth_bits")));
    check_cache(cfg, "depth", run, ": one rop.fast_clear_block_width x _height block of raster.samples samples, "
                                   "as rop.depth_compression = plane caches it");
  } else {
    check_cache(cfg, "depth", p.depth_cache, "");
  }
  // Only a modelled memory has addresses: a huge display with memory.model = fixed need
  // not move the surfaces apart.
  if (p.enabled) {
    check_overlap(cfg, p);
    check_parameter_buffer(cfg, p);
  }
  return p;
}

}  // namespace rastsim
