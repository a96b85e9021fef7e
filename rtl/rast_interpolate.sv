// SPDX-License-Identifier: Apache-2.0
// rast_interpolate: colour and depth of each covered pixel (ref: model/ref/interpolate.cpp;
// model: model/sc/interpolate.cpp).
//
// - Takes a tile's coverage mask and walks its set bits in order (row-major within
//   the tile), FragmentsPerCycle pixels a cycle: a mask of N pixels takes
//   ceil(N / FragmentsPerCycle) cycles, a marker one.
// - Per pixel: the barycentric weights are the edge values at the pixel centre,
//   w0 = E1, w1 = E2, w2 = E0 (signed EdgeW bits, sum area2); each attribute is
//   round_half_up((w0 a0 + w1 a1 + w2 a2) / area2), one rast_divider per attribute and
//   lane (quotient 8 bits colour, DepthW depth; numerators ColorNumW / DepthNumW).
// - Multisampling (msaa): a pixel with a covered sample but its centre outside the
//   triangle has a negative weight, and the rational may leave the attribute's range:
//   the result is clamped to [0, 2^bits - 1] as ref interpolate_plane_at does. The signed
//   numerator (NumW + 3 bits: |w| < 2^(EdgeW-1)) is tested before the divider: negative
//   -> 0; 2 num + area2 >= 2^(bits+1) area2 (the rounded quotient >= 2^bits) -> 2^bits - 1;
//   otherwise the divider gets it (then < 2^bits area2, as before). The flags ride the
//   side pipe. With one sample every weight is >= 0 and no flag is ever set.
// - Each fragment carries its pixel's sample mask (in_smask_i, MaxSamples bits a pixel).
// - Latency register stages (interp.latency_cycles) from a pixel's pick to its
//   fragment; the whole pipeline stalls while the output is not taken.
// - The input is popped in the cycle that picks its last pixels.
`default_nettype none

module rast_interpolate #(
  parameter int CoordW            = 24,  // N + 1
  parameter int CoordFrac         = 16,  // F
  parameter int CoefW             = 25,  // N + 2
  parameter int EdgeW             = 49,  // 2N + 3
  parameter int AreaW             = 48,  // 2N + 2
  parameter int ColorNumW         = 56,  // 2N + 10
  parameter int DepthNumW         = 72,  // 2N + 2 + D
  parameter int DepthW            = 24,  // D
  parameter int PixelW            = 14,  // pixel index bits
  parameter int TileLog2Max       = 4,   // largest tile: 2^TileLog2Max pixels square
  parameter int TileLog2W         = 3,   // tile_log2_i bits
  parameter int FragmentsPerCycle = 4,   // pixels interpolated per cycle
  parameter int Latency           = 6,   // pick-to-fragment register stages
  parameter int MaxSamples        = 16,  // sample mask bits a pixel (a power of two >= 2)
  localparam int MaskW = 1 << (2 * TileLog2Max),  // derived: coverage mask bits
  localparam int SMaskW = MaskW * MaxSamples,     // derived: sample mask bits
  localparam int Lanes = FragmentsPerCycle        // derived
) (
  input  wire logic                      clk_i,         // core clock
  input  wire logic                      rst_ni,        // asynchronous reset, active low
  input  wire logic [TileLog2W-1:0]      tile_log2_i,   // log2 tile size (static)
  input  wire logic                      in_valid_i,    // mask or marker at the head
  output      logic                      in_ready_o,    // pop the head
  input  wire logic                      in_marker_i,   // head is a marker
  input  wire logic [MaskW-1:0]          in_mask_i,     // covered pixels of the tile
  input  wire logic [SMaskW-1:0]         in_smask_i,    // pixel p's samples at [p*MaxSamples +: MaxSamples]
  input  wire logic [2*PixelW-1:0]       in_tile_i,     // tile corner pixel {y, x}
  input  wire logic [3*CoefW-1:0]        in_a_i,        // edge a
  input  wire logic [3*CoefW-1:0]        in_b_i,        // edge b
  input  wire logic [3*EdgeW-1:0]        in_c_i,        // edge c
  input  wire logic [2*PixelW-1:0]       in_origin_i,   // pixel of raw (0, 0): {y, x}
  input  wire logic [AreaW-1:0]          in_area2_i,    // doubled area, > 0
  input  wire logic [3*DepthW-1:0]       in_z_i,        // vertex k depth at [k*DepthW +: DepthW]
  input  wire logic [3*24-1:0]           in_rgb_i,      // vertex k colour {b, g, r} at [k*24 +: 24]
  output      logic                      out_valid_o,   // a beat of fragments or a marker
  input  wire logic                      out_ready_i,   // taken this cycle
  output      logic                      out_marker_o,  // the beat is a marker
  output      logic                      out_last_o,    // last beat of a tile's fragments
  output      logic [Lanes-1:0]          out_lanes_o,   // lane j holds a fragment
  output      logic [Lanes*PixelW-1:0]   out_x_o,       // lane j pixel x
  output      logic [Lanes*PixelW-1:0]   out_y_o,       // lane j pixel y
  output      logic [Lanes*DepthW-1:0]   out_z_o,       // lane j depth
  output      logic [Lanes*24-1:0]       out_rgb_o,     // lane j colour {b, g, r}
  output      logic [Lanes*MaxSamples-1:0] out_smask_o, // lane j sample mask
  output      logic                      busy_o         // a mask half done or a beat in the pipeline
);
  localparam int IdxW  = 2 * TileLog2Max;              // derived: mask index bits
  localparam int SIdxW = $clog2(MaxSamples);           // derived: sample index bits
  localparam int ClampW = 2 * 4;                       // derived: {lo, hi} flags of 4 dividers
  localparam int SideW = 3 + Lanes * (1 + 2 * PixelW + MaxSamples + ClampW);  // derived: side data bits
  localparam int CNumW = ColorNumW + 3;                // derived: signed colour numerator
  localparam int ZNumW = DepthNumW + 3;                // derived: signed depth numerator
  // The depth products e z as two half products, z = z_hi 2^ZLoW + z_lo: each sum of three
  // (|e| < 2^(EdgeW-1), a half below 2^ZHiW) fits ZPW signed bits, one machine word in the
  // verilated model on the shipped formats (57-63 bits), where a ZNumW-bit product is a
  // multi-word call. The same numerator: snum_z = sum_hi 2^ZLoW + sum_lo.
  localparam int ZLoW  = DepthW / 2;                   // derived: low half of z
  localparam int ZHiW  = DepthW - ZLoW;                // derived: high half of z
  localparam int ZPW   = EdgeW + ZHiW + 2;             // derived: a half products' sum, signed

  localparam int RowW  = 1 << TileLog2Max;             // derived: mask bits a row of the largest tile
  localparam int Rows  = MaskW / RowW;                 // derived: rows of the mask
  localparam int RowIW = TileLog2Max;                  // derived: row / bit-in-row index bits

  logic             en;
  logic [IdxW-1:0]  pos_q;  // mask bits below this were picked in earlier beats (0: none)
  // pos_q is {row, bit in row} (RowIW bits each), zero-extended to 32 bits for the scan's
  // compares with its int loop index (no int'() cast: Yosys 0.23 rejects it).
  logic [31:0] pos_row, pos_bit;
  assign pos_row = {{(32 - IdxW){1'b0}}, pos_q} >> RowIW;
  assign pos_bit = {{(32 - IdxW){1'b0}}, pos_q} & (RowW - 1);
  logic [IdxW-1:0]  idx [Lanes];
  logic [Lanes-1:0] pick;
  logic             last_beat;

  // ---- The next Lanes set bits of the mask at or after pos_q, lowest first ----
  // A row (RowW bits) at a time: a row without a set bit left costs one test, and the
  // scan stops looking once it has found Lanes + 1 bits (the +1 says whether this is the
  // last beat). In hardware the same function as a priority select over the whole mask;
  // in Verilator the per-cycle work follows the rows holding the beat's pixels, not the
  // mask width. (Was: rem = in_mask_i & ~consumed_q over all MaskW bits, a MaskW-bit
  // register of picked pixels, and a MaskW-iteration loop every cycle.)
  always_comb begin
    int k;
    logic [RowW-1:0] row;
    k = 0;
    pick = '0;
    for (int j = 0; j < Lanes; j++) idx[j] = '0;
    last_beat = 1'b1;
    for (int r = 0; r < Rows; r++) begin
      row = in_mask_i[r*RowW +: RowW];
      if (r < pos_row) row = '0;
      else if (r == pos_row) row = row & ({RowW{1'b1}} << pos_bit);
      if (k <= Lanes && row != '0) begin
        for (int b = 0; b < RowW; b++) begin
          if (row[b]) begin
            if (k < Lanes) begin
              idx[k]  = IdxW'(r * RowW + b);
              pick[k] = 1'b1;
            end else begin
              last_beat = 1'b0;
            end
            k = k + 1;
          end
        end
      end
    end
  end

  assign en         = !(out_valid_o && !out_ready_i);
  assign in_ready_o = en && in_valid_i && (in_marker_i || last_beat);

  // Not the last beat: all Lanes lanes picked, and the next beat starts after the last.
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) pos_q <= '0;
    else if (en && in_valid_i && !in_marker_i) pos_q <= last_beat ? '0 : idx[Lanes-1] + 1'b1;
  end

  // ---- Per lane: pixel, weights, numerators, dividers ----
  logic [Lanes*PixelW-1:0] lane_x, lane_y;
  logic [Lanes*MaxSamples-1:0] lane_smask;
  logic [Lanes*ClampW-1:0] lane_clamp, out_clamp;
  logic [Lanes*DepthW-1:0] div_z;
  logic [Lanes*24-1:0]     div_rgb;
  for (genvar j = 0; j < Lanes; j++) begin : g_lane
    logic [PixelW-1:0]     px, py;
    logic [CoordW-1:0]     sx, sy;
    logic signed [EdgeW-1:0] e [3];
    logic signed [CNumW-1:0] snum_c [3];
    logic signed [ZNumW-1:0] snum_z;
    logic signed [ZPW-1:0]   zsum_lo, zsum_hi;  // sum of e z_lo, of e z_hi
    logic [ColorNumW-1:0]  num_c [3];
    logic [DepthNumW-1:0]  num_z;
    logic [3:0]            lo, hi;  // per divider (r, g, b, z): clamp to 0 / to the maximum
    logic [IdxW-1:0]       mask_lx, lx, ly;
    logic                  live;   // the lane holds a picked pixel this cycle
    assign live = in_valid_i && !in_marker_i && pick[j];
    assign mask_lx = ~({IdxW{1'b1}} << tile_log2_i);
    assign lx = idx[j] & mask_lx;
    assign ly = idx[j] >> tile_log2_i;
    assign px = in_tile_i[0 +: PixelW] + {{(PixelW - IdxW){1'b0}}, lx};
    assign py = in_tile_i[PixelW +: PixelW] + {{(PixelW - IdxW){1'b0}}, ly};
    assign lane_x[j*PixelW +: PixelW] = px;
    assign lane_y[j*PixelW +: PixelW] = py;
    assign lane_smask[j*MaxSamples +: MaxSamples] = in_smask_i[{idx[j], SIdxW'(0)} +: MaxSamples];
    rast_sample #(.PixelW(PixelW), .CoordW(CoordW), .CoordFrac(CoordFrac)) u_sx (
      .p_i(px), .origin_i(in_origin_i[0 +: PixelW]), .s_o(sx));
    rast_sample #(.PixelW(PixelW), .CoordW(CoordW), .CoordFrac(CoordFrac)) u_sy (
      .p_i(py), .origin_i(in_origin_i[PixelW +: PixelW]), .s_o(sy));
    for (genvar i = 0; i < 3; i++) begin : g_edge
      rast_edge_eval #(.CoordW(CoordW), .CoefW(CoefW), .EdgeW(EdgeW)) u_eval (
        .a_i(in_a_i[i*CoefW +: CoefW]), .b_i(in_b_i[i*CoefW +: CoefW]),
        .c_i(in_c_i[i*EdgeW +: EdgeW]), .x_i(sx), .y_i(sy), .e_o(e[i]));
    end
    // Exact signed numerators: weight of vertex v is the edge opposite it, edge (v+1)%3
    // (in [0, area2] at a covered centre; |w| < 2^(EdgeW-1) anywhere in the box).
    // Zero on an idle lane (never read): Verilator then skips the wide products.
    always_comb begin
      for (int ch = 0; ch < 3; ch++) begin
        snum_c[ch] = '0;
        if (live)
          for (int v = 0; v < 3; v++)
            snum_c[ch] = snum_c[ch] + CNumW'(e[(v+1)%3]) * $signed({{(CNumW - 8){1'b0}}, in_rgb_i[v*24 + ch*8 +: 8]});
      end
      zsum_lo = '0;
      zsum_hi = '0;
      if (live)
        for (int v = 0; v < 3; v++) begin
          zsum_lo = zsum_lo + ZPW'(e[(v+1)%3]) * $signed({{(ZPW - ZLoW){1'b0}}, in_z_i[v*DepthW +: ZLoW]});
          zsum_hi = zsum_hi + ZPW'(e[(v+1)%3]) * $signed({{(ZPW - ZHiW){1'b0}}, in_z_i[v*DepthW + ZLoW +: ZHiW]});
        end
      snum_z = (ZNumW'(zsum_hi) <<< ZLoW) + ZNumW'(zsum_lo);
    end
    // Clamp flags: negative numerator, or 2 num + area2 >= 2^(bits+1) area2.
    always_comb begin
      for (int ch = 0; ch < 3; ch++) begin
        lo[ch] = snum_c[ch][CNumW-1];
        hi[ch] = !lo[ch] && (((CNumW + 2)'(snum_c[ch]) << 1) + (CNumW + 2)'(in_area2_i) >=
                             ((CNumW + 2)'(in_area2_i) << 9));
        num_c[ch] = (lo[ch] || hi[ch]) ? '0 : ColorNumW'(snum_c[ch]);
      end
      lo[3] = snum_z[ZNumW-1];
      hi[3] = !lo[3] && (((ZNumW + 2)'(snum_z) << 1) + (ZNumW + 2)'(in_area2_i) >=
                         ((ZNumW + 2)'(in_area2_i) << (DepthW + 1)));
      num_z = (lo[3] || hi[3]) ? '0 : DepthNumW'(snum_z);
    end
    assign lane_clamp[j*ClampW +: ClampW] = {hi, lo};
    for (genvar ch = 0; ch < 3; ch++) begin : g_color
      rast_divider #(.NumW(ColorNumW), .DenW(AreaW), .QW(8), .Latency(Latency)) u_div (
        .clk_i, .en_i(en), .valid_i(live), .num_i(num_c[ch]), .den_i(in_area2_i), .q_o(div_rgb[j*24 + ch*8 +: 8]));
      // The clamp at the divider's output (flags delayed like it).
      assign out_rgb_o[j*24 + ch*8 +: 8] = out_clamp[j*ClampW + 4 + ch] ? 8'hff :
                                           out_clamp[j*ClampW + ch] ? 8'h00 : div_rgb[j*24 + ch*8 +: 8];
    end
    rast_divider #(.NumW(DepthNumW), .DenW(AreaW), .QW(DepthW), .Latency(Latency)) u_div_z (
      .clk_i, .en_i(en), .valid_i(live), .num_i(num_z), .den_i(in_area2_i), .q_o(div_z[j*DepthW +: DepthW]));
    assign out_z_o[j*DepthW +: DepthW] = out_clamp[j*ClampW + 7] ? {DepthW{1'b1}} :
                                         out_clamp[j*ClampW + 3] ? '0 : div_z[j*DepthW +: DepthW];
  end

  // ---- Side data: valid, marker, last, lanes and pixels, delayed like the dividers ----
  logic             beat, side_occupied;
  logic [SideW-1:0] side_out;
  assign beat = in_valid_i && (in_marker_i || pick[0]);
  rast_pipe #(.Width(SideW), .Latency(Latency)) u_side (
    .clk_i, .rst_ni, .en_i(en),
    .d_i({beat, in_marker_i, last_beat && !in_marker_i, in_marker_i ? '0 : pick, lane_x, lane_y, lane_smask, lane_clamp}),
    .q_o(side_out), .occupied_o(side_occupied));
  assign {out_valid_o, out_marker_o, out_last_o, out_lanes_o, out_x_o, out_y_o, out_smask_o, out_clamp} = side_out;
  assign busy_o = (pos_q != '0) || side_occupied;
endmodule

`default_nettype wire
