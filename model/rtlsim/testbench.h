// SPDX-License-Identifier: Apache-2.0
// The co-simulation testbench around the verilated RTL, with no Verilator type in it:
// the stimulus and expectation of one run (TbSetup, filled by cosim_setup.cpp), the
// RTL's ports as the testbench sees them (RastPorts, implemented per verilated config by
// the port adapter in cosim_driver.h), and the testbench itself (run_testbench,
// testbench.cpp): the command front end, the ROP's command feed and the memory behind
// its port (the framebuffer; with memory.model = "dram" timed by tb_rop_memory.h), the stage meters and the checks. Internal to model/rtlsim; callers use cosim.h.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <unordered_map>
#include <string>
#include <vector>
#include <utility>

#include "config/timing_params.h"
#include "display/scanout_fetch.h"
#include "ref/2d/draw2d.h"
#include "ref/framebuffer.h"
#include "ref/interpolate.h"
#include "ref/memory/memory_params.h"
#include "ref/raster_state.h"
#include "ref/sample_pattern.h"
#include "ref/scene.h"
#include "ref/texture/texture.h"
#include "rtlsim/cosim.h"
#include "rtlsim/port_values.h"
#include "rtlsim/tb_binning.h"
#include "timing/dram.h"

namespace rastsim::rtlsim {

// One transaction of the testbench's command stream.
struct TbItem {
  // ClipCommand: a clip-space command, fetched whole into the geometry front end (its
  // job: front_end_steps) with a marker down the command FIFO; its triangles follow it
  // in `items`, out of the front end (from_front_end: fetch skips them).
  enum Kind { Triangle, Marker, Null, ClipCommand } kind = Triangle;
  uint64_t fetch_cost = 1;     // command fetch cycles (header + vertices)
  uint64_t assembly_cost = 1;  // primitive assembly cycles (1 for a marker)
  uint64_t rop_cost = 1;       // markers: ROP cycles (the end-of-frame marker's: the resolve pass)
  int64_t x[3] = {}, y[3] = {};  // snapped raw coordinates
  uint32_t z[3] = {};
  uint64_t rgb[3] = {};        // {b, g, r} packed as the RTL port: 8 + interp.color_frac_bits bits a channel
  int32_t s[3] = {}, t[3] = {};  // texture coordinates, raw interp.texcoord_format
  uint32_t q[3] = {1, 1, 1};   // perspective weights Q_k (24 bits)
  bool affine = true;          // interpolation needs no reciprocal (ref tri_setup)
  // The texture state (rast_top's tri_tex_*; ref/texture/texture.h's enum values).
  bool tex_on = false, tex_bilinear = false, tex_trilinear = false;  // bilinear: on each level read
  int tex_wrap_s = 0, tex_wrap_t = 0, tex_env = 0;
  int tex_width = 0, tex_height = 0;  // level 0, texels
  uint64_t tex_base = 0;              // level 0's byte address (TextureUnit's placement)
  int tex_levels = 1;                 // levels sampled: the chain's with mipmap on, else 1
  int32_t tex_bias = 0;               // texlod_bias, s.8
  int clip[4] = {};            // x0, y0, x1, y1
  int origin[2] = {};          // x, y
  int tri = -1;                // triangle index (names in TbSetup::tri_names)
  const Command* cmd = nullptr;  // markers: the state or 2D command (none: the end-of-frame marker)
  int work2d = -1;             // 2D markers: index in TbSetup::work2d
  bool from_front_end = false; // a clip-space command's triangle: the front end hands it to assembly
  size_t first_step = 0, steps = 0;  // ClipCommand: its steps in TbSetup::front_end_steps
  int64_t command = -1;        // the scene command it comes from (-1: the end-of-frame marker)
  bool fed = false;            // binned: a render-pass item the binner feeds (fetch skips it)
  int bin_marker = -1;         // binned: its bin command (TbSetup::binning.markers)
};
// One step of the geometry front end on a clip-space command (sc/front_end.cpp): busy
// `cycles` (TimingParams::front_end_step_cycles), then a screen-FIFO entry: triangle
// `item` (an index in TbSetup::items), or the command's end (-1).
struct TbFrontEndStep {
  uint64_t cycles = 0;
  int64_t item = -1;
};
// A 2D command's engine operations (ref/draw2d.h) and its front-end cost.
struct TbWork2d {
  Draw2dWork work;
  uint64_t setup_cost = 1;     // 2D front end cycles (TimingParams::setup2d_cycles)
  std::string name;            // "file:line"
};

// The textures in memory as the reference places them (TextureUnit::resident), each texel
// stored by encode_texel: 4 KiB pages, a byte no texel holds reads 0.
struct TextureMemory {
  static constexpr int kPageBits = 12;
  std::unordered_map<uint64_t, std::array<uint8_t, size_t{1} << kPageBits>> pages;
  uint8_t byte(uint64_t a) const {
    const auto it = pages.find(a >> kPageBits);
    return it == pages.end() ? 0 : it->second[size_t(a & ((uint64_t{1} << kPageBits) - 1))];
  }
  void set(uint64_t a, uint8_t v) { pages[a >> kPageBits][size_t(a & ((uint64_t{1} << kPageBits) - 1))] = v; }
};

struct Expected {
  Fragment f;
  int tri = 0;
  bool culled = false;  // depth.early: the reference culls it early (render_scene's kept stream lacks it)
  // depth.hiz_sync = lagged: >= 0, the index of the reference's Hi-Z culled tile it belongs
  // to (its fragments consecutive). The RTL's lagged table may draw that tile (all of its
  // fragments, each failing its depth test at the ROP) or cull it; -1: always expected.
  int64_t hiz_tile = -1;
};
// A depth write the reference's ROP makes (HizTracker's, in order): pixel and value.
struct TbDepthWrite {
  int x = 0, y = 0;
  uint32_t z = 0;
};

struct TbSetup {
  RtlParams params;                     // of the verilated model (widths, timing)
  // Run-time raster state of the config being simulated, driven on rast_top's static
  // inputs: log2 tile size, fill rule, cull mode (raster_state.h's enum values), front face.
  int tile_log2 = 0;
  int fill_rule = 0, cull_mode = 0, front_ccw = 1;
  // Multisampling: raster.samples and its snapped offsets (ref/sample_pattern.h), raw,
  // driven on samples_log2_i / sample_dx_i / sample_dy_i.
  int samples = 1;
  std::array<int64_t, kMaxSamples> sample_dx{}, sample_dy{};
  std::vector<TbItem> items;
  std::vector<Expected> expected;
  std::vector<std::string> tri_names;   // "file:line triangle k"
  std::vector<size_t> tri_command;      // each triangle's scene command (index)
  size_t commands = 0;                  // the scene's commands (CosimResult::command_starts)
  std::vector<TbWork2d> work2d;         // the 2D commands, in order
  std::vector<TbFrontEndStep> front_end_steps;  // the clip-space commands' steps, in order
  RasterState arch;                     // the config's state: framebuffer size, depth function and write (the ROP's static inputs)
  Framebuffer reference;                // the reference model's image of the scene
  TimingParams timing;                  // of the config being simulated: FIFO depths, ROP cost
  // memory.model = "dram" (memory.enabled): the timed memory system behind the ROP's port
  // (tb_rop_memory.h) with these caches, layout and DRAM; "fixed": the framebuffer alone.
  MemoryParams memory;
  DramParams dram;
  // The display's line fetch on that memory system, as in simulate: the config's display
  // (scanout_params_if_display; none when it does not resolve).
  std::optional<ScanoutParams> scanout;
  CosimOptions opts;
  // Textured scenes: the texture unit's parameters (format, layout, cache), the placed
  // textures' bytes (the texture cache's line fills read them), the reference's texture
  // cache fills (line byte addresses, in fetch order) and its helper pixels.
  TextureParams texture;
  TextureMemory texture_memory;
  std::vector<uint64_t> texture_fills;
  uint64_t helper_pixels = 0;
  // Hi-Z (hiz_applies): the reference's tiles culled and accepted (the expected fragments
  // leave the culled out) and its spilled entries' accesses by kind, in order (tb_hiz.h).
  bool hiz = false;
  uint64_t tiles_culled_hiz = 0, tiles_accepted_hiz = 0;
  std::vector<uint64_t> hiz_test_reads, hiz_flush_reads, hiz_writes;
  uint64_t hiz_entry_bytes = 0, hiz_base = 0, hiz_bytes_read = 0, hiz_bytes_written = 0;
  // Every depth write of the reference's ROP in order (with Hi-Z: each pixel's writes are
  // checked against the RTL ROP's, so a culled tile's fragment it draws must write none).
  // depth.hiz_sync = lagged: the expected stream holds the culled tiles' fragments too
  // (Expected::hiz_tile), hiz_culled_empty of those tiles having none.
  bool hiz_lagged = false;
  std::vector<TbDepthWrite> depth_writes;
  uint64_t hiz_culled_empty = 0;
  // depth.early (rtl/rast_early_z.sv): the reference's fragments_culled_early (the expected
  // stream holds every fragment, each flagged as the reference decides).
  bool depth_early = false;
  uint64_t fragments_culled_early = 0;
  // pipeline.mode = binned (tb_binning.h): the binner's program and bin commands.
  bool binned = false;
  TbBinning binning;
};

// The ROP's surfaces in the testbench's memory: 32-bit words, sample s of pixel (x, y) at
// base + ((y W + x) S + s) 4 (docs/rtl.md "ROP"); colour from 0, depth after it.
inline uint32_t rop_depth_base(int width, int height, int samples) {
  return uint32_t(uint64_t(width) * uint64_t(height) * uint64_t(samples) * 4);
}

// The verilated rast_top and rast_engine2d of one config, clocked together. Every call
// reads or drives ports of the models as they are now (outputs after the last eval).
class RastPorts {
 public:
  virtual ~RastPorts() = default;
  // Static inputs (raster state, multisampling, the 2D engine's timing), valids low,
  // reset asserted.
  virtual void drive_static(const TbSetup& s) = 0;
  virtual void release_reset() = 0;
  virtual void clock_edge(bool high) = 0;  // clk_i of both models, evaluated, waveform dumped
  virtual void finish() = 0;               // waveform closed, models finalised

