// SPDX-License-Identifier: Apache-2.0
// Keys of the functional memory system (docs/memory.md, "Framebuffer, caches, fast clear
// and compression"): the memory model switch, the framebuffer's layout and surface
// addresses, the ROP's colour and depth caches, fast clear and depth compression. The
// cross-key checks (cache geometry, surfaces that overlap) are in memory_config.cpp.
#include "config/config_schema.h"

namespace rastsim {

namespace {

// rop.<surface>_cache_bytes, _ways, _line_bytes.
void add_cache_keys(std::vector<ParamDef>& s, const std::string& surface) {
  using T = ParamType;
  const std::string pre = "rop." + surface + "_cache_";
  s.push_back({pre + "bytes", T::Int, int64_t{16384}, "bytes", 0, 1 << 24, {},
               "Capacity of the ROP's " + surface + " cache (write-back, write-allocate, true LRU); 0: no cache, every " +
                   "access goes to memory at its own size. Otherwise ways x line_bytes x a power-of-two set count"});
  s.push_back({pre + "ways", T::Int, int64_t{4}, "ways", 1, 64, {}, "Associativity of the ROP's " + surface + " cache"});
  s.push_back({pre + "line_bytes", T::Int, int64_t{64}, "bytes", 4, 4096, {},
               "Line of the ROP's " + surface + " cache: the bytes a fill reads and a write-back writes" +
                   (surface == "depth" ? std::string(" (with rop.depth_compression = plane a line is one block instead)")
                                       : std::string()),
               is_power_of_two, "a power of two"});
}

}  // namespace

void add_memory_params(std::vector<ParamDef>& s) {
  using T = ParamType;
  s.push_back({"memory.model", T::Enum, std::string("fixed"), "", 1, 0, {"fixed", "dram"},
               "fixed: every framebuffer access costs the ROP's fixed per-pixel cycles and no memory is modelled; "
               "dram: the memory system (ROP caches, fast clear, compression, DRAM) counts every byte "
               "(render --stats: dram_bytes_*, rop_*_cache_*, memory.clients.*)"});
  s.push_back({"memory.fb_layout", T::Enum, std::string("linear"), "", 1, 0, {"linear", "tiled"},
               "Framebuffer surfaces in memory: linear (row-major pixels) or tiled (memory.fb_tile_width x "
               "_height pixel tiles, row-major tiles, row-major pixels in a tile); a pixel's samples lie together"});
  s.push_back({"memory.fb_tile_width", T::Int, int64_t{8}, "px", 1, 128, {},
               "Tile width of memory.fb_layout = tiled", is_power_of_two, "a power of two"});
  s.push_back({"memory.fb_tile_height", T::Int, int64_t{8}, "px", 1, 128, {},
               "Tile height of memory.fb_layout = tiled", is_power_of_two, "a power of two"});
  s.push_back({"memory.color_base", T::Int, int64_t{0}, "bytes", 0, double(int64_t{1} << 40), {},
               "Byte address of the colour surface (RGBA8, 4 bytes a sample)", is_page_multiple,
               "a multiple of 4096"});
  s.push_back({"memory.depth_base", T::Int, int64_t{1} << 30, "bytes", 0, double(int64_t{1} << 40), {},
               "Byte address of the depth surface (2 bytes a sample for raster.depth_bits <= 16, else 4)",
               is_page_multiple, "a multiple of 4096"});
  add_cache_keys(s, "color");
  add_cache_keys(s, "depth");
  s.push_back({"rop.fast_clear", T::Bool, false, "", 1, 0, {},
               "Clears set an on-chip flag per block (rop.fast_clear_block_*) and write no memory; a cleared block "
               "is read as the clear value without a memory read until it is written back"});
  s.push_back({"rop.fast_clear_block_width", T::Int, int64_t{8}, "px", 1, 128, {},
               "Width of a fast-clear flag's block, and of a depth compression block", is_power_of_two,
               "a power of two"});
  s.push_back({"rop.fast_clear_block_height", T::Int, int64_t{8}, "px", 1, 128, {},
               "Height of a fast-clear flag's block, and of a depth compression block", is_power_of_two,
               "a power of two"});
  s.push_back({"rop.depth_compression", T::Enum, std::string("none"), "", 1, 0, {"none", "plane"},
               "Depth blocks in memory: none (raw) or plane (anchor, two slopes and 5-bit residuals a sample when "
               "they fit and are smaller, lossless; docs/memory.md); needs a depth cache"});
}

}  // namespace rastsim
