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
// - Lagged (depth.hiz_sync = lagged, docs/depth-culling.md "Lagged"): no hold for blocks.
//   Lane j is tested against the table as the ROP has written it by this cycle (the same
//   table, updated as the ROP writes); its cull stands (a stale bound only culls less),
//   its accept only when no entry in flight touches its blocks (the interlock's wait,
//   asked without waiting: a stale zmin would accept over nearer depths); every lane
//   waits only while a marker is in flight (a depth clear moves bounds the unsafe way).
//   So the decisions are a subset of HizTracker's, as SystemC's hiz_lagged.
// - The table applies only where the reference's would (hiz_applies): one sample and a
//   depth function the mode tests (less, lequal; minmax also greater, gequal). Otherwise
//   every answer is low and nothing waits: the run is the Hi-Z-off one.
// - The ROP's depth writes (wr_*, one sample: its group's lanes decided this cycle) update
//   the table, a depth clear's marker (rop_clear_i) sets it; rop_always_o: the oldest tile
//   the ROP has not finished was accepted (tested with `always`, no depth read);
//   rop_always_next_o: the one after it was.
// - The table's first Blocks entries are on chip (rast_hiz); the rest (SpillBlocks > 0)
//   are in memory behind mem_* (rast_hiz_spill, client `hiz`). A lane whose footprint
//   has a spilled block waits until lane 0 holds it and its entries are read (its blocks
//   free in the interlock and the spill unit's earlier writes written back); its bounds
//   are then the on-chip blocks' and the spilled ones' together.
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
  parameter int InflightDepth = 64,   // interlock entries (a power of two)
  parameter int Lagged        = 0,    // depth.hiz_sync = lagged (no spilled entries: cosim refuses both)
  parameter int SpillBlocks   = 0,    // the display's blocks past Blocks (0: none, no spill unit)
  parameter int EntryBytesLog2 = 4,   // log2 of an entry's bytes (ref hiz_entry_bytes)
  parameter int AddrW         = 40    // byte address bits of the spilled entries
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
  input  wire logic [WriteLanes*DepthW-1:0]  wr_z_i,
  input  wire logic [Lanes-1:0]              lane_keep_i,    // lane j is a tile not rejected
  input  wire logic                          culled_i,       // coarse raster consumed culled lanes this cycle
  // The spilled entries' memory port (rast_hiz_spill; tied off when SpillBlocks = 0).
  input  wire logic [AddrW-1:0]              base_i,         // depth.hiz_base (static)
  output      logic                          mem_req_valid_o,
  input  wire logic                          mem_req_ready_i,
  output      logic                          mem_req_write_o,
  output      logic                          mem_req_flush_o,
  output      logic [AddrW-1:0]              mem_req_addr_o,
  output      logic [511:0]                  mem_req_data_o,
  input  wire logic                          mem_rsp_valid_i,
  input  wire logic [511:0]                  mem_rsp_data_i,
  output      logic                          error_o,        // the spill unit's FIFO overflowed
  output      logic                          busy_o          // the spill unit has writes to apply or write back
);
  // The state Hi-Z applies to (ref hiz_applies; traversal and interpolation are the
  // RTL's only ones): one sample, a function the mode tests.
  logic on, handled;
  assign handled = depth_func_i == 3'd1 || depth_func_i == 3'd2 ||
                   (MinMax != 0 && (depth_func_i == 3'd4 || depth_func_i == 3'd5));
  assign on = samples_log2_i == '0 && handled;

  logic [Lanes*DepthW-1:0] q_min, q_max, t_min, t_max;  // on-chip blocks' bounds; with the spilled ones'
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
      .bound_min_i(t_min[j*DepthW +: DepthW]), .bound_max_i(t_max[j*DepthW +: DepthW]), .handled_o(handled_j),
      .cull_o(cull), .accept_o(accept));
    assign lane_cull_o[j] = on && handled_j && cull;
    // Lagged: an accept against blocks a tile in flight still writes is not made.
    assign lane_accept_o[j] = on && handled_j && accept && !(Lagged != 0 && wait_q[j]);
  end

  logic [Lanes-1:0] wait_q;
  logic marker_q;  // a marker in flight (lagged: the walk's only hold)
  /* verilator lint_off UNUSEDSIGNAL */
  logic empty;
  /* verilator lint_on UNUSEDSIGNAL */
  rast_hiz_inflight #(.PixelW(PixelW), .BlockLog2(BlockLog2), .Depth(InflightDepth), .Queries(Lanes)) u_inflight (
    .clk_i, .rst_ni, .push_i(on && push_i), .push_all_i(push_marker_i), .push_fp_i, .push_accept_i, .room_o,
    .fine_valid_i(on && fine_valid_i), .fine_drop_i, .rop_end_i(on && rop_end_i), .rop_marker_i(on && rop_marker_i), .rop_accept_o(rop_always_o),
    .rop_accept_next_o(rop_always_next_o),
    .q_fp_i(lane_fp_i), .wait_o(wait_q), .marker_o(marker_q), .empty_o(empty));
  // ---- The spilled entries ----
  logic [Lanes-1:0] spill_wait;  // lane j waits for its spilled entries
  if (SpillBlocks > 0) begin : g_spill
    localparam int BlkW = PixelW - BlockLog2 + 1;  // derived: a block coordinate
    logic [BlkW-1:0] nx;
    logic [Lanes-1:0] spilled;  // lane j's footprint has a block past Blocks
    logic s_valid, s_busy;
    logic [DepthW-1:0] s_min, s_max;
    assign nx = BlkW'((fb_width_i + PixelW'((1 << BlockLog2) - 1)) >> BlockLog2);
    for (genvar j = 0; j < Lanes; j++) begin : g_lane
      logic [PixelW-1:0] x1, y1;  // the footprint's exclusive right and bottom edges
      logic [2*BlkW-1:0] last;    // its last block, the largest index
      assign {y1, x1} = lane_fp_i[j*4*PixelW + 2*PixelW +: 2*PixelW];
      assign last = (2 * BlkW)'(BlkW'((y1 - 1'b1) >> BlockLog2)) * (2 * BlkW)'(nx) +
                    (2 * BlkW)'(BlkW'((x1 - 1'b1) >> BlockLog2));
      assign spilled[j] = last >= (2 * BlkW)'(Blocks);
      assign spill_wait[j] = spilled[j] && !(j == 0 && s_valid);
      assign t_min[j*DepthW +: DepthW] = j == 0 && spilled[j] && MinMax != 0 && s_min < q_min[j*DepthW +: DepthW]
                                         ? s_min : q_min[j*DepthW +: DepthW];
      assign t_max[j*DepthW +: DepthW] = j == 0 && spilled[j] && s_max > q_max[j*DepthW +: DepthW]
                                         ? s_max : q_max[j*DepthW +: DepthW];
    end
    rast_hiz_spill #(
      .DepthW(DepthW), .PixelW(PixelW), .BlockLog2(BlockLog2), .MinMax(MinMax), .OnChip(Blocks),
      .SpillBlocks(SpillBlocks), .EntryBytesLog2(EntryBytesLog2), .TileLog2Max(TileLog2Max), .WriteLanes(WriteLanes),
      .AddrW(AddrW)
    ) u_spill (
      .clk_i, .rst_ni, .fb_width_i, .fb_height_i, .base_i, .q_fp_i(lane_fp_i[0 +: 4*PixelW]),
      .q_go_i(on && lane_keep_i[0] && spilled[0] && !wait_q[0] && !s_busy),
      .q_consume_i(s_valid && ((push_i && !push_marker_i) || culled_i)), .q_valid_o(s_valid), .q_min_o(s_min),
      .q_max_o(s_max), .busy_o(s_busy), .wr_lanes_i(on ? wr_lanes_i : '0), .wr_x_i, .wr_y_i, .wr_z_i,
      .end_i(on && rop_end_i), .clear_i(rop_clear_i), .clear_z_i(rop_clear_z_i), .mem_req_valid_o, .mem_req_ready_i,
      .mem_req_write_o, .mem_req_flush_o, .mem_req_addr_o, .mem_req_data_o, .mem_rsp_valid_i, .mem_rsp_data_i,
      .error_o);
    assign busy_o = s_busy;
  end else begin : g_no_spill
    assign busy_o = 1'b0;
    assign spill_wait = '0;
    assign t_min = q_min;
    assign t_max = q_max;
    assign {mem_req_valid_o, mem_req_write_o, mem_req_flush_o, mem_req_addr_o, mem_req_data_o, error_o} = '0;
    wire unused_spill = ^{lane_keep_i, culled_i, base_i, mem_req_ready_i, mem_rsp_valid_i, mem_rsp_data_i};
  end
  assign lane_wait_o = !on ? '0 : Lagged != 0 ? {Lanes{marker_q}} | spill_wait : wait_q | spill_wait;
endmodule

`default_nettype wire