  // rast_top's triangle port: `it` offered (tri_valid_i high), or nothing (nullptr).
  virtual void drive_triangle(const TbItem* it) = 0;
  virtual bool triangle_ready() const = 0;  // tri_ready_o
  virtual bool fragment_taken() const = 0;  // frag_ready_o: the fragment FIFO takes the beat
  virtual FragmentBeat fragment_beat() const = 0;
  virtual bool fragment_lane_valid(int lane) const = 0;  // frag_lanes_o bit
  virtual bool fragment_lane_culled(int lane) const = 0;  // frag_culled_o bit (early Z)
  // The early test's depth read (ez_rd_*): the lanes read (ez_rd_lanes_o) and lane j's
  // pixel (ez_rd_x_o, ez_rd_y_o: the interpolator's beat into the texture stage); their
  // samples' stored depth (lane j sample s at words[j MaxSamples + s]) driven on
  // ez_rd_depth_i and rast_top evaluated again.
  virtual uint32_t early_read_lanes() const = 0;
  virtual std::pair<int, int> early_read_pixel(int lane) const = 0;
  virtual void drive_early_depth(const std::vector<uint32_t>& words) = 0;
  // Lane `lane` of the fragment port (x, y, z, colour, sample mask; samples left 1).
  virtual Fragment fragment_lane(int lane) const = 0;
  virtual bool idle() const = 0;  // idle_o
  // The texture cache's line fill port: the fill offered (tex_mem_req_valid_o: its line's
  // byte address, else nullopt), tex_mem_req_ready_i, a beat offered (tex_mem_rsp_valid_i,
  // its TexBeatBytes bytes), tex_mem_rsp_ready_o; the cache's hits and miss this cycle;
  // tex_helpers_o.
  virtual std::optional<uint64_t> texture_fill_request() const = 0;
  virtual void drive_texture_fill_ready(bool ready) = 0;
  virtual void drive_texture_beat(bool valid, const std::array<uint8_t, 16>& bytes) = 0;
  virtual bool texture_beat_taken() const = 0;
  virtual TexCacheEvents texture_cache_events() const = 0;
  virtual int helper_pixels() const = 0;
  virtual RtlStageBits stage_bits() const = 0;
  // Hi-Z's spilled entries: the request (taken whenever offered); hiz_base_i and a response.
  virtual HizRequest hiz_request() const = 0;
  virtual void drive_hiz(uint64_t base, bool valid, const std::array<uint8_t, 64>& data) = 0;

