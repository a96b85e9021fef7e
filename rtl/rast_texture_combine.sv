// SPDX-License-Identifier: Apache-2.0
// rast_texture_combine: the texenv combine of the texture colour T (RGBA8) with the
// fragment's interpolated colour C (RGB8) (docs/texture.md, "Texenv combine"; the golden
// arithmetic is ref/texture/texture.h texenv_combine). Per colour channel:
//   replace   T
//   modulate  (T C + 127) / 255
//   decal     (C (255 - T_a) + T T_a + 127) / 255
// The quotient by 255 without a divider: for 0 <= y <= 255 x 255 + 127 = 65152,
// floor(y / 255) = (y + 1 + (y >> 8)) >> 8 (true for every such y; the first y it misses
// is 65535). The unit bench feeds every (T, C) of modulate and every (C, T, T_a) of
// decal, so every numerator this unit can form is checked against the reference.
//
// Pipeline: 2 register stages (1: the products; 2: the quotient), one fragment a cycle;
// every stage advances while the last is empty or taken. Latency 2 cycles.
`default_nettype none

module rast_texture_combine (
  input  wire logic        clk_i,
  input  wire logic        rst_ni,      // asynchronous reset, active low
  input  wire logic        in_valid_i,
  output      logic        in_ready_o,
  input  wire logic [31:0] tex_i,       // T, RGBA8, R at [7:0]
  input  wire logic [23:0] color_i,     // C, RGB8, R at [7:0]
  input  wire logic [1:0]  env_i,       // 0 replace, 1 modulate, 2 decal
  output      logic        out_valid_o,
  input  wire logic        out_ready_i,
  output      logic [23:0] color_o      // RGB8, R at [7:0]
);
  logic en;
  logic v1_q, v2_q;
  assign en = !v2_q || out_ready_i;
  assign in_ready_o = en;
  assign out_valid_o = v2_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) {v1_q, v2_q} <= 2'b00;
    else if (en) {v1_q, v2_q} <= {in_valid_i, v1_q};
  end

  // ---- Stage 1: y = the numerator + 127 (<= 65152: 16 bits) ----
  logic [7:0] ta;
  assign ta = tex_i[31:24];
  logic [7:0] nta;   // 255 - T_a
  assign nta = 8'd255 - ta;
  logic [47:0] y;    // channel c's y at [16c +: 16]
  always_comb begin
    for (int c = 0; c < 3; c++) begin
      if (env_i == 2'd2)
        y[c*16 +: 16] = 16'(color_i[c*8 +: 8]) * 16'(nta) + 16'(tex_i[c*8 +: 8]) * 16'(ta) + 16'd127;
      else
        y[c*16 +: 16] = 16'(tex_i[c*8 +: 8]) * 16'(color_i[c*8 +: 8]) + 16'd127;
    end
  end
  logic [47:0] y_q;
  logic [23:0] t_q;
  logic replace_q;
  always_ff @(posedge clk_i) begin
    if (en && in_valid_i) begin
      y_q <= y;
      t_q <= tex_i[23:0];
      replace_q <= env_i == 2'd0;
    end
  end

  // ---- Stage 2: y / 255 ----
  logic [23:0] q;
  /* verilator lint_off UNUSEDSIGNAL */
  logic [16:0] yq;  // y + 1 + (y >> 8) < 2^16 for y <= 65152: bits 15..8 are the quotient
  /* verilator lint_on UNUSEDSIGNAL */
  always_comb begin
    for (int c = 0; c < 3; c++) begin
      yq = 17'(y_q[c*16 +: 16]) + 17'd1 + 17'(y_q[c*16 + 8 +: 8]);
      q[c*8 +: 8] = yq[15:8];
    end
  end
  always_ff @(posedge clk_i) begin
    if (en && v1_q) color_o <= replace_q ? t_q : q;
  end
endmodule

`default_nettype wire
