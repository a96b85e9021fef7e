// SPDX-License-Identifier: Apache-2.0
// rast_top_hiz: hierarchical Z inside rast_top (docs/depth-culling.md "RTL", docs/rtl.md
// "Hi-Z"): the on-chip bound table (rast_hiz), the tile test of each coarse-raster walk
// lane (rast_hiz_test) and the interlock (rast_hiz_inflight).
//
// - Lane j's footprint of the triangle at coarse raster's head is tested against the
//   bounds of the blocks it overlaps: lane_cull_o, lane_accept_o. lane_wait_o: a tile
//   sent and not yet finished by the ROP (or a marker: a depth clear reaches the table at
//   the ROP) touches those blocks, so the table may still change under the test; coarse
//   raster then holds that lane (rast_coarse_raster). So every test sees exactly the
//   writes of every earlier tile, as HizTracker's zero-lag table (model/ref/hiz.h).
// - The table applies only where the reference's would (hiz_applies): one sample and a
//   depth function the mode tests (less, lequal; minmax also greater, gequal). Otherwise
//   every answer is low and nothing waits: the run is the Hi-Z-off one.
// - The ROP's depth writes (wr_*, one sample: its group's lanes decided this cycle) update
//   the table, a depth clear's marker (rop_clear_i) sets it; rop_always_o: the oldest tile
//   the ROP has not finished was accepted (tested with `always`, no depth read);
//   rop_always_next_o: the one after it was.
// - The table is the on-chip part only: Blocks must cover the framebuffer (the spilled
//   entries have no port: `rastsim cosim` refuses depth.hiz_bytes below the display's).
`default_nettype none

module rast_top_hiz #(
  parameter int CoordW        = 24,   // N + 1
  parameter int CoordFrac     = 16,   // F
  parameter int CoefW         = 25,   // N + 2
  parameter int EdgeW         = 49,   // 2N + 3
  parameter int AreaW         = 48,   // 2N + 2
  parameter int DepthW        = 24,   // D = raster.depth_bits
  parameter int PixelW        = 14,   // pixel index bits
  parameter int BlockLog2     = 3,    // log2 depth.hiz_block
  parameter int MinMax        = 0,    // depth.hiz = minmax
  parameter int Blocks        = 512,  // entries on chip
  parameter int TileLog2Max   = 4,    // largest tile, log2 px
  parameter int WriteLanes    = 1,    // depth writes a cycle (rop.pixels_per_cycle)
  parameter int Lanes         = 1,    // walk lanes (coarse.tiles_per_cycle)
  parameter int SampleLog2W   = 3,    // samples_log2_i bits
  parameter int InflightDepth = 64    // interlock entries (a power of two)
) (
  input  wire logic                          clk_i,          // core clock
  input  wire logic                          rst_ni,         // asynchronous reset, active low
  input  wire logic [PixelW-1:0]             fb_width_i,     // framebuffer width, px (static)
  input  wire logic [PixelW-1:0]             fb_height_i,    // framebuffer height, px (static)
  input  wire logic [2:0]                    depth_func_i,   // raster.depth_func (static)
  input  wire logic [SampleLog2W-1:0]        samples_log2_i, // log2 raster.samples (static)
  // The triangle at coarse raster's head (the setup bundle).
  input  wire logic [3*CoefW-1:0]            tri_a_i,
  input  wire logic [3*CoefW-1:0]            tri_b_i,
  input  wire logic [3*EdgeW-1:0]            tri_c_i,
  input  wire logic [AreaW-1:0]              tri_area2_i,
  input  wire logic [3*DepthW-1:0]           tri_z_i,
  input  wire logic [2*PixelW-1:0]           tri_origin_i,
  // Coarse raster's walk lanes.
  input  wire logic [Lanes*4*PixelW-1:0]     lane_fp_i,      // lane j's footprint
  output      logic [Lanes-1:0]              lane_wait_o,    // its blocks have a tile in flight
  output      logic [Lanes-1:0]              lane_cull_o,    // culled
  output      logic [Lanes-1:0]              lane_accept_o,  // accepted (minmax)
  // Coarse raster's sends (tiles and markers) and the interlock's ends.
  input  wire logic                          push_i,
  input  wire logic                          push_marker_i,
  input  wire logic [4*PixelW-1:0]           push_fp_i,
  input  wire logic                          push_accept_i,
  output      logic                          room_o,
  input  wire logic                          fine_valid_i,   // fine raster finishes a tile or marker
  input  wire logic                          fine_drop_i,    // ... with no output
  // The ROP's hooks (rast_rop's hiz_*).
  input  wire logic                          rop_end_i,      // a batch ends
  input  wire logic                          rop_marker_i,   // a marker is taken (after that batch, same cycle)
  output      logic                          rop_always_o,
  output      logic                          rop_always_next_o,
  input  wire logic                          rop_clear_i,
  input  wire logic [DepthW-1:0]             rop_clear_z_i,
  input  wire logic [WriteLanes-1:0]         wr_lanes_i,
  input  wire logic [WriteLanes*PixelW-1:0]  wr_x_i,
  input  wire logic [WriteLanes*PixelW-1:0]  wr_y_i,
  input  wire logic [WriteLanes*DepthW-1:0]  wr_z_i
);
  // The state Hi-Z applies to (ref hiz_applies; traversal and interpolation are the
  // RTL's only ones): one sample, a function the mode tests.
  logic on, handled;
  assign handled = depth_func_i == 3'd1 || depth_func_i == 3'd2 ||
                   (MinMax != 0 && (depth_func_i == 3'd4 || depth_func_i == 3'd5));
  assign on = samples_log2_i == '0 && handled;

  logic [Lanes*DepthW-1:0] q_min, q_max;
  /* verilator lint_off UNUSEDSIGNAL */
  logic overflow;  // Blocks covers the framebuffer (the config's; cosim refuses less)
  logic [$clog2(WriteLanes+1)-1:0] completions;  // counted by the reference, not compared
  /* verilator lint_on UNUSEDSIGNAL */
  rast_hiz #(
    .DepthW(DepthW), .PixelW(PixelW), .BlockLog2(BlockLog2), .MinMax(MinMax), .Blocks(Blocks),
    .TileLog2Max(TileLog2Max), .Lanes(WriteLanes), .Queries(Lanes)
  ) u_table (
    .clk_i, .rst_ni, .fb_width_i, .fb_height_i, .overflow_o(overflow), .clear_i(rop_clear_i),
    .clear_z_i(rop_clear_z_i), .q_fp_i(lane_fp_i), .q_min_o(q_min), .q_max_o(q_max),
    .wr_valid_i(on ? wr_lanes_i : '0), .wr_x_i, .wr_y_i, .wr_z_i, .completions_o(completions));

  for (genvar j = 0; j < Lanes; j++) begin : g_lane
    logic handled_j, cull, accept;
    rast_hiz_test #(
      .CoordW(CoordW), .CoordFrac(CoordFrac), .CoefW(CoefW), .EdgeW(EdgeW), .AreaW(AreaW), .DepthW(DepthW),
      .PixelW(PixelW)
    ) u_test (
      .minmax_i(MinMax != 0), .depth_func_i, .a_i(tri_a_i), .b_i(tri_b_i), .c_i(tri_c_i), .area2_i(tri_area2_i),
      .z_i(tri_z_i), .origin_i(tri_origin_i), .fp_i(lane_fp_i[j*4*PixelW +: 4*PixelW]),
      .bound_min_i(q_min[j*DepthW +: DepthW]), .bound_max_i(q_max[j*DepthW +: DepthW]), .handled_o(handled_j),
      .cull_o(cull), .accept_o(accept));
    assign lane_cull_o[j] = on && handled_j && cull;
    assign lane_accept_o[j] = on && handled_j && accept;
  end

  logic [Lanes-1:0] wait_q;
  /* verilator lint_off UNUSEDSIGNAL */
  logic empty;
  /* verilator lint_on UNUSEDSIGNAL */
  rast_hiz_inflight #(.PixelW(PixelW), .BlockLog2(BlockLog2), .Depth(InflightDepth), .Queries(Lanes)) u_inflight (
    .clk_i, .rst_ni, .push_i(on && push_i), .push_all_i(push_marker_i), .push_fp_i, .push_accept_i, .room_o,
    .fine_valid_i(on && fine_valid_i), .fine_drop_i, .rop_end_i(on && rop_end_i), .rop_marker_i(on && rop_marker_i), .rop_accept_o(rop_always_o),
    .rop_accept_next_o(rop_always_next_o),
    .q_fp_i(lane_fp_i), .wait_o(wait_q), .empty_o(empty));
  assign lane_wait_o = on ? wait_q : '0;
endmodule

`default_nettype wire
