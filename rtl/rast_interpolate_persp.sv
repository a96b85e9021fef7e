// SPDX-License-Identifier: Apache-2.0
// rast_interpolate_persp: one interpolator lane's perspective-correct colour and texture
// coordinates (interp.perspective, interp.recip = "newton"), bit-exact with the
// reference's interpolate_perspective and NewtonDivider (model/ref/interpolate.cpp;
// docs/clip-space.md, "Perspective-correct interpolation", is the spec).
//
// - In, at the pick (combinational): the weights w_k (the edge values, signed EdgeW
//   bits) and the perspective weights Q_k (24 bits unsigned, 1 <= Q_k < 2^24):
//     e_k = w_k Q_k                      EkW = EdgeW + 24 bits signed
//     D   = e_0 + e_1 + e_2              (D <= 0, only outside the triangle: w_k < 0 taken as 0)
//     N_a = e_0 a_0 + e_1 a_1 + e_2 a_2  a: r, g, b (unsigned 8.ColorFrac) and s, t (TexW bits, signed)
//   the bit length L of D (a leading-one search), the divisor d = floor(D 2^(40 - L)) in
//   [2^39, 2^40) into rast_recip, the numerators n' = floor(N_a 2^(40 - L)) (an arithmetic
//   shift) into a delay line beside it, with a flag when |n'| >= 2^84 (85 bits signed: a
//   quotient beyond 2^43, extrapolated far outside the triangle).
// - rast_recip (SeedBits, Iterations): y ~ 2^80 / d, 1 + 2 Iterations stages.
// - Then a = (n' y + 2^79) >> 80 (round half up; 85 x 43-bit signed product; colour:
//   (n' y + 2^(79 + ColorFrac)) >> (80 + ColorFrac), its fraction bits rounded off once), +-2^43 when
//   flagged, clamped to the attribute's range ([0, 255] colour; the signed TexW-bit range
//   for s, t), through OutLatency register stages.
// - Latency from valid_i to the outputs: 1 + 2 Iterations + OutLatency enabled cycles.
//   rast_interpolate makes OutLatency = interp.latency_cycles + 1: the reciprocal unit
//   adds 2 + 2 Iterations to the interpolator's pipeline (TimingParams::interp_recip_latency).
// - Static pipeline: everything advances with en_i, rast_recip too (STATIC = 1: its
//   out_ready_i is the enable, bubbles included). Idle (no valid pixel), the lane's
//   products are not computed (0): the verilated model skips them.
`default_nettype none

module rast_interpolate_persp #(
  parameter int EdgeW      = 49,  // weights w_k: 2N + 3 bits, signed
  parameter int TexW       = 28,  // texture coordinate: 1 + I + F of interp.texcoord_format
  parameter int ColorFrac  = 8,   // interp.color_frac_bits: a vertex colour is unsigned 8.ColorFrac
  parameter int SeedBits   = 8,   // interp.recip_seed_bits
  parameter int Iterations = 2,   // interp.recip_iterations
  parameter int OutLatency = 7    // register stages after the reciprocal (>= 1)
) (
  input  wire logic                  clk_i,    // core clock
  input  wire logic                  rst_ni,   // asynchronous reset, active low
  input  wire logic                  en_i,     // advance the pipeline
  input  wire logic                  valid_i,  // a picked pixel of a perspective-correct triangle
  input  wire logic [3*EdgeW-1:0]    w_i,      // weight of vertex k at [k*EdgeW +: EdgeW], signed
  input  wire logic [3*24-1:0]       q_i,      // Q_k at [k*24 +: 24]
  input  wire logic [9*(8+ColorFrac)-1:0] rgb_i,  // vertex k colour {b, g, r} at [k*3*(8+ColorFrac) +: 3*(8+ColorFrac)]
  input  wire logic [3*TexW-1:0]     s_i,      // vertex k s at [k*TexW +: TexW], signed
  input  wire logic [3*TexW-1:0]     t_i,      // vertex k t, signed
  output      logic [23:0]           rgb_o,    // {b, g, r}
  output      logic [TexW-1:0]       s_o,      // signed
  output      logic [TexW-1:0]       t_o,      // signed
  output      logic                  busy_o    // a pixel in the pipeline
);
  localparam int QBits = 24;                       // Q_k
  localparam int F     = 40;                       // fraction bits of d and y (rast_recip)
  localparam int YW    = 42;                       // y
  localparam int EkW   = EdgeW + QBits;            // derived: e_k, signed
  localparam int DW    = EkW + 2;                  // derived: D, signed
  localparam int CW    = 8 + ColorFrac;            // derived: a vertex colour channel, unsigned
  localparam int AW    = TexW > CW + 1 ? TexW : CW + 1;  // derived: an attribute, signed
  localparam int NaW   = EkW + AW + 2;             // derived: N_a, signed
  localparam int NpW   = 85;                       // n', signed: |n'| < 2^84
  localparam int XW    = (NaW + F > NpW) ? NaW + F : NpW + 1;  // derived: N_a 2^40, signed
  localparam int LW    = $clog2(DW + 1);           // derived: L
  localparam int PW    = NpW + YW + 1;             // derived: n' y, signed
  localparam int QW    = PW - 2 * F;               // derived: the rounded quotient, signed
  localparam int Attrs = 5;                        // r, g, b, s, t
  localparam int Stages = 1 + 2 * Iterations;      // derived: rast_recip's latency
  localparam int NpPipeW = 1 + Attrs * (NpW + 1);  // derived: {valid, n' and flag a attribute}
  localparam int OutW  = 1 + 24 + 2 * TexW;        // derived: {valid, rgb, s, t}

  if (OutLatency < 1) begin : g_check_latency
    $error("rast_interpolate_persp: OutLatency (%0d) must be at least 1 (the product's stage)", OutLatency);
  end

  // ---- e_k, D ----
  logic signed [EkW-1:0] e_raw [3], e [3];
  logic signed [DW-1:0]  d_raw, d_sum;
  always_comb begin
    d_raw = '0;
    d_sum = '0;
    for (int k = 0; k < 3; k++) begin
      e_raw[k] = '0;
      e[k] = '0;
    end
    if (valid_i) begin
      for (int k = 0; k < 3; k++) begin
        e_raw[k] = EkW'($signed(w_i[k*EdgeW +: EdgeW])) * $signed({1'b0, q_i[k*QBits +: QBits]});
        d_raw = d_raw + DW'(e_raw[k]);
      end
      // Q_k > 0: e_k < 0 exactly when w_k < 0.
      for (int k = 0; k < 3; k++) begin
        e[k] = (d_raw <= 0 && e_raw[k] < 0) ? '0 : e_raw[k];
        d_sum = d_sum + DW'(e[k]);
      end
    end
  end

  // ---- The attributes, signed AW bits: attribute i of vertex k at [(i*3+k)*AW +: AW] ----
  logic [Attrs*3*AW-1:0] a_flat;
  for (genvar k = 0; k < 3; k++) begin : g_vertex
    for (genvar ch = 0; ch < 3; ch++) begin : g_color
      assign a_flat[(ch*3+k)*AW +: AW] = {{(AW - CW){1'b0}}, rgb_i[(k*3 + ch)*CW +: CW]};
    end
    assign a_flat[(3*3+k)*AW +: AW] = AW'($signed(s_i[k*TexW +: TexW]));
    assign a_flat[(4*3+k)*AW +: AW] = AW'($signed(t_i[k*TexW +: TexW]));
  end

  // ---- L, d, n' ----
  logic [LW-1:0]       len;
  logic [F-1:0]        d;
  logic [NpPipeW-1:0]  np_in, np_out;
  logic                np_busy;
  always_comb begin
    len = '0;
    d = '0;
    if (valid_i) begin
      for (int b = 0; b < DW; b++)
        if (d_sum[b]) len = LW'(b + 1);
      d = F'({d_sum, {F{1'b0}}} >> len);
    end
  end
  always_comb begin
    logic signed [NaW-1:0] num;
    logic signed [XW-1:0]  nx;
    num = '0;
    nx = '0;
    np_in = '0;
    np_in[NpPipeW-1] = valid_i;
    if (valid_i)
      for (int i = 0; i < Attrs; i++) begin
        num = '0;
        for (int k = 0; k < 3; k++) num = num + NaW'(e[k]) * NaW'($signed(a_flat[(i*3+k)*AW +: AW]));
        nx = XW'($signed({num, {F{1'b0}}})) >>> len;
        // {flag, n'}: the flag when nx does not fit NpW bits signed.
        np_in[i*(NpW+1) +: NpW+1] = {!(&nx[XW-1:NpW-1] || !(|nx[XW-1:NpW-1])), nx[NpW-1:0]};
      end
  end
  rast_pipe #(.Width(NpPipeW), .Latency(Stages)) u_np (
    .clk_i, .rst_ni, .en_i, .d_i(np_in), .q_o(np_out), .occupied_o(np_busy));

  // ---- The reciprocal ----
  logic [YW-1:0] y;
  logic          recip_ready, recip_valid;
  rast_recip #(.SEED_BITS(SeedBits), .ITERATIONS(Iterations), .STATIC(1)) u_recip (
    .clk_i, .rst_ni, .in_valid_i(valid_i), .in_ready_o(recip_ready), .d_i(d), .out_valid_o(recip_valid),
    .out_ready_i(en_i), .y_o(y));
  // Static pipeline: the unit's ready is en_i, and its valid is the n' delay line's.
  wire unused_ok = &{1'b0, recip_ready, recip_valid};

  // ---- a = (n' y + 2^79) >> 80, saturated, clamped ----
  logic [OutW-1:0] out_in, out_q;
  logic            out_busy;
  always_comb begin
    logic signed [NpW-1:0] np;
    logic                  flag;
    logic signed [PW-1:0]  prod;
    logic signed [QW-1:0]  qv, lo, hi;
    {flag, np} = '0;
    prod = '0;
    {qv, lo, hi} = '0;
    out_in = '0;
    out_in[OutW-1] = np_out[NpPipeW-1];
    if (np_out[NpPipeW-1])
      for (int i = 0; i < Attrs; i++) begin
        {flag, np} = np_out[i*(NpW+1) +: NpW+1];
        prod = PW'(np) * $signed({1'b0, y});
        if (i < 3) qv = QW'((prod + (PW'(1) <<< (2 * F + ColorFrac - 1))) >>> (2 * F + ColorFrac));
        else qv = QW'((prod + (PW'(1) <<< (2 * F - 1))) >>> (2 * F));
        if (flag) qv = np < 0 ? -(QW'(1) <<< 43) : (QW'(1) <<< 43);
        lo = i < 3 ? '0 : -(QW'(1) <<< (TexW - 1));
        hi = i < 3 ? QW'(255) : (QW'(1) <<< (TexW - 1)) - 1;
        if (qv < lo) qv = lo;
        if (qv > hi) qv = hi;
        if (i < 3) out_in[2*TexW + i*8 +: 8] = qv[7:0];
        else if (i == 3) out_in[TexW +: TexW] = qv[TexW-1:0];
        else out_in[0 +: TexW] = qv[TexW-1:0];
      end
  end
  rast_pipe #(.Width(OutW), .Latency(OutLatency)) u_out (
    .clk_i, .rst_ni, .en_i, .d_i(out_in), .q_o(out_q), .occupied_o(out_busy));
  assign rgb_o = out_q[2*TexW +: 24];
  assign s_o = out_q[TexW +: TexW];
  assign t_o = out_q[0 +: TexW];
  assign busy_o = np_busy || out_busy;
  wire unused_valid = &{1'b0, out_q[OutW-1]};  // the interpolator's side pipe says which lanes hold a pixel
endmodule

`default_nettype wire
