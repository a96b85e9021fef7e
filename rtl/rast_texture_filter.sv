// SPDX-License-Identifier: Apache-2.0
// rast_texture_filter: a sample's filtered colour from its texels (docs/texture.md,
// "Texel addressing and filters"; the golden arithmetic is ref/texture/texture.h
// filter_texels and blend_levels). Per channel (RGBA8):
//   nearest   the first texel
//   bilinear  (T00 (256-a)(256-b) + T10 a (256-b) + T01 (256-a) b + T11 a b + 2^15) >> 16
//             (a, b the weights 0..255 in 1/256 from rast_texture_address, already
//             rounded to texture.weight_bits; each weight product 17 bits, the sum 24)
//   trilinear (with blend_i) the level blend (c0 (256 - f) + c f + 128) >> 8,
//             c0 = prev_i the first level's colour, c
//             this level's, f = frac_i: the second level's sample carries the first's
//             result, so one unit does both levels, a sample a level. With chain_i the
//             first level's colour is instead this unit's previous output (color_o, the
//             sample just before: rast_texture_stage sends the two levels back to back
//             and drops the first's output), so the second level need not wait for it.
// No intermediate rounding: one rounding of the weighted sum, one of the blend.
//
// Pipeline: 3 register stages (1: the weight products; 2: the weighted sums, rounded;
// 3: the level blend), one sample a cycle; every stage advances while the last is empty
// or taken. Latency 3 cycles.
`default_nettype none

module rast_texture_filter (
  input  wire logic         clk_i,
  input  wire logic         rst_ni,      // asynchronous reset, active low
  input  wire logic         in_valid_i,
  output      logic         in_ready_o,
  input  wire logic [127:0] texels_i,    // texel k (fetch order) at [32k +: 32], channel c at [8c +: 8] (R first)
  input  wire logic [7:0]   alpha_i,     // weight of i1, /256
  input  wire logic [7:0]   beta_i,      // weight of j1, /256
  input  wire logic         bilinear_i,  // else nearest: texel 0
  input  wire logic         blend_i,     // blend with prev_i (trilinear's second level)
  input  wire logic [31:0]  prev_i,      // the first level's colour
  input  wire logic         chain_i,     // blend with the previous output (color_o), not prev_i
  input  wire logic [7:0]   frac_i,      // the second level's weight, /256
  output      logic         out_valid_o,
  input  wire logic         out_ready_i,
  output      logic [31:0]  color_o      // RGBA8, R at [7:0]
);
  logic en;
  logic v1_q, v2_q, v3_q;
  assign en = !v3_q || out_ready_i;
  assign in_ready_o = en;
  assign out_valid_o = v3_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) {v1_q, v2_q, v3_q} <= 3'b000;
    else if (en) {v1_q, v2_q, v3_q} <= {in_valid_i, v1_q, v2_q};
  end

  // ---- Stage 1: the four weights (0 .. 65536: 17 bits) ----
  logic [8:0] a, b, na, nb;  // 0..256
  assign a = {1'b0, alpha_i};
  assign b = {1'b0, beta_i};
  assign na = 9'd256 - a;
  assign nb = 9'd256 - b;
  logic [16:0] w0_q, w1_q, w2_q, w3_q;
  logic [127:0] tex1_q;
  logic bil1_q, blend1_q, blend2_q, chain1_q, chain2_q;
  logic [31:0] prev1_q, prev2_q;
  logic [7:0] frac1_q, frac2_q;
  always_ff @(posedge clk_i) begin
    if (en && in_valid_i) begin
      w0_q <= 17'(na) * 17'(nb);
      w1_q <= 17'(a) * 17'(nb);
      w2_q <= 17'(na) * 17'(b);
      w3_q <= 17'(a) * 17'(b);
      tex1_q <= texels_i;
      bil1_q <= bilinear_i;
      {blend1_q, chain1_q, prev1_q, frac1_q} <= {blend_i, chain_i, prev_i, frac_i};
    end
    if (en && v1_q) {blend2_q, chain2_q, prev2_q, frac2_q} <= {blend1_q, chain1_q, prev1_q, frac1_q};
  end

  // ---- Stage 2: the weighted sums, rounded half up (24 bits: the weights sum to 2^16) ----
  logic [31:0] c2_q;
  /* verilator lint_off UNUSEDSIGNAL */
  logic [95:0] sum;  // channel c's sum at [24c +: 24]: its top 8 bits are the result
  /* verilator lint_on UNUSEDSIGNAL */
  always_comb begin
    for (int c = 0; c < 4; c++)
      sum[c*24 +: 24] = 24'(w0_q) * 24'(tex1_q[c*8 +: 8]) + 24'(w1_q) * 24'(tex1_q[32 + c*8 +: 8]) +
               24'(w2_q) * 24'(tex1_q[64 + c*8 +: 8]) + 24'(w3_q) * 24'(tex1_q[96 + c*8 +: 8]) + 24'(1 << 15);
  end
  always_ff @(posedge clk_i) begin
    if (en && v1_q)
      c2_q <= bil1_q ? {sum[88 +: 8], sum[64 +: 8], sum[40 +: 8], sum[16 +: 8]} : tex1_q[31:0];
  end

  // ---- Stage 3: the level blend ----
  /* verilator lint_off UNUSEDSIGNAL */
  logic [63:0] mix;  // channel c's c0 (256 - f) + c f + 128 (<= 255 x 256 + 128) at [16c +: 16]: >> 8
  /* verilator lint_on UNUSEDSIGNAL */
  logic [8:0] nf;    // 256 - f
  logic [31:0] c0;   // the first level's colour
  assign nf = 9'd256 - {1'b0, frac2_q};
  assign c0 = chain2_q ? color_o : prev2_q;
  always_comb begin
    for (int c = 0; c < 4; c++)
      mix[c*16 +: 16] = 16'(c0[c*8 +: 8]) * 16'(nf) + 16'(c2_q[c*8 +: 8]) * 16'(frac2_q) + 16'd128;
  end
  always_ff @(posedge clk_i) begin
    if (en && v2_q)
      color_o <= blend2_q ? {mix[56 +: 8], mix[40 +: 8], mix[24 +: 8], mix[8 +: 8]} : c2_q;
  end
endmodule

`default_nettype wire
