// SPDX-License-Identifier: Apache-2.0
// RTL parameters: what the Verilog raster pipeline (rtl/rast_*.sv) is built with, derived
// from a validated Config. The datapath widths are computed here with the equations of
// docs/fixed-point.md ("Datapath widths") from the coordinate format, so no width is
// typed twice: the Verilog gets them through the exported header, the C++ testbench
// through this struct.
//
// - rtl_params_from_config: Config -> RtlParams (format, widths, timing keys the RTL
//   implements, FIFO depths). Fill rule, cull mode and front face are not parameters:
//   they are run-time inputs of the RTL like the tile size (docs/rtl.md), driven from
//   the RasterState of the config being simulated.
// - rtl_params_verilog: the Verilog header (a parameter port list body) that
//   rtl/rast_top.sv includes; `rastsim export-rtl` and the build's exporter write it.
// - rtl_params_values / rtl_params_from_values: the parameters as a C++ initializer
//   list of ints (the table's order), which the build compiles into the registry of
//   verilated models (model/rtlsim/CMakeLists.txt), so a binary knows what each model was
//   built with without reading any config at run time.
// - rtl_params_compatible: whether an RTL library built for one config can simulate
//   another (same widths and timing, tile size and sample count at most the built
//   maxima: both are run-time inputs of the RTL, see docs/rtl.md).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "config/arch_params.h"

