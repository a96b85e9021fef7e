// SPDX-License-Identifier: Apache-2.0
// Timing keys of the SystemC cycle-approximate model (model/sc), declared once here.
//
// Every number the timed model uses comes from this table: clock, per-stage throughput,
// initiation interval and latency, and the depth of every FIFO between stages. Units are
// in the key names. The defaults describe a mid-range design (one triangle every two
// cycles, 8 coverage samples and 4 fragments a cycle); configs/embedded.toml and
// configs/desktop.toml are the small and large ends. docs/microarchitecture.md gives the
// timing equation each key enters.
#include "config/config_schema.h"

namespace rastsim {

namespace {

using T = ParamType;

// Appends one key to the schema.
struct AddKey {
  std::vector<ParamDef>& schema;
  void operator()(ParamDef d) const { schema.push_back(std::move(d)); }
};

// The clock and the stages ahead of the rasterizer: command fetch, primitive assembly,
// triangle setup.
void add_front_end_keys(const AddKey& add) {
  // ---- clock ----
  add({"clock.core_mhz", T::Float, 500.0, "MHz", 1, 10000, {},
       "Core clock of the raster pipeline; converts cycles to seconds in the stats (1 simulated ns = 1 cycle)"});
  // ---- command fetch ----
  add({"fetch.cycles_per_command", T::Int, int64_t{1}, "cycles", 1, 1024, {},
       "Cycles to decode one command header (state command, or the start of a primitive command)"});
  add({"fetch.vertices_per_cycle", T::Int, int64_t{3}, "vertices/cycle", 1, 64, {},
       "Vertex fetch bandwidth; a triangle's new vertices (3 for lists, 1 for strips/fans) take ceil(n / this)"});
  // ---- primitive assembly ----
  add({"assembly.cycles_per_triangle", T::Int, int64_t{1}, "cycles", 1, 1024, {},
       "Cycles primitive assembly spends forming one triangle from its vertices"});
  // ---- triangle setup ----
  add({"setup.interval_cycles", T::Int, int64_t{2}, "cycles", 1, 4096, {},
       "Initiation interval of triangle setup: cycles between two triangles entering it"});
  add({"setup.latency_cycles", T::Int, int64_t{12}, "cycles", 1, 4096, {},
       "Latency of triangle setup: cycles from a triangle entering to its edge equations leaving (>= interval)"});
}

// The coarse and fine rasterizer (tile walk, coverage tests, scanline spans).
void add_raster_keys(const AddKey& add) {
  // ---- coarse raster ----
  add({"coarse.tiles_per_cycle", T::Int, int64_t{1}, "tiles/cycle", 1, 64, {},
       "Tiles the coarse walker classifies (early-out / early-in) per cycle, at every level of "
       "raster.traversal = hierarchical too"});
  add({"coarse.scanline_setup_cycles", T::Int, int64_t{4}, "cycles", 1, 1024, {},
       "raster.traversal = scanline: cycles of the edge walker's per-triangle setup (sort by y, three dx/dy "
       "divisions, the first x-intersections); then one row a cycle"});
  // ---- fine raster ----
  add({"fine.samples_per_cycle", T::Int, int64_t{8}, "samples/cycle", 1, 4096, {},
       "Coverage tests per cycle on a partial tile; a footprint of A pixels takes ceil(A / this)"});
  add({"fine.accepted_tile_cycles", T::Int, int64_t{1}, "cycles", 1, 1024, {},
       "Cycles to emit a trivially accepted tile (whole-footprint mask, no tests)"});
  add({"fine.span_setup_cycles", T::Int, int64_t{1}, "cycles", 0, 1024, {},
       "raster.traversal = scanline: cycles the span filler spends on each span before its pixels"});
  add({"fine.span_pixels_per_cycle", T::Int, int64_t{8}, "pixels/cycle", 1, 4096, {},
       "raster.traversal = scanline: pixels of one span the span filler emits per cycle"});
}

// The stages after the rasterizer: attribute interpolation and the ROP.
void add_back_end_keys(const AddKey& add) {
  // ---- attribute interpolation ----
  add({"interp.fragments_per_cycle", T::Int, int64_t{4}, "fragments/cycle", 1, 1024, {},
       "Fragments whose colour and depth are interpolated per cycle"});
  add({"interp.latency_cycles", T::Int, int64_t{6}, "cycles", 0, 4096, {},
       "Extra pipeline latency of the interpolator (divider) after a batch's last fragment enters"});
  // ---- ROP ----
  add({"rop.pixels_per_cycle", T::Int, int64_t{4}, "pixels/cycle", 1, 1024, {},
       "Fragments depth-tested and written per cycle"});
  add({"rop.clear_pixels_per_cycle", T::Int, int64_t{64}, "pixels/cycle", 1, 1 << 20, {},
       "Pixels a colour or depth clear writes per cycle (fast-clear bandwidth)"});
  add({"rop.resolve_bytes_per_cycle", T::Int, int64_t{64}, "bytes/cycle", 1, 1 << 20, {},
       "Bandwidth of the frame-end multisample resolve pass (raster.samples > 1): it reads W x H x samples x 4 "
       "bytes and writes W x H x 4"});
}

// The 2D path (docs/2d.md, "Timing"): command fetch -> 2D front end -> 2D engine, the
// engine writing the framebuffer through the ROP's port while the ROP holds for it; its
// two FIFOs' depths (in transactions) too.
void add_2d_path_keys(const AddKey& add) {
  add({"setup2d.ops_per_cycle", T::Int, int64_t{1}, "operations/cycle", 1, 64, {},
       "Engine operations (spans, pixels, lines, blits) the 2D front end turns out per cycle; a command of N "
       "operations takes max(1, ceil(N / this))"});
  add({"engine2d.fill_pixels_per_cycle", T::Int, int64_t{4}, "pixels/cycle", 1, 8, {},
       "Pixels of one span the 2D engine writes per beat (its framebuffer port width)"});
  add({"engine2d.span_setup_cycles", T::Int, int64_t{1}, "cycles", 0, 64, {},
       "Cycles the 2D engine spends setting up each span and each blit row"});
  add({"engine2d.rmw_cycles", T::Int, int64_t{2}, "cycles", 2, 16, {},
       "Cycles of one beat (or one line pixel) when the ROP3 code reads the destination D: read, wait, write; "
       "a beat that does not read D takes 1"});
  add({"engine2d.blit_bytes_per_cycle", T::Int, int64_t{8}, "bytes/cycle", 1, 8, {},
       "Framebuffer bandwidth of a blit: a pixel moves 4 bytes written plus 4 read for each of S and D the "
       "ROP3 code reads; a row of w pixels takes ceil(w * bytes / this). At most one pixel a cycle"});
  add({"fifo.draw2d_depth", T::Int, int64_t{4}, "entries", 1, 65536, {},
       "Command fetch -> 2D front end FIFO (one entry: a 2D command)"});
  add({"fifo.op2d_depth", T::Int, int64_t{2}, "entries", 1, 65536, {},
       "2D front end -> 2D engine FIFO (one entry: one command's engine operations)"});
}

// The depths of the 3D pipeline's FIFOs between stages (in transactions).
void add_fifo_keys(const AddKey& add) {
  add({"fifo.command_depth", T::Int, int64_t{8}, "entries", 1, 65536, {},
       "Command fetch -> primitive assembly FIFO (one entry: a state command or one triangle's vertices)"});
  add({"fifo.triangle_depth", T::Int, int64_t{4}, "entries", 1, 65536, {},
       "Primitive assembly -> triangle setup FIFO (one entry: a triangle or a state command)"});
  add({"fifo.setup_depth", T::Int, int64_t{4}, "entries", 1, 65536, {},
       "Triangle setup -> coarse raster FIFO (one entry: a set-up triangle or a state command)"});
  add({"fifo.tile_depth", T::Int, int64_t{8}, "entries", 1, 65536, {},
       "Coarse raster -> fine raster FIFO (one entry: an accepted or partial tile)"});
  add({"fifo.pixel_depth", T::Int, int64_t{4}, "entries", 1, 65536, {},
       "Fine raster -> interpolation FIFO (one entry: one tile's covered pixels)"});
  add({"fifo.fragment_depth", T::Int, int64_t{4}, "entries", 1, 65536, {},
       "Interpolation -> ROP FIFO (one entry: one tile's shaded fragments)"});
  add({"fifo.texture_depth", T::Int, int64_t{4}, "entries", 1, 65536, {},
       "Interpolation -> texture stage FIFO (one entry: one tile's textured fragments; plus interpolation's "
       "pipeline slots, as the fragment FIFO)"});
}

}  // namespace

void add_timing_params(std::vector<ParamDef>& s) {
  const AddKey add{s};
  add_front_end_keys(add);
  add_raster_keys(add);
  add_back_end_keys(add);
  add_2d_path_keys(add);
  add_fifo_keys(add);
}

}  // namespace rastsim
