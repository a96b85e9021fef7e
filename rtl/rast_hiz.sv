// SPDX-License-Identifier: Apache-2.0
// rast_hiz: hierarchical Z's per-block bound table (ref: model/ref/hiz.h HizTable;
// docs/depth-culling.md "The table: encoding and update rule").
//
// - Blocks of 2^BlockLog2 px squares (depth.hiz_block), row-major over the framebuffer
//   (nx = ceil(W / B) a row, the last column and row clipped to it): block i = by nx + bx.
//   Entries 0 .. Blocks - 1 are held here (the on-chip part of the table: depth.hiz_bytes /
//   entry bytes of them, rtl_params.cpp); a framebuffer with more blocks raises
//   overflow_o, and the blocks past Blocks (spilled, rast_hiz_spill) are neither queried
//   nor written here.
// - An entry: zmax (>= every stored depth), zmin (<= every stored depth; MinMax only),
//   the layer's lmax and lmin (D bits each) and its B^2-bit mask of pixels written since
//   the layer started, with their count.
// - Query (combinational, Queries ports): the bounds of the blocks a footprint overlaps, the nearest
//   zmin and the farthest zmax (at most MaxSpan^2 blocks: a tile of 2^TileLog2Max px is
//   aligned to the block grid, so it covers max(1, 2^TileLog2Max / B) blocks a side).
// - Update, per depth write of z at (x, y) to an on-chip block, lane order within a cycle
//   (lane j sees lanes 0 .. j-1's writes to its block): the rule of rast_hiz_update
//   (completions_o counts the layers completed a cycle).
// - A depth clear to c (clear_i): every entry zmin = zmax = c, the layer empty; it takes
//   precedence over a write in the same cycle (the ROP orders them).
`default_nettype none

module rast_hiz #(
  parameter int DepthW      = 24,   // D = raster.depth_bits
  parameter int PixelW      = 14,   // pixel index bits
  parameter int BlockLog2   = 3,    // log2 depth.hiz_block
  parameter int MinMax      = 0,    // depth.hiz = minmax (1) or max (0)
  parameter int Blocks      = 512,  // entries on chip
  parameter int TileLog2Max = 4,    // largest tile, log2 px
  parameter int Lanes       = 1,    // depth writes a cycle (rop.pixels_per_cycle)
  parameter int Queries     = 1     // query ports (rast_top: coarse.tiles_per_cycle, a walk lane each)
) (
  input  wire logic                     clk_i,        // core clock
  input  wire logic                     rst_ni,       // asynchronous reset, active low
  input  wire logic [PixelW-1:0]        fb_width_i,   // framebuffer width, px (static)
  input  wire logic [PixelW-1:0]        fb_height_i,  // framebuffer height, px (static)
  output      logic                     overflow_o,   // the framebuffer has more blocks than Blocks
  input  wire logic                     clear_i,      // depth clear this cycle
  input  wire logic [DepthW-1:0]        clear_z_i,    // its value
  input  wire logic [Queries*4*PixelW-1:0] q_fp_i,    // query n's footprint {y1, x1, y0, x0} at [n*4*PixelW +: 4*PixelW], not empty
  output      logic [Queries*DepthW-1:0]  q_min_o,    // query n's nearest zmin of its blocks (MinMax; else 0)
  output      logic [Queries*DepthW-1:0]  q_max_o,    // query n's farthest zmax
  input  wire logic [Lanes-1:0]         wr_valid_i,   // lane j writes depth this cycle
  input  wire logic [Lanes*PixelW-1:0]  wr_x_i,       // lane j pixel x
  input  wire logic [Lanes*PixelW-1:0]  wr_y_i,       // lane j pixel y
  input  wire logic [Lanes*DepthW-1:0]  wr_z_i,       // lane j depth
  output      logic [$clog2(Lanes+1)-1:0] completions_o  // layers completed this cycle (CompW bits)
);
  localparam int B       = 1 << BlockLog2;                       // derived: block edge, px
  localparam int MaskW   = B * B;                                // derived: layer mask bits
  localparam int CntW    = 2 * BlockLog2 + 1;                    // derived: 0 .. B^2
  localparam int IdxW    = Blocks > 1 ? $clog2(Blocks) : 1;      // derived: entry index
  localparam int MaxSpan = TileLog2Max > BlockLog2 ? 1 << (TileLog2Max - BlockLog2) : 1;  // derived
  localparam int BlkW    = PixelW - BlockLog2 + 1;               // derived: block coordinate
  localparam int CompW   = $clog2(Lanes + 1);                    // derived: completions_o bits

  // An entry, {zmin, zmax, lmin, lmax, mask, count} from the top bit down (flat vectors
  // and slices: Yosys 0.23 does not take members of a local struct variable).
  localparam int OCnt  = 0;                  // derived: field offsets
  localparam int OMask = OCnt + CntW;
  localparam int OLmax = OMask + MaskW;
  localparam int OLmin = OLmax + DepthW;
  localparam int OZmax = OLmin + DepthW;
  localparam int OZmin = OZmax + DepthW;
  localparam int EntryW = OZmin + DepthW;    // derived: entry bits
  logic [EntryW-1:0] table_q [Blocks];

  // Blocks a row and in all; one block's on-screen pixels.
  logic [BlkW-1:0]       nx, ny;
  logic [2*BlkW-1:0]     nblocks;
  assign nx = BlkW'((fb_width_i + PixelW'(B - 1)) >> BlockLog2);
  assign ny = BlkW'((fb_height_i + PixelW'(B - 1)) >> BlockLog2);
  assign nblocks = nx * ny;
  assign overflow_o = nblocks > (2 * BlkW)'(Blocks);

  // Block index by nx + bx (2 BlkW bits: every block of the framebuffer); an on-chip
  // entry's index is its low IdxW bits.
  function automatic logic [2*BlkW-1:0] index_of(logic [BlkW-1:0] bx, logic [BlkW-1:0] by, logic [BlkW-1:0] n);
    index_of = (2 * BlkW)'(by) * (2 * BlkW)'(n) + (2 * BlkW)'(bx);
  endfunction
  function automatic logic on_chip(logic [2*BlkW-1:0] i);
    on_chip = i < (2 * BlkW)'(Blocks);
  endfunction

  // ---- Query: the footprint's blocks (one port a walk lane) ----
  for (genvar n = 0; n < Queries; n++) begin : g_query
    logic [4*PixelW-1:0] fp;
    logic [BlkW-1:0] qbx0, qby0, qbx1, qby1;
    logic [DepthW-1:0] qmin, qmax;
    assign fp = q_fp_i[n*4*PixelW +: 4*PixelW];
    assign qbx0 = BlkW'(fp[0 +: PixelW] >> BlockLog2);
    assign qby0 = BlkW'(fp[PixelW +: PixelW] >> BlockLog2);
    assign qbx1 = BlkW'((fp[2*PixelW +: PixelW] - 1'b1) >> BlockLog2);
    assign qby1 = BlkW'((fp[3*PixelW +: PixelW] - 1'b1) >> BlockLog2);
    always_comb begin
      /* verilator lint_off UNUSEDSIGNAL */  // the layer fields: the update's; the index's high bits: on_chip's
      logic [EntryW-1:0] e;
      logic [2*BlkW-1:0] qi;
      /* verilator lint_on UNUSEDSIGNAL */
      qmin = '1;
      qmax = '0;
      for (int j = 0; j < MaxSpan; j++)
        for (int i = 0; i < MaxSpan; i++) begin
          qi = index_of(qbx0 + BlkW'(i), qby0 + BlkW'(j), nx);
          e = table_q[IdxW'(qi)];
          if (qbx0 + BlkW'(i) <= qbx1 && qby0 + BlkW'(j) <= qby1 && on_chip(qi)) begin
            if (e[OZmin +: DepthW] < qmin) qmin = e[OZmin +: DepthW];
            if (e[OZmax +: DepthW] > qmax) qmax = e[OZmax +: DepthW];
          end
        end
      if (MinMax == 0) qmin = '0;
    end
    assign q_min_o[n*DepthW +: DepthW] = qmin;
    assign q_max_o[n*DepthW +: DepthW] = qmax;
  end

  // ---- Update: each lane's on-chip entry after lanes 0 .. j-1 (rast_hiz_update) ----
  logic [IdxW-1:0]         w_idx [Lanes];
  logic [Lanes-1:0]        w_on;    // lane j writes an on-chip block
  logic [Lanes-1:0]        w_done;  // lane j completed its block's layer
  /* verilator lint_off UNOPTFLAT */
  logic [Lanes*EntryW-1:0] w_new;   // lane j's entry after its write at [j*EntryW +: EntryW]
  /* verilator lint_on UNOPTFLAT */
  for (genvar j = 0; j < Lanes; j++) begin : g_lane
    /* verilator lint_off UNUSEDSIGNAL */  // the index's high bits: on_chip's
    logic [2*BlkW-1:0] bi;
    /* verilator lint_on UNUSEDSIGNAL */
    logic [PixelW-1:0] x, y;
    logic              done;
    // The entry lane j updates: the table's, or the last earlier lane's on the same block
    // (lane k < j's slice of w_new: each lane reads only earlier lanes' outputs, so the
    // chain has no loop; Verilator sees the vectors whole).
    /* verilator lint_off UNOPTFLAT */
    logic [EntryW-1:0] e_in, e_out;
    /* verilator lint_on UNOPTFLAT */
    assign x = wr_x_i[j*PixelW +: PixelW];
    assign y = wr_y_i[j*PixelW +: PixelW];
    assign bi = index_of(BlkW'(x >> BlockLog2), BlkW'(y >> BlockLog2), nx);
    assign w_idx[j] = IdxW'(bi);
    assign w_on[j] = wr_valid_i[j] && on_chip(bi);
    always_comb begin
      e_in = table_q[w_idx[j]];
      for (int k = 0; k < j; k++)
        if (w_on[k] && w_idx[k] == w_idx[j]) e_in = w_new[k*EntryW +: EntryW];
    end
    rast_hiz_update #(.DepthW(DepthW), .PixelW(PixelW), .BlockLog2(BlockLog2)) u_update (
      .fb_width_i, .fb_height_i, .e_i(e_in), .x_i(x), .y_i(y), .z_i(wr_z_i[j*DepthW +: DepthW]),
      .e_o(e_out), .done_o(done));
    assign w_new[j*EntryW +: EntryW] = e_out;
    assign w_done[j] = w_on[j] && done;
  end
  always_comb begin
    completions_o = '0;
    for (int j = 0; j < Lanes; j++) completions_o = completions_o + CompW'(w_done[j]);
  end

  // ---- The entries: a register each, written by a clear or by the last lane writing it
  // (which saw the earlier ones). ----
  for (genvar i = 0; i < Blocks; i++) begin : g_entry
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        table_q[i] <= {{DepthW{1'b1}}, {DepthW{1'b1}}, {DepthW{1'b1}}, {DepthW{1'b0}}, {MaskW{1'b0}}, {CntW{1'b0}}};
      end else if (clear_i) begin
        table_q[i] <= {clear_z_i, clear_z_i, {DepthW{1'b1}}, {DepthW{1'b0}}, {MaskW{1'b0}}, {CntW{1'b0}}};  // {zmin, zmax, lmin, lmax, mask, count}
      end else begin
        for (int j = 0; j < Lanes; j++)
          if (w_on[j] && w_idx[j] == IdxW'(i)) table_q[i] <= w_new[j*EntryW +: EntryW];
      end
    end
  end
endmodule

`default_nettype wire
