// SPDX-License-Identifier: Apache-2.0
// rast_fine_raster: per-sample coverage of partial tiles, whole masks for accepted
// tiles (ref: model/ref/fine_raster.h fine_raster_partial / fine_raster_accepted; model:
// model/sc/fine_raster.cpp).
//
// - Multisampling: S = 2^samples_log2_i samples a pixel (1 .. MaxSamples), sample s at
//   the pixel centre plus (sample_dx_i[s], sample_dy_i[s]) (raw, snapped by the
//   testbench from the config: ref/sample_pattern.h). With S = 1 the offset is 0 and
//   every test is the pixel-centre test of before.
// - Partial tile: a stream of A x S coverage tests (pixels row-major, each pixel's
//   samples in order), SamplesPerCycle tests a cycle, each against the three edges with
//   its bias (E + a dx_s + b dy_s - bias >= 0): a footprint of A pixels takes
//   ceil(A S / SamplesPerCycle) cycles (TimingParams::fine_partial_cycles).
// - Accepted tile: the footprint's mask without tests, every sample covered, in
//   AcceptedTileCycles cycles.
// - Out: per tile, a pixel mask (bit (ly << tile_log2) | lx, pixel (lx, ly) of the tile,
//   row-major: some sample covered) and a sample mask (bits [p MaxSamples +: S] of
//   pixel bit p: its samples), with the tile's corner pixel; pushed in the tile's last
//   cycle, and only when some pixel is covered. A marker costs one cycle.
// - Quads (in_quads_i: the triangle is textured; docs/texture.md "Level of detail"): the
//   pixel mask is closed over 2x2 quads (pixels 2x..2x+1, 2y..2y+1; a tile's side is even):
//   every pixel of a quad with a covered pixel is out, the ones not covered as helper
//   pixels (their sample mask is 0), shaded for the derivatives and never written. The
//   tests, their cycles and the sample mask are the same.
// - The input is popped in the tile's last cycle: the head is the tile being rastered.
`default_nettype none

module rast_fine_raster #(
  parameter int CoordW             = 24,  // N + 1
  parameter int CoordFrac          = 16,  // F
  parameter int CoefW              = 25,  // N + 2
  parameter int EdgeW              = 49,  // 2N + 3
  parameter int PixelW             = 14,  // pixel index bits
  parameter int TileLog2Max        = 4,   // largest tile: 2^TileLog2Max pixels square
  parameter int TileLog2W          = 3,   // tile_log2_i bits
  parameter int SamplesPerCycle    = 8,   // coverage tests per cycle
  parameter int AcceptedTileCycles = 1,   // cycles to emit an accepted tile
  parameter int MaxSamples         = 16,  // largest sample count (a power of two >= 2)
  parameter int SampleLog2W        = 3,   // samples_log2_i bits
  parameter int SampleOffW         = 17,  // sample offset bits, signed raw (F + 1)
  localparam int TileMax = 1 << TileLog2Max,  // derived: largest tile side
  localparam int MaskW   = TileMax * TileMax,  // derived: coverage mask bits
  localparam int SMaskW  = MaskW * MaxSamples  // derived: sample mask bits
) (
  input  wire logic                 clk_i,          // core clock
  input  wire logic                 rst_ni,         // asynchronous reset, active low
  input  wire logic [TileLog2W-1:0] tile_log2_i,    // log2 tile size (static)
  input  wire logic [SampleLog2W-1:0] samples_log2_i,          // log2 samples a pixel (static)
  input  wire logic [MaxSamples*SampleOffW-1:0] sample_dx_i,   // sample s x offset at [s*SampleOffW +: SampleOffW] (static)
  input  wire logic [MaxSamples*SampleOffW-1:0] sample_dy_i,   // sample s y offset (static)
  input  wire logic                 in_valid_i,     // tile or marker at the head
  output      logic                 in_ready_o,     // pop the head (tile's last cycle)
  input  wire logic                 in_marker_i,    // head is a marker
  input  wire logic                 in_accepted_i,  // 1 accepted, 0 partial
  input  wire logic [4*PixelW-1:0]  in_fp_i,        // footprint {y1, x1, y0, x0}
  input  wire logic [3*CoefW-1:0]   in_a_i,         // edge a
  input  wire logic [3*CoefW-1:0]   in_b_i,         // edge b
  input  wire logic [3*EdgeW-1:0]   in_c_i,         // edge c
  input  wire logic [2:0]           in_bias_i,      // 1 = bias -1
  input  wire logic [2*PixelW-1:0]  in_origin_i,    // pixel of raw (0, 0): {y, x}
  input  wire logic                 in_quads_i,     // close the mask over 2x2 quads (textured)
  output      logic                 out_valid_o,    // mask or marker out
  input  wire logic                 out_ready_i,    // pixel FIFO takes it
  output      logic                 out_marker_o,   // a marker
  output      logic [MaskW-1:0]     out_mask_o,     // pixels of the tile with a covered sample
  output      logic [SMaskW-1:0]    out_smask_o,    // pixel p's samples at [p*MaxSamples +: MaxSamples]
  output      logic [2*PixelW-1:0]  out_tile_o,     // the tile's corner pixel {y, x}
  output      logic                 busy_o          // a tile is in progress
);
  localparam int Lanes = SamplesPerCycle;                 // derived
  localparam int CntW  = $clog2(AcceptedTileCycles + 1);  // derived: countdown bits
  localparam int SIdxW = (MaxSamples > 1) ? $clog2(MaxSamples) : 1;  // derived: sample index bits
  localparam int IdxW  = 2 * TileLog2Max;                 // derived: pixel index bits

  if (MaxSamples < 2 || (MaxSamples & (MaxSamples - 1)) != 0) begin : g_check_samples
    $error("rast_fine_raster: MaxSamples (%0d) must be a power of two >= 2", MaxSamples);
  end

  logic [SIdxW-1:0]  s_last;  // S - 1
  logic [MaxSamples-1:0] s_full;  // S ones
  assign s_last = SIdxW'((32'd1 << samples_log2_i) - 1);
  assign s_full = {MaxSamples{1'b1}} >> (MaxSamples - (1 << samples_log2_i));

  logic [PixelW-1:0] fx0, fy0, fx1, fy1, tile_x, tile_y;
  assign fx0 = in_fp_i[0 +: PixelW];
  assign fy0 = in_fp_i[PixelW +: PixelW];
  assign fx1 = in_fp_i[2*PixelW +: PixelW];
  assign fy1 = in_fp_i[3*PixelW +: PixelW];
  assign tile_x = (fx0 >> tile_log2_i) << tile_log2_i;
  assign tile_y = (fy0 >> tile_log2_i) << tile_log2_i;
  assign out_tile_o = {tile_y, tile_x};

  logic              active_q;
  logic [PixelW-1:0] cx_q, cy_q;  // next pixel to test
  logic [SIdxW-1:0]  cs_q;        // its next sample
  logic [CntW-1:0]   cnt_q;       // accepted tile: cycles left
  logic [MaskW-1:0]  mask_q;      // partial tile: covered so far
  logic [SMaskW-1:0] smask_q;     // partial tile: covered samples so far

  // ---- Sample lanes: the next SamplesPerCycle (pixel, sample) tests of the footprint ----
  logic [PixelW-1:0] lane_x [Lanes+1], lane_y [Lanes+1];
  logic [SIdxW-1:0]  lane_s [Lanes+1];
  logic [Lanes-1:0]  lane_cov;
  logic [IdxW-1:0]   lane_pix [Lanes];  // the lane's pixel in the tile, row-major
  always_comb begin
    lane_x[0] = active_q ? cx_q : fx0;
    lane_y[0] = active_q ? cy_q : fy0;
    lane_s[0] = active_q ? cs_q : '0;
    for (int j = 0; j < Lanes; j++) begin
      if (lane_s[j] != s_last) begin
        lane_s[j+1] = lane_s[j] + 1'b1;
        lane_x[j+1] = lane_x[j];
        lane_y[j+1] = lane_y[j];
      end else if (lane_x[j] + 1'b1 == fx1) begin
        lane_s[j+1] = '0;
        lane_x[j+1] = fx0;
        lane_y[j+1] = lane_y[j] + 1'b1;
      end else begin
        lane_s[j+1] = '0;
        lane_x[j+1] = lane_x[j] + 1'b1;
        lane_y[j+1] = lane_y[j];
      end
    end
  end

  for (genvar j = 0; j < Lanes; j++) begin : g_lane
    logic [CoordW-1:0] cx, cy, sx, sy;
    logic [SampleOffW-1:0] dx, dy;
    logic [2:0]        pass;
    rast_sample #(.PixelW(PixelW), .CoordW(CoordW), .CoordFrac(CoordFrac)) u_sx (
      .p_i(lane_x[j]), .origin_i(in_origin_i[0 +: PixelW]), .s_o(cx));
    rast_sample #(.PixelW(PixelW), .CoordW(CoordW), .CoordFrac(CoordFrac)) u_sy (
      .p_i(lane_y[j]), .origin_i(in_origin_i[PixelW +: PixelW]), .s_o(cy));
    // The sample position: centre + offset (|offset| <= 2^(F-1), inside the format).
    assign dx = sample_dx_i[lane_s[j]*SampleOffW +: SampleOffW];
    assign dy = sample_dy_i[lane_s[j]*SampleOffW +: SampleOffW];
    assign sx = cx + {{(CoordW - SampleOffW){dx[SampleOffW-1]}}, dx};
    assign sy = cy + {{(CoordW - SampleOffW){dy[SampleOffW-1]}}, dy};
    for (genvar i = 0; i < 3; i++) begin : g_edge
      logic signed [EdgeW-1:0] e, e_b;
      rast_edge_eval #(.CoordW(CoordW), .CoefW(CoefW), .EdgeW(EdgeW)) u_eval (
        .a_i(in_a_i[i*CoefW +: CoefW]), .b_i(in_b_i[i*CoefW +: CoefW]),
        .c_i(in_c_i[i*EdgeW +: EdgeW]), .x_i(sx), .y_i(sy), .e_o(e));
      assign e_b     = e - EdgeW'(in_bias_i[i]);
      assign pass[i] = !e_b[EdgeW-1];  // E + bias >= 0
    end
    assign lane_cov[j] = (lane_y[j] < fy1) && (pass == 3'b111);
    assign lane_pix[j] = IdxW'(((lane_y[j] - tile_y) << tile_log2_i) | (lane_x[j] - tile_x));
  end

  // ---- Masks: tested lanes of a partial tile, or the whole footprint ----
  logic [MaskW-1:0]  lane_mask, fp_mask;
  logic [TileMax-1:0] fp_cols;
  logic [SMaskW-1:0] lane_smask, fp_smask;
  always_comb begin
    lane_mask  = '0;
    lane_smask = '0;
    for (int j = 0; j < Lanes; j++)
      if (lane_cov[j]) begin
        lane_mask[lane_pix[j]] = 1'b1;
        lane_smask[{lane_pix[j], lane_s[j]}] = 1'b1;
      end
    // The footprint's mask: its columns (fp_cols, bit lx) on each of its rows ly, row ly
    // at bit ly << tile_log2_i. Only an accepted tile reads it (zero otherwise: a
    // verilated model skips the MaskW- and SMaskW-bit work on partial tiles).
    fp_cols = '0;
    fp_mask = '0;
    fp_smask = '0;
    if (in_accepted_i) begin
      for (int lx = 0; lx < TileMax; lx++)
        fp_cols[lx] = tile_x + PixelW'(lx) >= fx0 && tile_x + PixelW'(lx) < fx1 && (lx >> tile_log2_i) == 0;
      for (int ly = 0; ly < TileMax; ly++)
        if (tile_y + PixelW'(ly) >= fy0 && tile_y + PixelW'(ly) < fy1 && (ly >> tile_log2_i) == 0)
          fp_mask = fp_mask | (MaskW'(fp_cols) << (ly << tile_log2_i));
      for (int q = 0; q < MaskW; q++) fp_smask[q*MaxSamples +: MaxSamples] = fp_mask[q] ? s_full : '0;
    end
  end

  // ---- Control ----
  logic [CntW-1:0] left;
  logic            last, done;
  assign left = active_q ? cnt_q : CntW'(AcceptedTileCycles);
  always_comb begin
    if (in_marker_i)        last = 1'b1;
    else if (in_accepted_i) last = (left == CntW'(1));
    else                    last = (lane_y[Lanes] >= fy1);
  end
  assign out_marker_o = in_marker_i;
  logic [MaskW-1:0] cov_mask, quad_x, quad_xy;  // covered pixels; closed over x pairs, then y pairs
  assign cov_mask = in_accepted_i ? fp_mask : (mask_q | lane_mask);
  always_comb begin
    // Pixel p = (ly << tile_log2) | lx: its x partner is p ^ 1, its y partner p ^ (1 << tile_log2).
    for (int p = 0; p < MaskW; p++) quad_x[p] = cov_mask[p] | cov_mask[p ^ 1];
    for (int p = 0; p < MaskW; p++) quad_xy[p] = quad_x[p] | quad_x[IdxW'(p) ^ (IdxW'(1) << tile_log2_i)];
  end
  assign out_mask_o   = in_quads_i ? quad_xy : cov_mask;
  assign out_smask_o  = in_accepted_i ? fp_smask : (smask_q | lane_smask);
  assign out_valid_o  = in_valid_i && last && (in_marker_i || cov_mask != '0);
  assign done         = in_valid_i && last && (!out_valid_o || out_ready_i);
  assign in_ready_o   = done;
  assign busy_o       = active_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      active_q <= 1'b0;
      cx_q     <= '0;
      cy_q     <= '0;
      cs_q     <= '0;
      cnt_q    <= '0;
      mask_q   <= '0;
      smask_q  <= '0;
    end else if (done) begin
      active_q <= 1'b0;
      mask_q   <= '0;
      smask_q  <= '0;
    end else if (in_valid_i && !last) begin
      active_q <= 1'b1;
      cx_q     <= lane_x[Lanes];
      cy_q     <= lane_y[Lanes];
      cs_q     <= lane_s[Lanes];
      cnt_q    <= left - 1'b1;
      mask_q   <= cov_mask;
      smask_q  <= out_smask_o;
    end
  end
endmodule

`default_nettype wire
