// SPDX-License-Identifier: Apache-2.0
// Keys of the texture unit (docs/texture.md): the texel format and layout textures are
// stored in, their base address, and the texture cache. The cache geometry's cross-key
// check is in texture_config.cpp.
#include "config/config_schema.h"

namespace rastsim {

void add_texture_params(std::vector<ParamDef>& s) {
  using T = ParamType;
  s.push_back({"texture.format", T::Enum, std::string("rgba8888"), "", 1, 0, {"rgba8888", "rgb565", "l8"},
               "Texel format in memory: rgba8888 (4 bytes), rgb565 (2 bytes, each channel rounded to nearest, alpha "
               "255) or l8 (1 byte, L = (77 R + 150 G + 29 B + 128) >> 8); texels are read back as RGBA8"});
  s.push_back({"texture.layout", T::Enum, std::string("linear"), "", 1, 0, {"linear", "tiled", "morton"},
               "Texels of a mip level in memory: linear (row-major), tiled (4 x 4-texel tiles, row-major) or morton "
               "(Z order over the level padded to a power-of-two square)"});
  s.push_back({"texture.base", T::Int, int64_t{1} << 31, "bytes", 0, double(int64_t{1} << 40), {},
               "Byte address of the first texture; textures follow in order of first use, each at a multiple of "
               "4096 bytes with its whole mip chain",
               is_page_multiple, "a multiple of 4096"});
  s.push_back({"texture.cache_bytes", T::Int, int64_t{16384}, "bytes", 0, 1 << 24, {},
               "Capacity of the texture cache (read-only, true LRU); 0: no cache, every texel fetch reads its own "
               "bytes from memory. Otherwise texture.ways x texture.line_bytes x a power-of-two set count"});
  s.push_back({"texture.ways", T::Int, int64_t{4}, "ways", 1, 64, {}, "Associativity of the texture cache"});
  s.push_back({"texture.weight_bits", T::Int, int64_t{8}, "bits", 1, 8, {},
               "Fraction bits of the bilinear weights: u - 1/2 rounded to nearest (ties up) at this many bits "
               "(8: weights in 1/256)"});
  s.push_back({"texture.line_bytes", T::Int, int64_t{64}, "bytes", 4, 4096, {},
               "Line of the texture cache: the bytes a miss reads from memory", is_power_of_two, "a power of two"});
  // The timed texture stage (simulate; docs/texture.md, "Timed texture stage").
  s.push_back({"texture.quads_per_cycle", T::Int, int64_t{1}, "quads/cycle", 1, 64, {},
               "Timed texture stage: 2x2 quads a cycle through level of detail and texel addressing (helper pixels "
               "included: they ride in their quad)"});
  s.push_back({"texture.bilinear_per_cycle", T::Int, int64_t{4}, "samples/cycle", 1, 64, {},
               "Timed texture stage: bilinear (or nearest) samples filtered a cycle; a trilinear sample is two "
               "bilinear ones (half rate)"});
  s.push_back({"texture.texels_per_cycle", T::Int, int64_t{16}, "texels/cycle", 1, 256, {},
               "Timed texture stage: the texture cache's port, texel fetches a cycle"});
  s.push_back({"texture.combine_per_cycle", T::Int, int64_t{4}, "fragments/cycle", 1, 64, {},
               "Timed texture stage: fragments through the texenv combine a cycle"});
  s.push_back({"texture.latency_cycles", T::Int, int64_t{8}, "cycles", 0, 4096, {},
               "Timed texture stage: cycles from a textured batch's last sample in the stage to the ROP's start on it (the "
               "RTL's datapath after its last texel lookup: the cache's response 2, the filter 3, the combine 2, the "
               "fragment FIFO 1; docs/texture.md, \"Timed texture stage\")"});
  s.push_back({"texture.miss_cycles", T::Int, int64_t{20}, "cycles", 0, 65536, {},
               "Timed texture stage, memory.model = \"fixed\": cycles each texture-cache line miss stalls the stage "
               "(its line read from memory); with memory.model = \"dram\" each miss is a blocking line fill through the "
               "memory system instead (docs/texture.md, \"Timed texture stage\")"});
}

}  // namespace rastsim
