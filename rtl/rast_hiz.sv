// SPDX-License-Identifier: Apache-2.0
// rast_hiz: hierarchical Z's per-block bound table (ref: model/ref/hiz.h HizTable;
// docs/depth-culling.md "The table: encoding and update rule").
//
// - Blocks of 2^BlockLog2 px squares (depth.hiz_block), row-major over the framebuffer
//   (nx = ceil(W / B) a row, the last column and row clipped to it): block i = by nx + bx.
//   Entries 0 .. Blocks - 1 are held here (the on-chip part of the table: depth.hiz_bytes /
//   entry bytes of them, rtl_params.cpp); a framebuffer with more blocks raises
//   overflow_o (the spilled entries' port is not built yet: docs/rtl.md "Hi-Z").
// - An entry: zmax (>= every stored depth), zmin (<= every stored depth; MinMax only),
//   the layer's lmax and lmin (D bits each) and its B^2-bit mask of pixels written since
//   the layer started, with their count.
// - Query (combinational, Queries ports): the bounds of the blocks a footprint overlaps, the nearest
//   zmin and the farthest zmax (at most MaxSpan^2 blocks: a tile of 2^TileLog2Max px is
//   aligned to the block grid, so it covers max(1, 2^TileLog2Max / B) blocks a side).
// - Update, per depth write of z at (x, y), lane order within a cycle (lane j sees lanes
//   0 .. j-1's writes to its block): zmax = max(zmax, z), zmin = min(zmin, z), lmax =
//   max(lmax, z), lmin = min(lmin, z); a pixel new to the mask sets its bit, and when the
//   count reaches the block's on-screen pixels, zmax = min(zmax, lmax), zmin = max(zmin,
//   lmin) and the layer restarts empty (completions_o counts those a cycle).
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

  // Entry index by nx + bx (IdxW bits: exact while the framebuffer fits, !overflow_o).
  /* verilator lint_off UNUSEDSIGNAL */  // the high bits matter only past the table (overflow_o)
  function automatic logic [IdxW-1:0] index_of(logic [BlkW-1:0] bx, logic [BlkW-1:0] by, logic [BlkW-1:0] n);
    index_of = IdxW'(by) * IdxW'(n) + IdxW'(bx);
  endfunction
  /* verilator lint_on UNUSEDSIGNAL */

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
      /* verilator lint_off UNUSEDSIGNAL */  // the layer fields: the update's
      logic [EntryW-1:0] e;
      /* verilator lint_on UNUSEDSIGNAL */
      qmin = '1;
      qmax = '0;
      for (int j = 0; j < MaxSpan; j++)
        for (int i = 0; i < MaxSpan; i++) begin
          e = table_q[index_of(qbx0 + BlkW'(i), qby0 + BlkW'(j), nx)];
          if (qbx0 + BlkW'(i) <= qbx1 && qby0 + BlkW'(j) <= qby1) begin
            if (e[OZmin +: DepthW] < qmin) qmin = e[OZmin +: DepthW];
            if (e[OZmax +: DepthW] > qmax) qmax = e[OZmax +: DepthW];
          end
        end
      if (MinMax == 0) qmin = '0;
    end
    assign q_min_o[n*DepthW +: DepthW] = qmin;
    assign q_max_o[n*DepthW +: DepthW] = qmax;
  end

  // ---- Update: each lane's block, pixel bit and the block's on-screen pixels ----
  logic [IdxW-1:0]        w_idx [Lanes];
  logic [2*BlockLog2-1:0] w_bit [Lanes];
  logic [CntW-1:0]        w_full [Lanes];
  for (genvar j = 0; j < Lanes; j++) begin : g_lane
    logic [PixelW-1:0] x, y;
    logic [BlkW-1:0]   bx, by;
    logic [PixelW:0]   rx, ry, wx, wy;  // pixels from the block's left (top) edge to the framebuffer's; clipped to B
    assign x = wr_x_i[j*PixelW +: PixelW];
    assign y = wr_y_i[j*PixelW +: PixelW];
    assign bx = BlkW'(x >> BlockLog2);
    assign by = BlkW'(y >> BlockLog2);
    assign w_idx[j] = index_of(bx, by, nx);
    assign rx = {1'b0, fb_width_i} - ((PixelW + 1)'(bx) << BlockLog2);
    assign ry = {1'b0, fb_height_i} - ((PixelW + 1)'(by) << BlockLog2);
    assign wx = rx > (PixelW + 1)'(B) ? (PixelW + 1)'(B) : rx;
    assign wy = ry > (PixelW + 1)'(B) ? (PixelW + 1)'(B) : ry;
    assign w_full[j] = CntW'(wx * wy);
    assign w_bit[j] = {y[BlockLog2-1:0], x[BlockLog2-1:0]};
  end
  // Lane j's entry after lanes 0 .. j-1, in lane order (lane k's slice of w_new is read
  // only for k < j, already written: Verilator's order check sees the vector whole).
  /* verilator lint_off ALWCOMBORDER */
  logic [Lanes*EntryW-1:0] w_new;  // lane j's entry at [j*EntryW +: EntryW]
  logic [Lanes-1:0] w_done;  // lane j completed its block's layer
  always_comb begin
    logic [EntryW-1:0] e;
    logic [DepthW-1:0] z, zmin, zmax, lmin, lmax;
    logic [MaskW-1:0]  mask;
    logic [CntW-1:0]   count;
    w_new = '0;
    for (int j = 0; j < Lanes; j++) begin
      z = wr_z_i[j*DepthW +: DepthW];
      e = table_q[w_idx[j]];
      for (int k = 0; k < j; k++)
        if (wr_valid_i[k] && w_idx[k] == w_idx[j]) e = w_new[k*EntryW +: EntryW];
      {zmin, zmax, lmin, lmax, mask, count} = e;
      if (z > zmax) zmax = z;
      if (z < zmin) zmin = z;
      if (z > lmax) lmax = z;
      if (z < lmin) lmin = z;
      w_done[j] = 1'b0;
      if (!mask[w_bit[j]]) begin
        mask[w_bit[j]] = 1'b1;
        count = count + 1'b1;
        if (count == w_full[j]) begin  // every pixel written during the layer
          if (lmax < zmax) zmax = lmax;
          if (lmin > zmin) zmin = lmin;
          mask = '0;
          count = '0;
          lmin = '1;
          lmax = '0;
          w_done[j] = wr_valid_i[j];
        end
      end
      w_new[j*EntryW +: EntryW] = {zmin, zmax, lmin, lmax, mask, count};
    end
  end
  /* verilator lint_on ALWCOMBORDER */
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
          if (wr_valid_i[j] && w_idx[j] == IdxW'(i)) table_q[i] <= w_new[j*EntryW +: EntryW];
      end
    end
  end
endmodule

`default_nettype wire
