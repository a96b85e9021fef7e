// SPDX-License-Identifier: Apache-2.0
#include "rtlsim/area_memory.h"

#include <bit>

#include "config/arch_params.h"
#include "ref/memory/rop_memory.h"
#include "rtlsim/area.h"
#include "rtlsim/rtl_params.h"

namespace rastsim {

namespace {

uint64_t log2_exact(uint64_t power_of_two) { return uint64_t(std::countr_zero(power_of_two)); }

StorageArray cache_data_array(const std::string& prefix, uint64_t bytes) {
  StorageArray a{prefix + ".data", bytes * 8, false, 0};
  a.transistors = storage_transistors(a.bits, a.sram);
  return a;
}

// The arrays of one cache (`prefix`.data, .tags, .state) over a surface of `surface_bytes`
// bytes (its footprint, padding included).
void add_cache(std::vector<StorageArray>& out, const std::string& prefix, const CacheParams& c,
               uint64_t surface_bytes) {
  if (c.bytes == 0) return;
  const uint64_t lines = c.bytes / uint64_t(c.line_bytes);
  const uint64_t sets = lines / uint64_t(c.ways);
  const uint64_t address_bits = uint64_t(rop_cache_rtl_params(c, surface_bytes, 1).addr_w);  // rast_rop_cache's AddrW
  const uint64_t below_tag = log2_exact(uint64_t(c.line_bytes)) + log2_exact(sets);
  const uint64_t tag_bits = address_bits > below_tag ? address_bits - below_tag : 0;
  const uint64_t lru_bits = uint64_t(std::bit_width(unsigned(c.ways - 1)));  // a way's recency rank, 0..ways-1
  out.push_back(cache_data_array(prefix, c.bytes));
  out.push_back({prefix + ".tags", lines * tag_bits, false, 0});
  out.push_back({prefix + ".state", lines * (2 + lru_bits), false, 0});  // valid, dirty, rank
}

}  // namespace

uint64_t storage_transistors(uint64_t bits, bool& sram) {
  sram = bits >= kSramMinBits;
  if (!sram) return bits * kFlopBitTransistors;
  const uint64_t cells = bits * kSramCellTransistors;
  return cells + cells * kSramPeripheryPercent / 100;
}

std::vector<StorageArray> memory_storage(const MemoryParams& m, int width, int height, int samples, int depth_bits) {
  std::vector<StorageArray> out;
  if (!m.enabled) return out;
  // The surfaces and the depth cache as the functional model builds them (rop_memory.h):
  // plane compression tiles the depth surface by the block and makes a line one block.
  const SurfaceLayout color = color_surface_layout(m, width, height, samples);
  const SurfaceLayout depth = depth_surface_layout(m, width, height, samples, depth_bits);
  add_cache(out, "rop_color_cache", m.color_cache, color.footprint_bytes());
  add_cache(out, "rop_depth_cache", depth_cache_params(m, samples, depth_bits), depth.footprint_bytes());
  // Blocks over a surface as SurfaceClient counts them (edge blocks partly outside).
  const uint64_t blocks = uint64_t((width + m.block_width - 1) / m.block_width) *
                          uint64_t((height + m.block_height - 1) / m.block_height);
  if (m.fast_clear) {
    out.push_back({"rop_color.fast_clear_flags", blocks, false, 0});
    out.push_back({"rop_depth.fast_clear_flags", blocks, false, 0});
  }
  if (m.depth_compression == DepthCompression::Plane) out.push_back({"rop_depth.compression_flags", blocks, false, 0});
  for (StorageArray& a : out) a.transistors = storage_transistors(a.bits, a.sram);
  return out;
}

std::vector<StorageArray> memory_storage(const ArchParams& arch) {
  const RasterState& r = arch.raster;
  return memory_storage(arch.memory, r.fb_width, r.fb_height, r.samples, r.depth_bits);
}

std::vector<StorageArray> rop_cache_data_storage(const ArchParams& arch) {
  return {cache_data_array("rop_color_cache", uint64_t(rop_cache_rtl_params(arch).cache_bytes))};
}

std::vector<StorageArray> texture_cache_data_storage(const ArchParams& arch) {
  const TextureRtlParams p = texture_rtl_params(arch);
  std::vector<StorageArray> out;
  if (p.cache_bytes == 0) return out;  // no cache: rast_top ties the texel port off
  for (int k = 0; k < p.ports; ++k)
    out.push_back(cache_data_array("texture_cache.copy" + std::to_string(k), uint64_t(p.cache_bytes)));
  return out;
}

std::vector<StorageArray> tile_buffer_storage(const ArchParams& arch) {
  const RtlParams p = rtl_params(arch);  // Slots and DepthW as rast_top builds rast_tile_buffer_data
  const uint64_t slots = uint64_t(p.tile_buffer_samples);
  if (slots == 0) return {};  // immediate mode: rast_top builds no tile buffer
  std::vector<StorageArray> out{{"tile_buffer.color", slots * (32 + 1), false, 0},
                                {"tile_buffer.depth", slots * uint64_t(p.depth_w + 1), false, 0}};
  for (StorageArray& a : out) a.transistors = storage_transistors(a.bits, a.sram);
  return out;
}

StorageArray fragment_fifo_storage(const RtlParams& p) {
  // rast_top.sv's localparams Lanes, TileBeats, FragBeats and its beat_t.
  const uint64_t lanes = uint64_t(p.interp_fragments_per_cycle);
  const uint64_t fewest = p.interp_perspective != 0 ? uint64_t(p.interp_persp_lanes) : lanes;
  const uint64_t tile_beats = ((uint64_t{1} << (2 * p.tile_log2_max)) + fewest - 1) / fewest;
  const uint64_t depth = (uint64_t(p.fragment_fifo_entries) + 3) * tile_beats;
  const uint64_t width = 2 + lanes * (1 + 2 * uint64_t(p.pixel_w) + uint64_t(p.depth_w) + 24 + uint64_t(p.max_samples));
  StorageArray a{"fragment_fifo.beats", depth * width, false, 0};
  a.transistors = storage_transistors(a.bits, a.sram);
  return a;
}

std::vector<StorageArray> rast_top_storage(const ArchParams& arch) {
  std::vector<StorageArray> out{fragment_fifo_storage(rtl_params(arch))};
  for (StorageArray& a : texture_cache_data_storage(arch)) out.push_back(std::move(a));
  for (StorageArray& a : tile_buffer_storage(arch)) out.push_back(std::move(a));
  return out;
}

std::vector<StorageArray> design_storage(const ArchParams& arch) {
  std::vector<StorageArray> out = memory_storage(arch);
  for (StorageArray& a : rast_top_storage(arch)) out.push_back(std::move(a));
  return out;
}

void add_storage(AreaReport& r, const std::vector<StorageArray>& arrays) {
  for (const StorageArray& a : arrays) {
    r.storage.push_back(a);
    r.total.transistors += a.transistors;
  }
}

}  // namespace rastsim