namespace rastsim {

struct RtlParams {
  // Coordinate format s.I.F and the widths that follow from it (docs/fixed-point.md).
  int coord_int = 0, coord_frac = 0;  // I, F
  int coord_w = 0;       // snapped vertex x, y: N + 1
  int coef_w = 0;        // edge a, b: N + 2
  int edge_w = 0;        // edge c and E(x, y), E + bias: 2N + 3
  int area_w = 0;        // area2 and barycentric weights, unsigned: 2N + 2
  int color_num_w = 0;   // colour numerator sum w_k c_k, unsigned: 2N + 10 + color_frac
  int color_frac = 0;    // interp.color_frac_bits: a vertex colour channel is unsigned 8.color_frac
  int depth_num_w = 0;   // depth numerator sum w_k z_k, unsigned: 2N + 2 + D
  int depth_w = 0;       // D = raster.depth_bits
  int pixel_w = 0;       // pixel x, y, unsigned: holds the schema's largest display.width/height - 1
  int tile_log2_max = 0; // log2 of raster.tile_size: the largest tile the RTL supports
  int tile_log2_w = 0;   // the tile_log2_i port: holds log2 of the schema's largest raster.tile_size
  // Multisampling: raster.samples is a run-time input up to max_samples (docs/rtl.md).
  int max_samples = 0;    // raster.max_samples: the largest raster.samples (sample mask bits a pixel)
  int sample_log2_w = 0;  // the samples_log2_i port: holds log2 of max_samples
  int sample_off_w = 0;   // a sample offset from the pixel centre, raw, signed: F + 1
  // Timing keys the RTL implements (config_schema_timing.cpp).
  int setup_interval = 0, setup_latency = 0;
  int coarse_tiles_per_cycle = 0;
  int fine_samples_per_cycle = 0, fine_accepted_tile_cycles = 0;
  int interp_fragments_per_cycle = 0, interp_latency = 0;
  // Texture coordinates and the perspective datapath (docs/clip-space.md).
  int tex_w = 0;                 // s, t: 1 + I + F of interp.texcoord_format, signed
  int interp_perspective = 0;    // interp.perspective: the reciprocal lanes are built
  int interp_persp_lanes = 0;    // lanes with a reciprocal: TimingParams::interp_lanes(false)
  int recip_seed_bits = 0, recip_iterations = 0;  // interp.recip_seed_bits, interp.recip_iterations
  int interp_recip_latency = 0;  // TimingParams::interp_recip_latency (the RTL checks its structure against it)
  // The texture stage (rtl/rast_texture_stage.sv; docs/texture.md "RTL"): texture_rtl_params' widths.
  int tex_frac = 0;         // F of interp.texcoord_format
  int tex_weight_bits = 0;  // texture.weight_bits
  int tex_size_w = 0;       // bits of a texture side (up to kMaxTextureExtent)
  int tex_addr_w = 0;       // bits of a texel's byte address
  // Its texture cache (rtl/rast_texture_cache.sv in rast_top): texture_rtl_params' cache
  // fields, all 0 with texture.cache_bytes = 0 (no RTL cache: the port tied off).
  int tex_cache_bytes = 0, tex_ways = 0, tex_line_bytes = 0, tex_ports = 0, tex_beat_bytes = 0;
  int tex_level_w = 0;      // bits of a mip level index (rast_texture_lod's LevelW)
  int tex_bias_w = 0;       // texlod_bias in s.8, signed (rast_texture_lod's BiasW)
  int fifo_triangle = 0, fifo_tile = 0, fifo_pixel = 0;
  int setup_fifo_entries = 0;  // fifo.setup_depth + setup's latency slots (TimingParams)
  int fragment_fifo_entries = 0;  // fifo.fragment_depth + the interpolator's latency slots (TimingParams), tiles
  int rop_pixels_per_cycle = 0, rop_clear_pixels_per_cycle = 0;  // rop.pixels_per_cycle, rop.clear_pixels_per_cycle
  int rop_len_w = 0;  // a ROP burst length in words, up to a clear's: clog2(clear pixels x max_samples + 1) bits
  // Hi-Z in rast_top (rtl/rast_top_hiz.sv): depth.hiz 0 off, 1 max, 2 minmax; its block
  // and on-chip entries (hiz_onchip_blocks; 3 and 1 when off, nothing built).
  int hiz_mode = 0, hiz_block_log2 = 0, hiz_blocks = 0;
  // The display's blocks past those (rtl/rast_hiz_spill.sv, in memory: 0 none, no spill
  // unit built) and log2 of an entry's bytes (hiz_entry_bytes).
  int hiz_spill_blocks = 0, hiz_entry_bytes_log2 = 0;
  // depth.hiz_sync = lagged: 1 (rast_top_hiz's Lagged; 0 the interlock, and without a table).
  int hiz_lagged = 0;
  // depth.early: 1 builds rtl/rast_early_z.sv in rast_top (0: none).
  int depth_early = 0;
  // pipeline.mode = binned (rtl/rast_tile_buffer.sv): the tile buffer's samples (0: no
  // tile buffer, immediate mode), its load/store beat in bytes (rop.resolve_bytes_per_cycle)
  // and in words (bytes / a depth sample's bytes: the widest beat).
  int tile_buffer_samples = 0, tile_port_bytes = 4, tile_port_words = 1;

  bool operator==(const RtlParams&) const = default;
};

RtlParams rtl_params(const ArchParams& arch);
// The Hi-Z parameters of a rast_top without a table (HizMode 0).
void rtl_params_without_hiz(RtlParams& p);

// The Verilog header: "parameter Name = value, // comment" lines (the last without a
// comma), to be `include`d in rast_top's parameter port list. `source` names the
// config in the banner.
std::string rtl_params_verilog(const RtlParams& p, const std::string& source);

// "{v0, v1, ...}": every parameter in the export table's order; rtl_params_from_values
// reads it back (throws std::invalid_argument on a wrong count).
std::string rtl_params_values(const RtlParams& p);
RtlParams rtl_params_from_values(const std::vector<int>& values);

// Every parameter as (Verilog name, value), in the export table's order (reports).
std::vector<std::pair<std::string, int>> rtl_params_named(const RtlParams& p);

// An RTL built with `built` can run `wanted` (tile size as a run-time input up to the
// built maximum). On false, `why` says which parameter differs.
bool rtl_params_compatible(const RtlParams& built, const RtlParams& wanted, std::string* why = nullptr);

// The scan-out RTL (rtl/scanout_*.sv) is built with the video timing, framebuffer size
// and DAC width of a config (video_timing.h, display.*, dac.bits).
struct ScanoutRtlParams {
  int h_active = 0, h_front_porch = 0, h_sync = 0, h_back_porch = 0;  // px
  int v_active = 0, v_front_porch = 0, v_sync = 0, v_back_porch = 0;  // lines
  int h_sync_positive = 0, v_sync_positive = 0;  // 1: the sync is high during the pulse
  int fb_width = 0, fb_height = 0;               // framebuffer, px
  int dac_bits = 0;                              // DAC code width a channel

