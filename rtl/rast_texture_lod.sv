// SPDX-License-Identifier: Apache-2.0
// rast_texture_lod: the texture unit's level of detail (docs/texture.md, "Level of
// detail"; the golden arithmetic is ref/texture/texture.h texture_lod and choose_levels):
// from a 2x2 quad's coarse texture-coordinate derivatives (raw interp.texcoord_format
// units) and the level-0 size W x H, the mip levels a sample reads and the trilinear
// weight of the second.
//
//   du/dx = |ds/dx| W, dv/dx = |dt/dx| H (and dy alike)        2^-F texels
//   len(a, b) = max(a, b) + (min(a, b) >> 1)
//   rho = max(len(du/dx, dv/dx), len(du/dy, dv/dy))
//   lambda = 256 n + (the 8 bits below the leading one) - 256 F   (s.8; rho = 0: -infinity)
//   l = clamp(lambda + bias, 0, 256 (levels - 1))
//   nearest, bilinear: level0 = level1 = (l + 127) >> 8, frac 0
//   trilinear: level0 = l >> 8, frac = l & 255, level1 = frac ? level0 + 1 : level0
// (l & 255 != 0 implies l < 256 (levels - 1), so level0 + 1 is a level: no clamp.)
// With levels = 1 (mipmap off) l is 0 whatever lambda, as the reference's lambda = 0.
//
// Pipeline: 3 register stages, one quad a cycle; every stage advances together while the
// last is empty or taken (in_ready_o = that enable). Latency 3 cycles.
`default_nettype none

module rast_texture_lod #(
  parameter int TexW    = 28,  // texture coordinate s, t: 1 + I + F of interp.texcoord_format, signed
  parameter int TexFrac = 20,  // F of interp.texcoord_format
  parameter int SizeW   = 15,  // a texture side, texels: 1 .. 2^(SizeW-1)
  parameter int LevelW  = 4,   // a mip level index (levels of a 2^(SizeW-1) side: SizeW)
  parameter int BiasW   = 14   // texlod_bias in s.8: 256 x [-16, 16], signed
) (
  input  wire logic                    clk_i,
  input  wire logic                    rst_ni,        // asynchronous reset, active low
  input  wire logic                    in_valid_i,
  output      logic                    in_ready_o,
  input  wire logic signed [TexW:0]    dsdx_i,        // coarse derivatives: differences of two
  input  wire logic signed [TexW:0]    dtdx_i,        //   TexW-bit coordinates, TexW + 1 bits
  input  wire logic signed [TexW:0]    dsdy_i,
  input  wire logic signed [TexW:0]    dtdy_i,
  input  wire logic [SizeW-1:0]        width_i,       // level 0, texels
  input  wire logic [SizeW-1:0]        height_i,
  input  wire logic [LevelW-1:0]       levels_i,      // levels sampled: the chain's, 1 with mipmap off
  input  wire logic signed [BiasW-1:0] bias_i,        // s.8
  input  wire logic                    trilinear_i,   // texfilter trilinear
  output      logic                    out_valid_o,
  input  wire logic                    out_ready_i,
  output      logic [LevelW-1:0]       level0_o,
  output      logic [LevelW-1:0]       level1_o,      // = level0_o: one level
  output      logic [7:0]              frac_o         // weight of level1, /256
);
  localparam int MagW = TexW + 1;             // |derivative| <= 2^TexW
  localparam int ProdW = MagW + SizeW;        // |d| x side, 2^-F texels
  localparam int RhoW = ProdW + 1;            // max + min / 2 < 2^(ProdW + 1)
  localparam int NW = $clog2(RhoW);           // the leading one's position
  localparam int LW = NW + 8 + 2;             // signed s.8 lambda, bias and clamp: headroom

  if (RhoW < 9) begin : g_check
    $error("rast_texture_lod: TexW + SizeW too small for an 8-bit log2 fraction");
  end

  logic en;  // every stage advances
  logic v1_q, v2_q, v3_q;
  assign en = !v3_q || out_ready_i;
  assign in_ready_o = en;
  assign out_valid_o = v3_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) {v1_q, v2_q, v3_q} <= 3'b000;
    else if (en) {v1_q, v2_q, v3_q} <= {in_valid_i, v1_q, v2_q};
  end

  function automatic logic [MagW-1:0] mag(input logic signed [TexW:0] d);
    mag = d[TexW] ? MagW'(-d) : MagW'(d);
  endfunction

  function automatic logic [RhoW-1:0] len(input logic [ProdW-1:0] a, input logic [ProdW-1:0] b);
    len = (a > b) ? RhoW'(a) + (RhoW'(b) >> 1) : RhoW'(b) + (RhoW'(a) >> 1);
  endfunction

  // ---- Stage 1: the four products |d| x side ----
  logic [ProdW-1:0] dux_q, dvx_q, duy_q, dvy_q;
  logic [LevelW-1:0] levels1_q, levels2_q;
  logic signed [BiasW-1:0] bias1_q, bias2_q;
  logic tri1_q, tri2_q;
  always_ff @(posedge clk_i) begin
    if (en && in_valid_i) begin
      dux_q <= ProdW'(mag(dsdx_i)) * ProdW'(width_i);
      dvx_q <= ProdW'(mag(dtdx_i)) * ProdW'(height_i);
      duy_q <= ProdW'(mag(dsdy_i)) * ProdW'(width_i);
      dvy_q <= ProdW'(mag(dtdy_i)) * ProdW'(height_i);
      levels1_q <= levels_i;
      bias1_q <= bias_i;
      tri1_q <= trilinear_i;
    end
  end

  // ---- Stage 2: rho ----
  logic [RhoW-1:0] lx, ly, rho_q;
  assign lx = len(dux_q, dvx_q);
  assign ly = len(duy_q, dvy_q);
  always_ff @(posedge clk_i) begin
    if (en && v1_q) begin
      rho_q <= (lx > ly) ? lx : ly;
      levels2_q <= levels1_q;
      bias2_q <= bias1_q;
      tri2_q <= tri1_q;
    end
  end

  // ---- Stage 3: log2, bias, clamp, the levels ----
  logic [NW-1:0] n;           // floor(log2 rho)
  /* verilator lint_off UNUSEDSIGNAL */
  logic [RhoW-1:0] norm;      // rho shifted so that its leading one is the top bit (8 bits below it read)
  /* verilator lint_on UNUSEDSIGNAL */
  logic signed [LW-1:0] lambda, l, top;
  logic [LevelW-1:0] k_near, k_tri;
  always_comb begin
    n = '0;
    for (int b = 0; b < RhoW; b++)
      if (rho_q[b]) n = NW'(b);
    norm = rho_q << (NW'(RhoW - 1) - n);
    lambda = (LW'(n) <<< 8) + LW'(norm[RhoW-2 -: 8]) - LW'(TexFrac * 256) + LW'(bias2_q);
    top = (LW'(levels2_q) - LW'(1)) <<< 8;
    // rho = 0: lambda is -infinity, clamped to 0.
    if (rho_q == '0 || lambda < 0) l = '0;
    else if (lambda > top) l = top;
    else l = lambda;
    k_near = LevelW'((l + LW'(127)) >>> 8);
    k_tri = LevelW'(l >>> 8);
  end
  always_ff @(posedge clk_i) begin
    if (en && v2_q) begin
      if (tri2_q) begin
        level0_o <= k_tri;
        level1_o <= (l[7:0] != 8'd0) ? k_tri + 1'b1 : k_tri;
        frac_o <= l[7:0];
      end else begin
        level0_o <= k_near;
        level1_o <= k_near;
        frac_o <= 8'd0;
      end
    end
  end
endmodule

`default_nettype wire