  // The ROP's command port: cmd_ready_o (a marker waits for its command, the ROP is
  // quiet), and the command offered (cmd_valid_i, cmd_op_i, cmd_value_i; cmd_bin_i: a bin
  // command's rectangle x0, y0, x1, y1).
  virtual bool rop_command_wanted() const = 0;
  virtual void drive_rop_command(bool valid, int op, uint32_t value, const int* bin = nullptr) = 0;
  // Binned mode: the tile buffer's beat, and tl_ready_i, tl_rvalid_i with its words.
  virtual TileBeat tile_beat() const = 0;
  virtual void drive_tile(bool ready, bool rvalid, const std::vector<uint32_t>& words) = 0;
  // The ROP's memory port. Reads: rd_valid_o, lane k's rd_lanes_o bit and request.
  virtual bool rop_read_valid() const = 0;
  virtual bool rop_read_lane_valid(int k) const = 0;
  // rd_no_depth_o: the group's tile was Hi-Z accepted (tested with `always`): its accesses
  // read no depth (the response still comes, its words unused).
  virtual bool rop_read_no_depth() const = 0;
  virtual RopLane rop_read_lane(int k) const = 0;
  // rd_ready_i and wr_ready_i.
  virtual void drive_rop_memory_ready(bool read, bool write) = 0;
  // rd_rvalid_i, and rd_rdata_i: lane k word i at words[k MaxSamples + i].
  virtual void drive_rop_response(bool valid, const std::vector<uint32_t>& words) = 0;
  // Writes: wr_valid_o, wr_fill_o, lane k's bit, request, data word and word i's byte enables.
  virtual bool rop_write_valid() const = 0;
  virtual bool rop_write_fill() const = 0;
  virtual bool rop_write_lane_valid(int k) const = 0;
  virtual RopLane rop_write_lane(int k) const = 0;
  virtual uint32_t rop_write_data(int k) const = 0;
  virtual uint32_t rop_write_enables(int k, int word) const = 0;