  bool operator==(const ScanoutRtlParams&) const = default;
};

ScanoutRtlParams scanout_rtl_params(const ArchParams& arch, const DisplayParams& display);

// The 2D engine (rtl/rast_engine2d.sv, rast_line, rast_pattern, rast_rop3) is one
// verilated model for every config (its timing keys are run-time inputs): its two
// parameters, for the testbench's port packing (model/rtlsim/testbench.cpp, cosim_driver.h).
struct Engine2dRtlParams {
  int width = 0;      // Width: bits of a signed pixel index on its operation, clip and memory ports
  int lanes_max = 0;  // LanesMax: framebuffer lanes a beat, the largest engine2d.fill_pixels_per_cycle

  bool operator==(const Engine2dRtlParams&) const = default;
};
const Engine2dRtlParams& engine2d_rtl_params();

// The verilated engine (its public parameters, `built`) is the one the testbench packs
// ports for (`wanted`): every parameter equal. On false, `why` names the one that differs.
bool engine2d_rtl_params_compatible(const Engine2dRtlParams& built, const Engine2dRtlParams& wanted,
                                    std::string* why = nullptr);

// The reciprocal unit (rtl/rast_recip.sv), which `rastsim area --top rast_recip`
// synthesises as a root of its own.
struct RecipRtlParams {
  int seed_bits = 0;   // SEED_BITS: interp.recip_seed_bits, index bits of the seed table
  int iterations = 0;  // ITERATIONS: interp.recip_iterations, Newton-Raphson steps
};

// The ROP's cache of one surface (rtl/rast_rop_cache.sv; docs/rtl.md "ROP cache"), not
// yet in rast_top: `rastsim area --top rast_rop_cache` synthesises it as a root of its own
// with the colour cache's parameters (rop.color_cache_*), rop_cache_rtl_params(arch).
struct RopCacheRtlParams {
  int addr_w = 0;       // AddrW: bits of a byte offset in the surface (the bit width of its last byte's)
  int cache_bytes = 0;  // CacheBytes: rop.*_cache_bytes
  int ways = 0;         // Ways: rop.*_cache_ways
  int line_bytes = 0;   // LineBytes: rop.*_cache_line_bytes
  int word_bytes = 0;   // WordBytes: bytes of a sample (colour 4; depth 2 or 4)
};
// A cache `c` of a surface of `surface_bytes` bytes (its footprint, padding included) of
// word_bytes-byte samples.
RopCacheRtlParams rop_cache_rtl_params(const CacheParams& c, uint64_t surface_bytes, int word_bytes);
// ... the colour cache of a resolved config (over its colour surface); throws naming
// rop.color_cache_bytes when it is 0 (no cache to build).
RopCacheRtlParams rop_cache_rtl_params(const ArchParams& arch);

// The texture unit's datapath (rtl/rast_texture_*.sv; docs/texture.md "RTL"), standalone
// units not yet in rast_top: `rastsim area --top rast_texture_lod` (and _address) synthesise
// them with these, and tb/rtl_texture verilates them with the default config's
// (`rastsim_export_rtl --root`). The filter and the combine take no parameter (RGBA8 and
// 1/256 weights whatever the config).
struct TextureRtlParams {
  int tex_w = 0;        // TexW: s, t bits, 1 + I + F of interp.texcoord_format, signed
  int tex_frac = 0;     // TexFrac: F of interp.texcoord_format
  int weight_bits = 0;  // WeightBits: texture.weight_bits
  int size_w = 0;       // SizeW: bits of a texture side, up to kMaxTextureExtent (scene/texture_file.h)
  int level_w = 0;      // LevelW: bits of a mip level index (levels of the largest side)
  int bias_w = 0;       // BiasW: bits of texlod_bias in s.8, signed (256 x kMaxLodBias)
  int addr_w = 0;       // AddrW: bits of a texel's byte address (texture.base's schema maximum, twice)
  // rast_texture_cache (texture.cache_bytes 0: all 0; root_rtl_params refuses it).
  int cache_bytes = 0;  // CacheBytes: texture.cache_bytes
  int ways = 0;         // Ways: texture.ways
  int line_bytes = 0;   // LineBytes: texture.line_bytes
  int ports = 0;        // Ports: texel lookups a cycle, ceil(texels_per_cycle / bilinear_per_cycle) in 1..4
  int beat_bytes = 0;   // BeatBytes: a fill beat, min(line_bytes, kTextureFillBeatBytes)
};
// The texture cache's fill port: 16-byte (128-bit) beats, a design choice (not a config key).
inline constexpr int kTextureFillBeatBytes = 16;
TextureRtlParams texture_rtl_params(const ArchParams& arch);

// Hierarchical Z's units (docs/rtl.md "Hi-Z"), standalone, not yet in rast_top: the bound
// table rtl/rast_hiz.sv and the tile test rtl/rast_hiz_test.sv, which `rastsim area --top`
// synthesises with these (hiz_rtl_params(arch): throws naming depth.hiz when it is off
// and depth.hiz_bytes when no block is on chip).
struct HizRtlParams {
  // rast_hiz
  int depth_w = 0;        // DepthW: raster.depth_bits
  int pixel_w = 0;        // PixelW: rast_top's pixel index bits
  int block_log2 = 0;     // BlockLog2: log2 depth.hiz_block
  int min_max = 0;        // MinMax: depth.hiz = minmax
  int blocks = 0;         // Blocks: entries on chip, min(the display's blocks, depth.hiz_bytes / entry bytes)
  int tile_log2_max = 0;  // TileLog2Max: log2 raster.tile_size
  int lanes = 0;          // Lanes: depth writes a cycle, rop.pixels_per_cycle
  // rast_hiz_test (and DepthW, PixelW): rast_top's widths (RtlParams)
  int coord_w = 0, coord_frac = 0, coef_w = 0, edge_w = 0, area_w = 0;
};
HizRtlParams hiz_rtl_params(const ArchParams& arch);

// The parameters a standalone area root (area.h) takes from the config, as (its Verilog
// name, value) in its table's order: rast_recip's SEED_BITS and ITERATIONS, rast_rop_cache's
// AddrW, CacheBytes, Ways, LineBytes and WordBytes, rast_texture_lod's,
// rast_texture_address's and rast_texture_cache's TextureRtlParams fields (the cache's
// throws naming texture.cache_bytes when it is 0); none for a root without config
// parameters (rast_engine2d, the binary32 units) or another name.
std::vector<std::pair<std::string, int>> root_rtl_params(const std::string& root, const ArchParams& arch);
// Their names alone (what the root can be given), in the same order.
std::vector<std::string> root_rtl_param_names(const std::string& root);

// The Verilog header of the scan-out: "parameter int Name = value, // comment" lines,
// the body of the scan-out top's parameter port list (rtl/scanout_cosim_top.sv).
std::string scanout_rtl_params_verilog(const ScanoutRtlParams& p, const std::string& source);

}  // namespace rastsim
