// SPDX-License-Identifier: Apache-2.0
#include "rtlsim/rtl_params.h"
#include "config/timing_params.h"

#include <algorithm>
#include <bit>
#include <sstream>
#include <stdexcept>

#include "ref/fixed_point.h"
#include "ref/hiz_entry.h"
#include "ref/raster_state.h"
#include "config/raster_state_config.h"
#include "config/video_timing.h"
#include "ref/memory/rop_memory.h"
#include "ref/memory/surface_layout.h"
#include "config/texture_config.h"
#include "scene/texture_file.h"

namespace rastsim {

namespace {

// Every exported parameter once: Verilog name, member, meaning. The export, the
// compatibility check, the registry's initializer and the testbench all walk this table.
template <class P>
struct ParamField {
  const char* name;
  int P::*member;
  const char* comment;
};

// "  parameter int Name = value,  // comment" a field, the last without the comma.
template <class P, size_t N>
void write_parameters(std::ostream& os, const P& p, const ParamField<P> (&fields)[N]) {
  for (size_t k = 0; k < N; ++k)
    os << "  parameter int " << fields[k].name << " = " << p.*fields[k].member << (k + 1 < N ? "," : " ")
       << "  // " << fields[k].comment << "\n";
}

constexpr ParamField<RtlParams> kFields[] = {
    {"CoordInt", &RtlParams::coord_int, "I of raster.coord_format s.I.F"},
    {"CoordFrac", &RtlParams::coord_frac, "F of raster.coord_format (sub-pixel bits)"},
    {"CoordW", &RtlParams::coord_w, "snapped vertex x, y: N + 1 bits, signed"},
    {"CoefW", &RtlParams::coef_w, "edge a, b: N + 2 bits, signed"},
    {"EdgeW", &RtlParams::edge_w, "edge c, E(x, y), E + bias: 2N + 3 bits, signed"},
    {"AreaW", &RtlParams::area_w, "area2 and weights: 2N + 2 bits, unsigned"},
    {"ColorNumW", &RtlParams::color_num_w, "colour numerator: 2N + 10 + ColorFrac bits, unsigned"},
    {"ColorFrac", &RtlParams::color_frac, "interp.color_frac_bits: a vertex colour channel is unsigned 8.ColorFrac"},
    {"DepthNumW", &RtlParams::depth_num_w, "depth numerator: 2N + 2 + D bits, unsigned"},
    {"DepthW", &RtlParams::depth_w, "D = raster.depth_bits"},
    {"PixelW", &RtlParams::pixel_w, "pixel x, y: unsigned, up to the largest display.width/height"},
    {"TileLog2Max", &RtlParams::tile_log2_max, "log2 of the largest tile (raster.tile_size)"},
    {"TileLog2W", &RtlParams::tile_log2_w, "tile_log2_i bits: up to log2 of the largest raster.tile_size"},
    {"MaxSamples", &RtlParams::max_samples, "largest raster.samples: sample mask bits a pixel"},
    {"SampleLog2W", &RtlParams::sample_log2_w, "samples_log2_i bits: up to log2 of MaxSamples"},
    {"SampleOffW", &RtlParams::sample_off_w, "sample offset from the pixel centre: F + 1 bits, signed"},
    {"SetupInterval", &RtlParams::setup_interval, "setup.interval_cycles"},
    {"SetupLatency", &RtlParams::setup_latency, "setup.latency_cycles"},
    {"CoarseTilesPerCycle", &RtlParams::coarse_tiles_per_cycle, "coarse.tiles_per_cycle"},
    {"FineSamplesPerCycle", &RtlParams::fine_samples_per_cycle, "fine.samples_per_cycle"},
    {"FineAcceptedTileCycles", &RtlParams::fine_accepted_tile_cycles, "fine.accepted_tile_cycles"},
    {"InterpFragmentsPerCycle", &RtlParams::interp_fragments_per_cycle, "interp.fragments_per_cycle"},
    {"InterpLatency", &RtlParams::interp_latency, "interp.latency_cycles"},
    {"TexW", &RtlParams::tex_w, "texture coordinate s, t: 1 + I + F of interp.texcoord_format, signed"},
    {"InterpPerspective", &RtlParams::interp_perspective, "interp.perspective: 1 builds the reciprocal lanes"},
    {"InterpPerspLanes", &RtlParams::interp_persp_lanes, "lanes with a reciprocal: min(interp.fragments_per_cycle, recip.lanes)"},
    {"RecipSeedBits", &RtlParams::recip_seed_bits, "interp.recip_seed_bits"},
    {"RecipIterations", &RtlParams::recip_iterations, "interp.recip_iterations"},
    {"InterpRecipLatency", &RtlParams::interp_recip_latency, "the reciprocal unit's stages: 2 + 2 RecipIterations, 0 without it"},
    {"TexFrac", &RtlParams::tex_frac, "F of interp.texcoord_format"},
    {"TexWeightBits", &RtlParams::tex_weight_bits, "texture.weight_bits"},
    {"TexSizeW", &RtlParams::tex_size_w, "bits of a texture side (up to the largest texture)"},
    {"TexAddrW", &RtlParams::tex_addr_w, "bits of a texel's byte address"},
    {"TexCacheBytes", &RtlParams::tex_cache_bytes, "texture.cache_bytes (0: no texture cache)"},
    {"TexWays", &RtlParams::tex_ways, "texture.ways"},
    {"TexLineBytes", &RtlParams::tex_line_bytes, "texture.line_bytes"},
    {"TexPorts", &RtlParams::tex_ports, "texel lookups a cycle: texels_per_cycle / bilinear_per_cycle, 1..4"},
    {"TexBeatBytes", &RtlParams::tex_beat_bytes, "bytes of a texture line fill beat"},
    {"TexLevelW", &RtlParams::tex_level_w, "bits of a mip level index"},
    {"TexBiasW", &RtlParams::tex_bias_w, "texlod_bias in s.8, signed"},
    {"TriangleFifoDepth", &RtlParams::fifo_triangle, "fifo.triangle_depth"},
    {"SetupFifoEntries", &RtlParams::setup_fifo_entries, "fifo.setup_depth + setup latency slots"},
    {"TileFifoDepth", &RtlParams::fifo_tile, "fifo.tile_depth"},
    {"PixelFifoDepth", &RtlParams::fifo_pixel, "fifo.pixel_depth"},
    {"FragmentFifoEntries", &RtlParams::fragment_fifo_entries, "fifo.fragment_depth + interpolator latency slots, tiles"},
    {"RopPixelsPerCycle", &RtlParams::rop_pixels_per_cycle, "rop.pixels_per_cycle: ROP accesses a cycle"},
    {"RopClearPixelsPerCycle", &RtlParams::rop_clear_pixels_per_cycle, "rop.clear_pixels_per_cycle"},
    {"RopLenW", &RtlParams::rop_len_w, "ROP burst length bits: clog2(RopClearPixelsPerCycle MaxSamples + 1)"},
    {"HizMode", &RtlParams::hiz_mode, "depth.hiz: 0 off (no table built), 1 max, 2 minmax"},
    {"HizBlockLog2", &RtlParams::hiz_block_log2, "log2 depth.hiz_block"},
    {"HizBlocks", &RtlParams::hiz_blocks, "Hi-Z entries on chip: depth.hiz_bytes / entry bytes, at most the display's"},
    {"HizSpillBlocks", &RtlParams::hiz_spill_blocks, "the display's Hi-Z blocks past HizBlocks, in memory (client hiz)"},
    {"HizEntryBytesLog2", &RtlParams::hiz_entry_bytes_log2, "log2 of a Hi-Z entry's bytes (hiz_entry_bytes)"},
    {"HizLagged", &RtlParams::hiz_lagged, "depth.hiz_sync: 0 interlock, 1 lagged (rast_top_hiz's walk holds only for a marker)"},
    {"DepthEarly", &RtlParams::depth_early, "depth.early: 1 builds the early depth test (rtl/rast_early_z.sv)"},
    {"TileBufferSamples", &RtlParams::tile_buffer_samples,
     "pipeline.mode = binned: bin.tile_buffer_bytes / (4 + depth bytes) samples; 0: immediate (no tile buffer)"},
    {"TilePortBytes", &RtlParams::tile_port_bytes, "binned: rop.resolve_bytes_per_cycle, a load or store beat; else 4"},
    {"TilePortWords", &RtlParams::tile_port_words, "binned: TilePortBytes / depth bytes, words of a beat; else 1"},
};

constexpr ParamField<ScanoutRtlParams> kScanoutFields[] = {
    {"HActive", &ScanoutRtlParams::h_active, "active pixels a line"},
    {"HFrontPorch", &ScanoutRtlParams::h_front_porch, "px from the last active pixel to hsync"},
    {"HSync", &ScanoutRtlParams::h_sync, "hsync width, px"},
    {"HBackPorch", &ScanoutRtlParams::h_back_porch, "px from the end of hsync to the next line"},
    {"VActive", &ScanoutRtlParams::v_active, "active lines a frame"},
    {"VFrontPorch", &ScanoutRtlParams::v_front_porch, "lines from the last active line to vsync"},
    {"VSync", &ScanoutRtlParams::v_sync, "vsync width, lines"},
    {"VBackPorch", &ScanoutRtlParams::v_back_porch, "lines from the end of vsync to the next frame"},
    {"HSyncPositive", &ScanoutRtlParams::h_sync_positive, "1: hsync is high during the pulse"},
    {"VSyncPositive", &ScanoutRtlParams::v_sync_positive, "1: vsync is high during the pulse"},
    {"FbWidth", &ScanoutRtlParams::fb_width, "framebuffer width, px (display.width)"},
    {"FbHeight", &ScanoutRtlParams::fb_height, "framebuffer height, px (display.height)"},
    {"DacBits", &ScanoutRtlParams::dac_bits, "DAC code width a channel (dac.bits)"},
};

constexpr ParamField<Engine2dRtlParams> kEngine2dFields[] = {
    {"Width", &Engine2dRtlParams::width, "bits of a signed pixel index"},
    {"LanesMax", &Engine2dRtlParams::lanes_max, "largest engine2d.fill_pixels_per_cycle"},
};

// The reciprocal unit synthesised as a root of its own (`rastsim area --top rast_recip`):
// its parameters from the config (rast_recip's names).
constexpr ParamField<RecipRtlParams> kRecipFields[] = {
    {"SEED_BITS", &RecipRtlParams::seed_bits, "interp.recip_seed_bits"},
    {"ITERATIONS", &RecipRtlParams::iterations, "interp.recip_iterations"},
};

// The ROP's cache synthesised as a root of its own (`rastsim area --top rast_rop_cache`).
constexpr ParamField<RopCacheRtlParams> kRopCacheFields[] = {
    {"AddrW", &RopCacheRtlParams::addr_w, "bits of a byte offset in the surface"},
    {"CacheBytes", &RopCacheRtlParams::cache_bytes, "rop.color_cache_bytes"},
    {"Ways", &RopCacheRtlParams::ways, "rop.color_cache_ways"},
    {"LineBytes", &RopCacheRtlParams::line_bytes, "rop.color_cache_line_bytes"},
    {"WordBytes", &RopCacheRtlParams::word_bytes, "bytes of a colour sample"},
};

// The texture unit's units synthesised as roots of their own (`rastsim area --top
// rast_texture_lod`, `--top rast_texture_address`): each its own subset of TextureRtlParams.
constexpr ParamField<TextureRtlParams> kTextureLodFields[] = {
    {"TexW", &TextureRtlParams::tex_w, "texture coordinate s, t: 1 + I + F of interp.texcoord_format, signed"},
    {"TexFrac", &TextureRtlParams::tex_frac, "F of interp.texcoord_format"},
    {"SizeW", &TextureRtlParams::size_w, "bits of a texture side (up to the largest texture)"},
    {"LevelW", &TextureRtlParams::level_w, "bits of a mip level index"},
    {"BiasW", &TextureRtlParams::bias_w, "texlod_bias in s.8, signed"},
};
constexpr ParamField<TextureRtlParams> kTextureAddressFields[] = {
    {"TexW", &TextureRtlParams::tex_w, "texture coordinate s, t: 1 + I + F of interp.texcoord_format, signed"},
    {"TexFrac", &TextureRtlParams::tex_frac, "F of interp.texcoord_format"},
    {"WeightBits", &TextureRtlParams::weight_bits, "texture.weight_bits"},
    {"SizeW", &TextureRtlParams::size_w, "bits of a texture side (up to the largest texture)"},
    {"AddrW", &TextureRtlParams::addr_w, "bits of a texel's byte address"},
};
constexpr ParamField<TextureRtlParams> kTextureCacheFields[] = {
    {"AddrW", &TextureRtlParams::addr_w, "bits of a texel's byte address"},
    {"CacheBytes", &TextureRtlParams::cache_bytes, "texture.cache_bytes"},
    {"Ways", &TextureRtlParams::ways, "texture.ways"},
    {"LineBytes", &TextureRtlParams::line_bytes, "texture.line_bytes"},
    {"Ports", &TextureRtlParams::ports, "texel lookups a cycle: texels_per_cycle / bilinear_per_cycle, 1..4"},
    {"BeatBytes", &TextureRtlParams::beat_bytes, "bytes of a fill beat"},
};

// Hierarchical Z's units synthesised as roots of their own (`rastsim area --top rast_hiz`,
// `--top rast_hiz_test`).
constexpr ParamField<HizRtlParams> kHizFields[] = {
    {"DepthW", &HizRtlParams::depth_w, "raster.depth_bits"},
    {"PixelW", &HizRtlParams::pixel_w, "pixel index bits"},
    {"BlockLog2", &HizRtlParams::block_log2, "log2 depth.hiz_block"},
    {"MinMax", &HizRtlParams::min_max, "depth.hiz = minmax"},
    {"Blocks", &HizRtlParams::blocks, "entries on chip: depth.hiz_bytes / entry bytes, at most the display's"},
    {"TileLog2Max", &HizRtlParams::tile_log2_max, "log2 raster.tile_size"},
    {"Lanes", &HizRtlParams::lanes, "depth writes a cycle: rop.pixels_per_cycle"},
};
constexpr ParamField<HizRtlParams> kHizTestFields[] = {
    {"CoordW", &HizRtlParams::coord_w, "N + 1"},
    {"CoordFrac", &HizRtlParams::coord_frac, "F of raster.coord_format"},
    {"CoefW", &HizRtlParams::coef_w, "N + 2"},
    {"EdgeW", &HizRtlParams::edge_w, "2N + 3"},
    {"AreaW", &HizRtlParams::area_w, "2N + 2"},
    {"DepthW", &HizRtlParams::depth_w, "raster.depth_bits"},
    {"PixelW", &HizRtlParams::pixel_w, "pixel index bits"},
};

// (name, value) of each field of `p`, in the table's order.
template <class P, size_t N>
std::vector<std::pair<std::string, int>> named_fields(const P& p, const ParamField<P> (&fields)[N]) {
  std::vector<std::pair<std::string, int>> out;
  for (const auto& f : fields) out.emplace_back(f.name, p.*f.member);
  return out;
}

// Bits of the 2D engine's signed pixel indices: a 2D command's coordinates, clipped or
// not (a line's far end, a blit's source), with room above the largest framebuffer.
constexpr int kEngine2dIndexBits = 20;

}  // namespace

const Engine2dRtlParams& engine2d_rtl_params() {
  static const Engine2dRtlParams p{
      kEngine2dIndexBits, static_cast<int>(find_param("engine2d.fill_pixels_per_cycle")->max)};
  return p;
}

bool engine2d_rtl_params_compatible(const Engine2dRtlParams& built, const Engine2dRtlParams& wanted,
                                    std::string* why) {
  for (const auto& f : kEngine2dFields) {
    if (built.*f.member == wanted.*f.member) continue;
    if (why)
      *why = std::string(f.name) + " is " + std::to_string(wanted.*f.member) + " (" + f.comment +
             "), the RTL was built with " + std::to_string(built.*f.member);
    return false;
  }
  return true;
}

RopCacheRtlParams rop_cache_rtl_params(const CacheParams& c, uint64_t surface_bytes, int word_bytes) {
  RopCacheRtlParams p;
  p.addr_w = surface_bytes > 1 ? int(std::bit_width(surface_bytes - 1)) : 0;
  p.cache_bytes = int(c.bytes);
  p.ways = c.ways;
  p.line_bytes = c.line_bytes;
  p.word_bytes = word_bytes;
  return p;
}

RopCacheRtlParams rop_cache_rtl_params(const ArchParams& arch) {
  const RasterState& r = arch.raster;
  if (arch.memory.color_cache.bytes == 0)
    throw std::runtime_error("rast_rop_cache is built with the colour cache's parameters, and rop.color_cache_bytes "
                             "is 0 (no cache): set it (e.g. --set rop.color_cache_bytes=16384)");
  const SurfaceLayout color = color_surface_layout(arch.memory, r.fb_width, r.fb_height, r.samples);
  return rop_cache_rtl_params(arch.memory.color_cache, color.footprint_bytes(), kColorBytesPerSample);
}

HizRtlParams hiz_rtl_params(const ArchParams& arch) {
  const RasterState& r = arch.raster;
  if (r.hiz_mode == HizMode::Off)
    throw std::runtime_error("rast_hiz and rast_hiz_test are built with depth.hiz's parameters, and depth.hiz is "
                             "off: set it (e.g. --set depth.hiz=max)");
  const RtlParams w = rtl_params(arch);
  HizRtlParams p;
  p.depth_w = w.depth_w;
  p.pixel_w = w.pixel_w;
  p.block_log2 = std::countr_zero(unsigned(r.hiz_block));
  p.min_max = r.hiz_mode == HizMode::MinMax ? 1 : 0;
  p.blocks = int(hiz_onchip_blocks(r.hiz_mode, r.hiz_block, r.hiz_bytes, r.fb_width, r.fb_height, r.depth_bits));
  if (p.blocks == 0)
    throw std::runtime_error("rast_hiz holds the on-chip part of the table, and depth.hiz_bytes = " +
                             std::to_string(r.hiz_bytes) + " holds no " +
                             std::to_string(hiz_entry_bytes(r.hiz_mode, r.hiz_block, r.depth_bits)) +
                             "-byte entry: set it larger");
  p.tile_log2_max = w.tile_log2_max;
  p.lanes = w.rop_pixels_per_cycle;
  p.coord_w = w.coord_w;
  p.coord_frac = w.coord_frac;
  p.coef_w = w.coef_w;
  p.edge_w = w.edge_w;
  p.area_w = w.area_w;
  return p;
}

TextureRtlParams texture_rtl_params(const ArchParams& arch) {
  TextureRtlParams p;
  const auto& tc = arch.raster.texcoord_format;
  p.tex_w = tc.total_bits();
  p.tex_frac = tc.frac_bits;
  p.weight_bits = texture_params_from_config(arch.config).weight_bits;
  // A side of up to kMaxTextureExtent texels; its mip chain has bit_width(extent) levels.
  p.size_w = int(std::bit_width(unsigned(kMaxTextureExtent)));
  p.level_w = int(std::bit_width(unsigned(p.size_w - 1)));
  p.bias_w = int(std::bit_width(unsigned(kMaxLodBias * 256))) + 1;
  // Textures are placed from texture.base upwards: room for the largest base and as many
  // bytes again above it.
  p.addr_w = int(std::bit_width(uint64_t(find_param("texture.base")->max))) + 1;
  // The cache serves one lane (a bilinear sample a cycle): the stage's texel port shared
  // by its bilinear_per_cycle lanes, at most a request's 4 texels.
  const CacheParams c = texture_params_from_config(arch.config).cache;
  if (c.bytes > 0) {
    p.cache_bytes = int(c.bytes);
    p.ways = c.ways;
    p.line_bytes = c.line_bytes;
    p.ports = int(arch.timing.texture_cache_ports());
    p.beat_bytes = std::min(c.line_bytes, kTextureFillBeatBytes);
  }
  return p;
}

std::vector<std::string> root_rtl_param_names(const std::string& root) {
  std::vector<std::string> out;
  if (root == "rast_recip")
    for (const auto& f : kRecipFields) out.emplace_back(f.name);
  if (root == "rast_rop_cache")
    for (const auto& f : kRopCacheFields) out.emplace_back(f.name);
  if (root == "rast_texture_lod")
    for (const auto& f : kTextureLodFields) out.emplace_back(f.name);
  if (root == "rast_texture_address")
    for (const auto& f : kTextureAddressFields) out.emplace_back(f.name);
  if (root == "rast_texture_cache")
    for (const auto& f : kTextureCacheFields) out.emplace_back(f.name);
  if (root == "rast_hiz")
    for (const auto& f : kHizFields) out.emplace_back(f.name);
  if (root == "rast_hiz_test")
    for (const auto& f : kHizTestFields) out.emplace_back(f.name);
  return out;
}

std::vector<std::pair<std::string, int>> root_rtl_params(const std::string& root, const ArchParams& arch) {
  if (root == "rast_recip")
    return named_fields(RecipRtlParams{arch.raster.recip_seed_bits, arch.raster.recip_iterations}, kRecipFields);
  if (root == "rast_rop_cache") return named_fields(rop_cache_rtl_params(arch), kRopCacheFields);
  if (root == "rast_texture_lod") return named_fields(texture_rtl_params(arch), kTextureLodFields);
  if (root == "rast_texture_address") return named_fields(texture_rtl_params(arch), kTextureAddressFields);
  if (root == "rast_texture_cache") {
    if (texture_params_from_config(arch.config).cache.bytes == 0)
      throw std::runtime_error("rast_texture_cache is built with the texture cache's parameters, and "
                               "texture.cache_bytes is 0 (no cache): set it (e.g. --set texture.cache_bytes=16384)");
    return named_fields(texture_rtl_params(arch), kTextureCacheFields);
  }
  if (root == "rast_hiz") return named_fields(hiz_rtl_params(arch), kHizFields);
  if (root == "rast_hiz_test") return named_fields(hiz_rtl_params(arch), kHizTestFields);
  return {};
}

ScanoutRtlParams scanout_rtl_params(const ArchParams& arch, const DisplayParams& display) {
  const VideoTiming& t = display.video;
  ScanoutRtlParams p;
  p.h_active = t.h_active;
  p.h_front_porch = t.h_front_porch;
  p.h_sync = t.h_sync;
  p.h_back_porch = t.h_back_porch;
  p.v_active = t.v_active;
  p.v_front_porch = t.v_front_porch;
  p.v_sync = t.v_sync;
  p.v_back_porch = t.v_back_porch;
  p.h_sync_positive = t.h_sync_positive ? 1 : 0;
  p.v_sync_positive = t.v_sync_positive ? 1 : 0;
  p.fb_width = arch.raster.fb_width;
  p.fb_height = arch.raster.fb_height;
  p.dac_bits = display.dac.bits;
  return p;
}

std::string scanout_rtl_params_verilog(const ScanoutRtlParams& p, const std::string& source) {
  std::ostringstream os;
  os << "// Generated by `rastsim export-rtl-scanout` from " << source << ". Do not edit.\n"
     << "// The body of the scan-out top's parameter port list; computed in model/rtlsim/rtl_params.cpp.\n";
  write_parameters(os, p, kScanoutFields);
  return os.str();
}

// Hi-Z (rtl/rast_top_hiz.sv): built when depth.hiz is on (the state decides at run time
// whether it applies: rast_top_hiz's `on`), with at least one entry on chip.
static void set_hiz_params(const RasterState& st, RtlParams& p) {
  const int64_t hiz_blocks =
      st.hiz_mode == HizMode::Off
          ? 0
          : hiz_onchip_blocks(st.hiz_mode, st.hiz_block, st.hiz_bytes, st.fb_width, st.fb_height, st.depth_bits);
  if (hiz_blocks == 0) {
    rtl_params_without_hiz(p);
  } else {
    p.hiz_mode = st.hiz_mode == HizMode::MinMax ? 2 : 1;
    p.hiz_block_log2 = std::countr_zero(unsigned(st.hiz_block));
    p.hiz_blocks = int(hiz_blocks);
    const int64_t blocks = int64_t((st.fb_width + st.hiz_block - 1) / st.hiz_block) *
                           ((st.fb_height + st.hiz_block - 1) / st.hiz_block);
    p.hiz_spill_blocks = int(blocks - hiz_blocks);
    p.hiz_entry_bytes_log2 = std::countr_zero(unsigned(hiz_entry_bytes(st.hiz_mode, st.hiz_block, st.depth_bits)));
    p.hiz_lagged = st.hiz_sync == HizSync::Lagged ? 1 : 0;
  }
}

// pipeline.mode = binned's tile buffer and its port.
static void set_tile_buffer_params(const RasterState& st, const TimingParams& t, RtlParams& p) {
  // The tile buffer (rtl/rast_tile_buffer.sv) is built in binned mode only: a sample is
  // 4 colour bytes + the reference's depth bytes (ref/binning.h bin_depth_sample_bytes).
  const bool binned = st.bin.mode == PipelineMode::Binned;
  const uint64_t sample_bytes = 4 + uint64_t(depth_bytes_per_sample(st.depth_bits));
  p.tile_buffer_samples = binned ? static_cast<int>(st.bin.tile_buffer_bytes / sample_bytes) : 0;
  p.tile_port_bytes = binned ? static_cast<int>(t.rop_resolve_bytes_per_cycle) : 4;
  p.tile_port_words = binned ? p.tile_port_bytes / depth_bytes_per_sample(st.depth_bits) : 1;
  // Binned: rast_tri_setup sees only the render pass's triangles, which the timed model's
  // binner hands to coarse raster set up already (one a cycle through fifos.bin_fifo, the
  // setup FIFO's depth; setup's interval and latency are paid in the binning pass, which
  // the testbench times: docs/rtl.md "Tile buffer"), so it is built with one cycle of each.
  if (binned) p.setup_interval = p.setup_latency = 1;
}

RtlParams rtl_params(const ArchParams& arch) {
  const RasterState& st = arch.raster;
  RtlParams p;
  p.coord_int = st.coord_format.int_bits;
  p.coord_frac = st.coord_format.frac_bits;
  // docs/fixed-point.md, "Datapath widths": written once, in ref/fixed_point.cpp.
  const DatapathWidths w = datapath_widths(st.coord_format, st.depth_bits);
  p.coord_w = w.coord;
  p.coef_w = w.coef;
  p.edge_w = w.edge;
  p.area_w = w.area;
  // Vertex colours unsigned 8.F (interp.color_frac_bits): F bits wider than 8-bit c_k.
  p.color_frac = st.color_frac_bits;
  p.color_num_w = w.color_num + p.color_frac;
  p.depth_num_w = w.depth_num;
  p.depth_w = st.depth_bits;
  p.tile_log2_max = std::countr_zero(static_cast<unsigned>(st.tile_size));
  // Port widths from the schema's maxima, so every config's RTL has the same ports.
  const auto schema_max = [](const char* key) { return static_cast<unsigned>(find_param(key)->max); };
  p.pixel_w = std::bit_width(std::max(schema_max("display.width"), schema_max("display.height")) - 1);
  p.tile_log2_w = std::bit_width(static_cast<unsigned>(std::countr_zero(schema_max("raster.tile_size"))));
  // Multisampling: the sample count and the snapped offsets are run-time inputs (the
  // testbench drives ref/sample_pattern.h's table) up to the build-time maximum
  // raster.max_samples (validated: a power of two, 2 .. the schema's largest
  // raster.samples, >= raster.samples); |offset| <= 2^(F-1) raw. The port width stays the
  // schema's, so every config's RTL has the same samples_log2_i port.
  p.max_samples = arch.rtl_max_samples;
  p.sample_log2_w = std::bit_width(static_cast<unsigned>(std::countr_zero(schema_max("raster.samples"))));
  p.sample_off_w = st.coord_format.frac_bits + 1;
  // The timing keys, read and checked once (timing_params.cpp), as the SystemC model reads them.
  const TimingParams& t = arch.timing;
  p.setup_interval = static_cast<int>(t.setup_interval);
  p.setup_latency = static_cast<int>(t.setup_latency);
  p.coarse_tiles_per_cycle = static_cast<int>(t.coarse_tiles_per_cycle);
  p.fine_samples_per_cycle = static_cast<int>(t.fine_samples_per_cycle);
  p.fine_accepted_tile_cycles = static_cast<int>(t.fine_accepted_tile_cycles);
  p.interp_fragments_per_cycle = static_cast<int>(t.interp_fragments_per_cycle);
  p.interp_latency = static_cast<int>(t.interp_latency);
  p.tex_w = st.texcoord_format.total_bits();
  p.interp_perspective = t.interp_perspective ? 1 : 0;
  p.interp_persp_lanes = static_cast<int>(t.interp_lanes(false));
  p.recip_seed_bits = st.recip_seed_bits;
  p.recip_iterations = st.recip_iterations;
  p.interp_recip_latency = static_cast<int>(t.interp_recip_latency());
  const TextureRtlParams tex = texture_rtl_params(arch);
  p.tex_frac = tex.tex_frac;
  p.tex_weight_bits = tex.weight_bits;
  p.tex_size_w = tex.size_w;
  p.tex_addr_w = tex.addr_w;
  p.tex_cache_bytes = tex.cache_bytes;
  p.tex_ways = tex.ways;
  p.tex_line_bytes = tex.line_bytes;
  p.tex_ports = tex.ports;
  p.tex_beat_bytes = tex.beat_bytes;
  p.tex_level_w = tex.level_w;
  p.tex_bias_w = tex.bias_w;
  p.fifo_triangle = t.fifo_triangle;
  p.setup_fifo_entries = t.setup_fifo_entries();
  p.fifo_tile = t.fifo_tile;
  p.fifo_pixel = t.fifo_pixel;
  p.fragment_fifo_entries = t.fragment_fifo_entries();
  p.rop_pixels_per_cycle = static_cast<int>(t.rop_pixels_per_cycle);
  p.rop_clear_pixels_per_cycle = static_cast<int>(t.rop_clear_pixels_per_cycle);
  p.rop_len_w = std::bit_width(static_cast<unsigned>(p.rop_clear_pixels_per_cycle * p.max_samples));  // clog2(n + 1)
  set_hiz_params(st, p);
  p.depth_early = st.depth_early ? 1 : 0;
  set_tile_buffer_params(st, t, p);
  return p;
}

void rtl_params_without_hiz(RtlParams& p) {
  p.hiz_mode = 0;
  p.hiz_block_log2 = 3;  // any: nothing is built
  p.hiz_blocks = 1;
  p.hiz_spill_blocks = 0;
  p.hiz_entry_bytes_log2 = 3;
  p.hiz_lagged = 0;
}

std::string rtl_params_verilog(const RtlParams& p, const std::string& source) {
  std::ostringstream os;
  os << "// Generated by `rastsim export-rtl` from " << source << ". Do not edit.\n"
     << "// The body of rast_top's parameter port list (rtl/rast_top.sv); widths follow\n"
     << "// docs/fixed-point.md and are computed in model/rtlsim/rtl_params.cpp.\n";
  write_parameters(os, p, kFields);
  return os.str();
}

std::string rtl_params_values(const RtlParams& p) {
  std::string s = "{";
  for (const auto& f : kFields) s += (s.size() > 1 ? ", " : "") + std::to_string(p.*f.member);
  return s + "}";
}

std::vector<std::pair<std::string, int>> rtl_params_named(const RtlParams& p) {
  std::vector<std::pair<std::string, int>> out;
  for (const auto& f : kFields) out.emplace_back(f.name, p.*f.member);
  return out;
}

RtlParams rtl_params_from_values(const std::vector<int>& values) {
  if (values.size() != std::size(kFields))
    throw std::invalid_argument("RTL parameter list has " + std::to_string(values.size()) + " values, expected " +
                                std::to_string(std::size(kFields)));
  RtlParams p;
  size_t k = 0;
  for (const auto& f : kFields) p.*f.member = values[k++];
  return p;
}

bool rtl_params_compatible(const RtlParams& built, const RtlParams& wanted, std::string* why) {
  for (const auto& f : kFields) {
    const int b = built.*f.member, w = wanted.*f.member;
    const bool run_time_max = f.member == &RtlParams::tile_log2_max || f.member == &RtlParams::max_samples;
    const bool ok = run_time_max ? (w <= b && w >= 1) : (w == b);
    if (!ok) {
      if (why)
        *why = std::string(f.name) + " (" + f.comment + ") is " + std::to_string(w) + ", the RTL was built with " +
               (run_time_max ? "a maximum of " : "") + std::to_string(b);
      return false;
    }
  }
  return true;
}

}  // namespace rastsim
