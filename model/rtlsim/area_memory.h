// SPDX-License-Identifier: Apache-2.0
// The on-chip storage of the ROP's memory system (docs/memory.md) that `rastsim area`
// counts beside the synthesised RTL (docs/area.md, "Storage of the memory system"). The
// whole design's report has no cache RTL in it (rtl/rast_rop_cache.sv is not yet in
// rast_top), so every array is counted from the config by a stated rule; `--top
// rast_rop_cache` synthesises the cache's tags and state and counts its data array
// (rast_rop_cache_data, a blackbox to Yosys) by the same rule.
//
// - Arrays a cache (rop.color_cache_*, rop.depth_cache_*; none when its bytes are 0):
//   data (bytes x 8 bits), tags (a tag a line) and state (valid and dirty a line, an LRU
//   rank of log2(ways) bits a way). The tag is the line address above the set index:
//   address bits of the surface (rast_rop_cache's AddrW, rop_cache_rtl_params: the cache
//   indexes the byte offset in its surface, the base is added past it) - log2(line
//   bytes) - log2(sets).
// - Fast-clear flags (rop.fast_clear): one bit a fast-clear block over each surface.
// - Plane compression (rop.depth_compression = plane): one bit a depth block, whether
//   memory holds it plane-encoded (a fill reads the plane size or the raw size).
// - Transistors: an array of at least kSramMinBits bits is 6T SRAM cells plus
//   kSramPeripheryPercent for its periphery; a smaller one is flip-flops priced as the
//   synthesised RTL prices an enabled register with a read port.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "ref/memory/memory_params.h"

namespace rastsim {

struct AreaReport;
struct ArchParams;
struct RtlParams;

// The SRAM cell: six transistors a bit (the 6T cell; Weste and Harris, "CMOS VLSI Design",
// 4th ed., section 12.2.1).
inline constexpr uint64_t kSramCellTransistors = 6;
// Decoders, precharge, sense amplifiers, write drivers and column muxes, as a share of the
// cells' transistors: an assumption. A square array of n bits has about sqrt(n) columns of
// some 20 transistors and sqrt(n) rows of some 10, 7 % of 6n at 4 kbit and less above it.
inline constexpr uint64_t kSramPeripheryPercent = 10;
// A flip-flop bit as Yosys' `stat -tech cmos` prices the synthesised RTL's registers: the D
// flop (16), the 2:1 mux dfflegalize makes of its write enable (12), and its share of the
// read port (an n-entry read is n - 1 2:1 muxes an output bit: about one mux a bit, 12).
inline constexpr uint64_t kFlopBitTransistors = 16 + 12 + 12;
// Arrays below this many bits are flip-flops (small, flash-cleared and read-modify-written
// every access); from it on, SRAM. 4 kbit: an assumption, stated in docs/area.md.
inline constexpr uint64_t kSramMinBits = 4096;

// One array of storage bits.
struct StorageArray {
  std::string name;  // "rop_color_cache.data", "rop_depth.fast_clear_flags", ...
  uint64_t bits = 0;
  bool sram = false;  // counted as SRAM (else flip-flops), by kSramMinBits
  uint64_t transistors = 0;
};

// The transistors of an array of `bits` bits by the rule above; `sram` set to the kind.
uint64_t storage_transistors(uint64_t bits, bool& sram);

// The memory system's storage for a framebuffer of width x height pixels of `samples`
// samples and depth_bits-bit depth: empty when the memory system is off (`fixed`).
std::vector<StorageArray> memory_storage(const MemoryParams& m, int width, int height, int samples, int depth_bits);
// ... for a resolved config: its display size, raster.samples and raster.depth_bits.
std::vector<StorageArray> memory_storage(const ArchParams& arch);

// The data array of rast_rop_cache as `rastsim area --top rast_rop_cache` builds it (the
// colour cache): "rop_color_cache.data", bytes x 8 bits.
std::vector<StorageArray> rop_cache_data_storage(const ArchParams& arch);
// The data arrays of rast_texture_cache as `rastsim area --top rast_texture_cache` builds
// it: Ports copies (a read port each, every fill written to all), "texture_cache.copy<p>.data",
// texture.cache_bytes x 8 bits each; none without a cache (texture.cache_bytes = 0).
std::vector<StorageArray> texture_cache_data_storage(const ArchParams& arch);
// The arrays of rast_tile_buffer (binned mode, rast_tile_buffer_data) as `rastsim area
// --top rast_tile_buffer` builds it: "tile_buffer.color", TileBufferSamples x (32 + 1)
// bits, and "tile_buffer.depth", TileBufferSamples x (raster.depth_bits + 1) bits (a
// word and its valid bit a sample); none in immediate mode (no tile buffer).
std::vector<StorageArray> tile_buffer_storage(const ArchParams& arch);
// The fragment FIFO's ring of beats (rtl/rast_fragment_fifo_data.sv in rast_top):
// "fragment_fifo.beats", FragBeats x BeatW bits with rast_top's derived parameters:
// FragBeats = (FragmentFifoEntries + 3) x TileBeats, TileBeats = ceil(4^TileLog2Max / the
// fewest lanes a beat: InterpPerspLanes when perspective is built, else Lanes), BeatW =
// 2 (marker, last) + Lanes x (1 lane bit + 2 PixelW + DepthW + 24 colour + MaxSamples),
// Lanes = InterpFragmentsPerCycle. Every config has one.
StorageArray fragment_fifo_storage(const RtlParams& p);
// What rast_top holds as blackboxes: the fragment FIFO's beats, the texture cache's data
// copies (rast_top's g_tex_cache) and the tile buffer's arrays (g_bins), counted for
// `--top rast_top` and the whole design.
std::vector<StorageArray> rast_top_storage(const ArchParams& arch);
// The whole design's counted arrays (`rastsim area`, `rastsim sweep --area`): the memory
// system's (memory_storage), then rast_top's (rast_top_storage).
std::vector<StorageArray> design_storage(const ArchParams& arch);

// Adds the arrays to the report (its storage rows) and their transistors to its total.
void add_storage(AreaReport& r, const std::vector<StorageArray>& arrays);

}  // namespace rastsim