  // The 2D engine's operation port: `op` of `work` offered (in_valid_i high with the
  // command's paint state and clip box), or nothing (nullptr).
  virtual void drive_operation(const Draw2dWork* work, const Op2d* op) = 0;
  virtual bool operation_ready() const = 0;  // in_ready_o
  // The engine's memory port: the addresses, the read request; rd_ready_i and the
  // response (rd_rvalid_i, each lane's D {b, g, r} in `d`, S in `s`), which evaluates the
  // engine again; the write request, wr_ready_i (evaluates again) and the write's data.
  virtual Engine2dAccess engine_access() const = 0;
  virtual Engine2dRead engine_read() const = 0;
  virtual void drive_engine_read(bool ready, bool rvalid, const std::vector<uint32_t>& d, uint32_t s) = 0;
  virtual Engine2dWrite engine_write() const = 0;
  virtual void drive_engine_write_ready(bool ready) = 0;
  virtual uint32_t engine_write_rgb(int lane) const = 0;  // wr_data_o lane {b, g, r}
};

// One co-simulation run of `setup` on `ports` (cosim.h's comment): every fragment
// compared, cycles, stage statistics and the framebuffer's CRC into `result`.
void run_testbench(const TbSetup& setup, RastPorts& ports, CosimResult& result);

using RunFn = void (*)(const TbSetup&, CosimResult&);
struct RegistryEntry {
  const char* name;    // the config's name, or <config>_circuit (the divider as its circuit)
  const char* config;  // configs/<config>.toml
  RunFn run;
  RtlParams params;  // what Vrast_<name> was built with
};
const std::vector<RegistryEntry>& rtl_registry();  // generated: rtl_registry.cpp

}  // namespace rastsim::rtlsim
