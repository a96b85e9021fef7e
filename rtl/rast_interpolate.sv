// SPDX-License-Identifier: Apache-2.0
// rast_interpolate: colour, depth and texture coordinates of each covered pixel (ref:
// model/ref/interpolate.cpp; model: model/sc/interpolate.cpp).
//
// - Takes a tile's coverage mask and walks its set bits in order (row-major within
//   the tile), FragmentsPerCycle pixels a cycle: a mask of N pixels takes
//   ceil(N / FragmentsPerCycle) cycles, a marker one. A perspective-correct triangle
//   (Perspective and in_affine_i low) is walked PerspLanes pixels a cycle (the lanes
//   with a reciprocal unit, min(interp.fragments_per_cycle, recip.lanes)):
//   ceil(N / PerspLanes) cycles (TimingParams::interp_batch_cycles).
// - Per pixel: the barycentric weights are the edge values at the pixel centre,
//   w0 = E1, w1 = E2, w2 = E0 (signed EdgeW bits, sum area2); each attribute is
//   round_half_up((w0 a0 + w1 a1 + w2 a2) / area2), one rast_divider per attribute and
//   lane (quotient 8 bits colour, DepthW depth; numerators ColorNumW / DepthNumW).
// - Colour: vertex values unsigned 8.ColorFrac (interp.color_frac_bits), the colour
//   round_half_up((w0 c0 + w1 c1 + w2 c2) / (area2 2^ColorFrac)): the divider's
//   denominator is area2 shifted, so the quotient is RGB8, rounded once.
// - Texture coordinates s, t (signed TexW bits) of an affine triangle: the same rational
//   on the vertex values offset by 2^(TexW-1) (unsigned, so the divider and the clamp
//   are the colour's: round_half_up(x + k) = round_half_up(x) + k for an integer k), the
//   offset taken off at the output. s and t the same at the three vertices (every
//   untextured scene) are that value at every point (the weights sum to area2): the
//   side pipe carries it, and the dividers idle.
// - Perspective-correct colour and texture coordinates (not affine; Perspective):
//   rast_interpolate_persp on the first PerspLanes lanes, from the same weights and the
//   vertices' Q_k (docs/clip-space.md); depth stays the affine divider's.
// - Multisampling (msaa): a pixel with a covered sample but its centre outside the
//   triangle has a negative weight, and the rational may leave the attribute's range:
//   the result is clamped to [0, 2^bits - 1] as ref interpolate_plane_at does. The signed
//   numerator (NumW + 3 bits: |w| < 2^(EdgeW-1)) is tested before the divider: negative
//   -> 0; 2 num + area2 >= 2^(bits+1) area2 (the rounded quotient >= 2^bits) -> 2^bits - 1;
//   otherwise the divider gets it (then < 2^bits area2, as before). The flags ride the
//   side pipe. With one sample every weight is >= 0 and no flag is ever set.
// - Each fragment carries its pixel's sample mask (in_smask_i, MaxSamples bits a pixel).
// - Latency + RecipLatency register stages (interp.latency_cycles, plus the reciprocal
//   unit's 2 + 2 RecipIterations when Perspective: TimingParams::interp_pipeline_latency)
//   from a pixel's pick to its fragment, for every triangle (a static pipeline); the
//   whole pipeline stalls while the output is not taken.
// - The input is popped in the cycle that picks its last pixels.
`default_nettype none

module rast_interpolate #(
  parameter int CoordW            = 24,  // N + 1
  parameter int CoordFrac         = 16,  // F
  parameter int CoefW             = 25,  // N + 2
  parameter int EdgeW             = 49,  // 2N + 3
  parameter int AreaW             = 48,  // 2N + 2
  parameter int ColorNumW         = 64,  // 2N + 10 + ColorFrac
  parameter int ColorFrac         = 8,   // interp.color_frac_bits: a vertex colour is unsigned 8.ColorFrac
  parameter int DepthNumW         = 72,  // 2N + 2 + D
  parameter int DepthW            = 24,  // D
  parameter int PixelW            = 14,  // pixel index bits
  parameter int TileLog2Max       = 4,   // largest tile: 2^TileLog2Max pixels square
  parameter int TileLog2W         = 3,   // tile_log2_i bits
  parameter int FragmentsPerCycle = 4,   // pixels interpolated per cycle
  parameter int Latency           = 6,   // pick-to-fragment register stages
  parameter int MaxSamples        = 16,  // sample mask bits a pixel (a power of two >= 2)
  parameter int TexW              = 28,  // texture coordinate: 1 + I + F of interp.texcoord_format, signed
  parameter int Perspective       = 1,   // interp.perspective: build the reciprocal lanes
  parameter int PerspLanes        = 4,   // lanes with a reciprocal: min(FragmentsPerCycle, recip.lanes)
  parameter int RecipSeedBits     = 8,   // interp.recip_seed_bits
  parameter int RecipIterations   = 2,   // interp.recip_iterations
  parameter int RecipLatency      = 6,   // the unit's stages: 2 + 2 RecipIterations, 0 without it
  localparam int MaskW = 1 << (2 * TileLog2Max),  // derived: coverage mask bits
  localparam int SMaskW = MaskW * MaxSamples,     // derived: sample mask bits
  localparam int Lanes = FragmentsPerCycle,       // derived
  localparam int ColorW = 8 + ColorFrac           // derived: a vertex colour channel
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
  input  wire logic                      in_rowpair_i,  // textured: a beat holds one row pair's pixels
  input  wire logic [3*CoefW-1:0]        in_a_i,        // edge a
  input  wire logic [3*CoefW-1:0]        in_b_i,        // edge b
  input  wire logic [3*EdgeW-1:0]        in_c_i,        // edge c
  input  wire logic [2*PixelW-1:0]       in_origin_i,   // pixel of raw (0, 0): {y, x}
  input  wire logic [AreaW-1:0]          in_area2_i,    // doubled area, > 0
  input  wire logic [3*DepthW-1:0]       in_z_i,        // vertex k depth at [k*DepthW +: DepthW]
  input  wire logic [9*ColorW-1:0]       in_rgb_i,      // vertex k colour {b, g, r} at [k*3*ColorW +: 3*ColorW]
  input  wire logic [3*TexW-1:0]         in_s_i,        // vertex k s at [k*TexW +: TexW], signed
  input  wire logic [3*TexW-1:0]         in_t_i,        // vertex k t, signed
  input  wire logic [3*24-1:0]           in_q_i,        // vertex k perspective weight Q_k at [k*24 +: 24]
  input  wire logic                      in_affine_i,   // no reciprocal needed (tri_setup's affine)
  output      logic                      out_valid_o,   // a beat of fragments or a marker
  input  wire logic                      out_ready_i,   // taken this cycle
  output      logic                      out_marker_o,  // the beat is a marker
  output      logic                      out_last_o,    // last beat of a tile's fragments
  output      logic [Lanes-1:0]          out_lanes_o,   // lane j holds a fragment
  output      logic [Lanes*PixelW-1:0]   out_x_o,       // lane j pixel x
  output      logic [Lanes*PixelW-1:0]   out_y_o,       // lane j pixel y
  output      logic [Lanes*DepthW-1:0]   out_z_o,       // lane j depth
  output      logic [Lanes*24-1:0]       out_rgb_o,     // lane j colour {b, g, r}
  output      logic [Lanes*TexW-1:0]     out_s_o,       // lane j s, signed
  output      logic [Lanes*TexW-1:0]     out_t_o,       // lane j t, signed
  output      logic [Lanes*MaxSamples-1:0] out_smask_o, // lane j sample mask
  output      logic                      busy_o         // a mask half done or a beat in the pipeline
);
  // Elaboration-time checks: the reciprocal lanes and the latency the export computed
  // (TimingParams::interp_recip_latency) are this structure's.
  if (Perspective != 0 && (PerspLanes < 1 || PerspLanes > FragmentsPerCycle)) begin : g_check_persp_lanes
    $error("rast_interpolate: PerspLanes (%0d) must be in 1..FragmentsPerCycle (%0d)", PerspLanes, FragmentsPerCycle);
  end
  if (RecipLatency != (Perspective != 0 ? 2 + 2 * RecipIterations : 0)) begin : g_check_recip_latency
    $error("rast_interpolate: RecipLatency (%0d) must be %0d (Perspective %0d, RecipIterations %0d)", RecipLatency,
           Perspective != 0 ? 2 + 2 * RecipIterations : 0, Perspective, RecipIterations);
  end
  if (Perspective == 0) begin : g_no_recip
    wire unused_q = &{1'b0, in_q_i};  // Q_k matter only to the reciprocal lanes
  end
  localparam int IdxW  = 2 * TileLog2Max;              // derived: mask index bits
  localparam int SIdxW = $clog2(MaxSamples);           // derived: sample index bits
  localparam int Divs  = 6;                            // dividers a lane: r, g, b, z, s, t
  localparam int ClampW = 2 * Divs;                    // derived: {lo, hi} flags of the dividers
  localparam int BeatW = 2 + 2 * TexW;                 // derived: {perspective, flat s t, s, t} of a beat
  localparam int SideW = 3 + BeatW + Lanes * (1 + 2 * PixelW + MaxSamples + ClampW);  // derived: side data bits
  localparam int CNumW = ColorNumW + 3;                // derived: signed colour numerator
  localparam int CDenW = AreaW + ColorFrac;            // derived: the colour divider's area2 2^ColorFrac
  localparam int TexNumW = AreaW + TexW;               // derived: texture numerator (offset, unsigned)
  localparam int TNumW = TexNumW + 3;                  // derived: signed texture numerator
  localparam int PipeLatency = Latency + RecipLatency; // derived: pick to fragment
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
  // The beat's triangle needs the reciprocal: at most PerspLanes pixels a beat.
  logic        persp;
  logic [31:0] beat_lanes;
  assign persp = Perspective != 0 && !in_affine_i;
  assign beat_lanes = persp ? PerspLanes : Lanes;
  assign pos_row = {{(32 - IdxW){1'b0}}, pos_q} >> RowIW;
  assign pos_bit = {{(32 - IdxW){1'b0}}, pos_q} & (RowW - 1);
  logic [IdxW-1:0]  idx [Lanes];
  logic [Lanes-1:0] pick;
  logic             last_beat;
  logic [IdxW-1:0]  next_pos;  // the bit after the beat's last pick

  // ---- The next Lanes set bits of the mask at or after pos_q, lowest first ----
  // A row (RowW bits) at a time: a row without a set bit left costs one test, and the
  // scan stops looking once it has found Lanes + 1 bits (the +1 says whether this is the
  // last beat). In hardware the same function as a priority select over the whole mask;
  // in Verilator the per-cycle work follows the rows holding the beat's pixels, not the
  // mask width. (Was: rem = in_mask_i & ~consumed_q over all MaskW bits, a MaskW-bit
  // register of picked pixels, and a MaskW-iteration loop every cycle.)
  // A textured tile (in_rowpair_i) stops a beat at the end of a row pair (pixel rows 2m,
  // 2m + 1: ly >> 1 of the bit, whatever the tile size): the texture stage's quad table
  // then sees one row pair a beat (rast_texture_stage.sv).
  always_comb begin
    int k;
    logic stop;
    logic [RowW-1:0] row;
    logic [IdxW-1:0] p, rp, rp0;
    k = 0;
    stop = 1'b0;
    p = '0;
    rp = '0;
    rp0 = '0;
    pick = '0;
    next_pos = '0;
    for (int j = 0; j < Lanes; j++) idx[j] = '0;
    last_beat = 1'b1;
    for (int r = 0; r < Rows; r++) begin
      row = in_mask_i[r*RowW +: RowW];
      if (r < pos_row) row = '0;
      else if (r == pos_row) row = row & ({RowW{1'b1}} << pos_bit);
      if (k <= beat_lanes && !stop && row != '0) begin
        for (int b = 0; b < RowW; b++) begin
          if (row[b] && !stop) begin
            p = IdxW'(r * RowW + b);
            rp = p >> (32'(tile_log2_i) + 1);
            if (in_rowpair_i && k > 0 && rp != rp0) begin
              stop = 1'b1;  // the next row pair: the next beat
              last_beat = 1'b0;
            end else if (k < beat_lanes) begin
              idx[k]  = p;
              pick[k] = 1'b1;
              next_pos = p + 1'b1;
              if (k == 0) rp0 = rp;
              k = k + 1;
            end else begin
              last_beat = 1'b0;
              k = k + 1;
            end
          end
        end
      end
    end
  end

  assign en         = !(out_valid_o && !out_ready_i);
  assign in_ready_o = en && in_valid_i && (in_marker_i || last_beat);

  // Not the last beat: all beat_lanes lanes picked, and the next beat starts after the last.
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) pos_q <= '0;
    else if (en && in_valid_i && !in_marker_i) pos_q <= last_beat ? '0 : next_pos;
  end

  // s and t flat (equal at the three vertices): the vertex value at every point.
  logic tex_flat;
  assign tex_flat = in_s_i[0 +: TexW] == in_s_i[TexW +: TexW] && in_s_i[0 +: TexW] == in_s_i[2*TexW +: TexW] &&
                    in_t_i[0 +: TexW] == in_t_i[TexW +: TexW] && in_t_i[0 +: TexW] == in_t_i[2*TexW +: TexW];
  logic [BeatW-1:0] beat_in, beat_out;  // {persp, tex_flat, s0, t0}
  assign beat_in = {persp, tex_flat, in_s_i[0 +: TexW], in_t_i[0 +: TexW]};
  logic out_persp, out_tex_flat;
  logic [TexW-1:0] out_s0, out_t0;
  assign {out_persp, out_tex_flat, out_s0, out_t0} = beat_out;

  // ---- Per lane: pixel, weights, numerators, dividers ----
  logic [Lanes*PixelW-1:0] lane_x, lane_y;
  logic [Lanes*MaxSamples-1:0] lane_smask;
  logic [Lanes*ClampW-1:0] lane_clamp, out_clamp;
  logic [Lanes*DepthW-1:0] div_z;
  logic [Lanes*24-1:0]     div_rgb;
  logic [Lanes*2*TexW-1:0] div_st;   // lane j {s, t}, offset by 2^(TexW-1)
  logic [Lanes-1:0]        persp_busy;
  for (genvar j = 0; j < Lanes; j++) begin : g_lane
    logic [PixelW-1:0]     px, py;
    logic [CoordW-1:0]     sx, sy;
    logic signed [EdgeW-1:0] e [3];
    logic signed [CNumW-1:0] snum_c [3];
    logic signed [TNumW-1:0] snum_t [2];  // s, t
    logic [TexNumW-1:0]    num_t [2];
    logic signed [ZNumW-1:0] snum_z;
    logic signed [ZPW-1:0]   zsum_lo, zsum_hi;  // sum of e z_lo, of e z_hi
    logic [ColorNumW-1:0]  num_c [3];
    logic [DepthNumW-1:0]  num_z;
    logic [Divs-1:0]       lo, hi;  // per divider (r, g, b, z, s, t): clamp to 0 / to the maximum
    logic [IdxW-1:0]       mask_lx, lx, ly;
    logic                  live;   // the lane holds a picked pixel this cycle
    logic                  alive;  // ... of an affine triangle: the colour dividers' pixel
    logic                  tlive;  // ... whose s, t vary: the texture dividers' pixel
    assign live = in_valid_i && !in_marker_i && pick[j];
    assign alive = live && !persp;
    assign tlive = alive && !tex_flat;
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
        if (alive)
          for (int v = 0; v < 3; v++)
            snum_c[ch] = snum_c[ch] + CNumW'(e[(v+1)%3]) *
                         $signed({{(CNumW - ColorW){1'b0}}, in_rgb_i[(v*3 + ch)*ColorW +: ColorW]});
      end
      zsum_lo = '0;
      zsum_hi = '0;
      if (live)
        for (int v = 0; v < 3; v++) begin
          zsum_lo = zsum_lo + ZPW'(e[(v+1)%3]) * $signed({{(ZPW - ZLoW){1'b0}}, in_z_i[v*DepthW +: ZLoW]});
          zsum_hi = zsum_hi + ZPW'(e[(v+1)%3]) * $signed({{(ZPW - ZHiW){1'b0}}, in_z_i[v*DepthW + ZLoW +: ZHiW]});
        end
      snum_z = (ZNumW'(zsum_hi) <<< ZLoW) + ZNumW'(zsum_lo);
      // s (c = 0), t (c = 1), each vertex value offset by 2^(TexW-1): its sign bit flipped.
      snum_t[0] = '0;
      snum_t[1] = '0;
      if (tlive)
        for (int v = 0; v < 3; v++) begin
          snum_t[0] = snum_t[0] + TNumW'(e[(v+1)%3]) *
                      $signed({{(TNumW - TexW){1'b0}}, ~in_s_i[v*TexW + TexW - 1], in_s_i[v*TexW +: TexW-1]});
          snum_t[1] = snum_t[1] + TNumW'(e[(v+1)%3]) *
                      $signed({{(TNumW - TexW){1'b0}}, ~in_t_i[v*TexW + TexW - 1], in_t_i[v*TexW +: TexW-1]});
        end
    end
    // Clamp flags: negative numerator, or 2 num + den >= 2^(bits+1) den (colour: den =
    // area2 2^ColorFrac).
    always_comb begin
      for (int ch = 0; ch < 3; ch++) begin
        lo[ch] = snum_c[ch][CNumW-1];
        hi[ch] = !lo[ch] && (((CNumW + 2)'(snum_c[ch]) << 1) + ((CNumW + 2)'(in_area2_i) << ColorFrac) >=
                             ((CNumW + 2)'(in_area2_i) << (9 + ColorFrac)));
        num_c[ch] = (lo[ch] || hi[ch]) ? '0 : ColorNumW'(snum_c[ch]);
      end
      lo[3] = snum_z[ZNumW-1];
      hi[3] = !lo[3] && (((ZNumW + 2)'(snum_z) << 1) + (ZNumW + 2)'(in_area2_i) >=
                         ((ZNumW + 2)'(in_area2_i) << (DepthW + 1)));
      num_z = (lo[3] || hi[3]) ? '0 : DepthNumW'(snum_z);
      for (int c = 0; c < 2; c++) begin
        lo[4 + c] = 1'b0;
        hi[4 + c] = 1'b0;
        num_t[c] = '0;
        if (tlive) begin  // else the dividers idle (flat s, t or another path)
          lo[4 + c] = snum_t[c][TNumW-1];
          hi[4 + c] = !lo[4 + c] && (((TNumW + 2)'(snum_t[c]) << 1) + (TNumW + 2)'(in_area2_i) >=
                                     ((TNumW + 2)'(in_area2_i) << (TexW + 1)));
          num_t[c] = (lo[4 + c] || hi[4 + c]) ? '0 : TexNumW'(snum_t[c]);
        end
      end
    end
    assign lane_clamp[j*ClampW +: ClampW] = {hi, lo};
    // Perspective-correct colour and s, t (the first PerspLanes lanes).
    logic [23:0]     persp_rgb;
    logic [TexW-1:0] persp_s, persp_t;
    if (Perspective != 0 && j < PerspLanes) begin : g_persp
      logic [3*EdgeW-1:0] w;  // weight of vertex v: edge (v+1)%3
      for (genvar v = 0; v < 3; v++) begin : g_w
        assign w[v*EdgeW +: EdgeW] = e[(v+1)%3];
      end
      rast_interpolate_persp #(.EdgeW(EdgeW), .TexW(TexW), .ColorFrac(ColorFrac), .SeedBits(RecipSeedBits), .Iterations(RecipIterations),
                               .OutLatency(Latency + 1)) u_persp (
        .clk_i, .rst_ni, .en_i(en), .valid_i(live && persp), .w_i(w), .q_i(in_q_i), .rgb_i(in_rgb_i), .s_i(in_s_i),
        .t_i(in_t_i), .rgb_o(persp_rgb), .s_o(persp_s), .t_o(persp_t), .busy_o(persp_busy[j]));
    end else begin : g_affine_only  // never picked for a perspective-correct triangle
      assign {persp_rgb, persp_s, persp_t} = '0;
      assign persp_busy[j] = 1'b0;
    end
    for (genvar ch = 0; ch < 3; ch++) begin : g_color
      rast_divider #(.NumW(ColorNumW), .DenW(CDenW), .QW(8), .Latency(PipeLatency)) u_div (
        .clk_i, .en_i(en), .valid_i(alive), .num_i(num_c[ch]), .den_i(CDenW'(in_area2_i) << ColorFrac),
        .q_o(div_rgb[j*24 + ch*8 +: 8]));
      // The clamp at the divider's output (flags delayed like it).
      assign out_rgb_o[j*24 + ch*8 +: 8] = out_persp ? persp_rgb[ch*8 +: 8] :
                                           out_clamp[j*ClampW + Divs + ch] ? 8'hff :
                                           out_clamp[j*ClampW + ch] ? 8'h00 : div_rgb[j*24 + ch*8 +: 8];
    end
    rast_divider #(.NumW(DepthNumW), .DenW(AreaW), .QW(DepthW), .Latency(PipeLatency)) u_div_z (
      .clk_i, .en_i(en), .valid_i(live), .num_i(num_z), .den_i(in_area2_i), .q_o(div_z[j*DepthW +: DepthW]));
    assign out_z_o[j*DepthW +: DepthW] = out_clamp[j*ClampW + Divs + 3] ? {DepthW{1'b1}} :
                                         out_clamp[j*ClampW + 3] ? '0 : div_z[j*DepthW +: DepthW];
    for (genvar c = 0; c < 2; c++) begin : g_tex
      logic [TexW-1:0] q, clamped;
      rast_divider #(.NumW(TexNumW), .DenW(AreaW), .QW(TexW), .Latency(PipeLatency)) u_div (
        .clk_i, .en_i(en), .valid_i(tlive), .num_i(num_t[c]), .den_i(in_area2_i), .q_o(q));
      assign clamped = out_clamp[j*ClampW + Divs + 4 + c] ? {TexW{1'b1}} : out_clamp[j*ClampW + 4 + c] ? '0 : q;
      assign div_st[(j*2+c)*TexW +: TexW] = {~clamped[TexW-1], clamped[TexW-2:0]};  // the offset taken off
    end
    assign out_s_o[j*TexW +: TexW] = out_persp ? persp_s : out_tex_flat ? out_s0 : div_st[(j*2)*TexW +: TexW];
    assign out_t_o[j*TexW +: TexW] = out_persp ? persp_t : out_tex_flat ? out_t0 : div_st[(j*2+1)*TexW +: TexW];
  end

  // ---- Side data: valid, marker, last, the beat's triangle, lanes and pixels, delayed like
  // the dividers ----
  logic             beat, side_occupied;
  logic [SideW-1:0] side_out;
  assign beat = in_valid_i && (in_marker_i || pick[0]);
  rast_pipe #(.Width(SideW), .Latency(PipeLatency)) u_side (
    .clk_i, .rst_ni, .en_i(en),
    .d_i({beat, in_marker_i, last_beat && !in_marker_i, beat_in, in_marker_i ? '0 : pick, lane_x, lane_y, lane_smask,
          lane_clamp}),
    .q_o(side_out), .occupied_o(side_occupied));
  assign {out_valid_o, out_marker_o, out_last_o, beat_out, out_lanes_o, out_x_o, out_y_o, out_smask_o, out_clamp} =
      side_out;
  assign busy_o = (pos_q != '0) || side_occupied || (|persp_busy);
endmodule

`default_nettype wire
