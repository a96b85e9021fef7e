// SPDX-License-Identifier: Apache-2.0
// rast_texture_address: the texels a sample reads on one mip level of W x H texels and
// their byte addresses (docs/texture.md, "Texel addressing and filters", "Memory"; the
// golden arithmetic is ref/texture/texture.h texel_quad and texture_unit.h texel_offset).
//
// Per axis (s with W, t with H; F = TexFrac, B = WeightBits):
//   nearest   i = floor(s W / 2^F)
//   bilinear  xB = floor((s W 2^B - 2^(F+B-1) + 2^(F-1)) / 2^F), i0 = xB >> B, i1 = i0 + 1,
//             alpha = (xB mod 2^B) 2^(8-B)                          (1/256)
// then each index wrapped: repeat i mod n, clamp clamp(i, 0, n - 1), mirror m = i mod 2n,
// m < n ? m : 2n - 1 - m. No divider: with s = q 2^F + r (q = s >>> F, 0 <= r < 2^F),
// i = q n + i', where i' is the same formula on r alone, in [-1, n] (i0' >= -1, i1' <= n;
// nearest [0, n - 1]). So i mod n is i' brought into [0, n) by at most one n; the
// repeat's parity (mirror) is q's low bit, s[F], less one where i' = -1 or n moved it;
// and clamp is n - 1 for q > 0, 0 for q < 0, clamp(i', 0, n - 1) for q = 0 (q n + i'
// with i' in [-1, n] is >= n - 1 or <= 0 there).
//
// Texel (i, j)'s offset in the level, texels, by layout_i (texture.layout):
//   linear  j W + i
//   tiled   (((j >> 2) tiles_x + (i >> 2)) << 4) + ((j & 3) << 2) + (i & 3), tiles_x = ceil(W / 4)
//   morton  i bit k to bit 2k, j bit k to bit 2k + 1
// in bytes << 2 (rgba8888), << 1 (rgb565), << 0 (l8) by format_i (texture.format); the
// address is base_i (the level's first byte) plus it. The four texels are (i0, j0),
// (i1, j0), (i0, j1), (i1, j1), the fetch order; nearest reads the first only.
//
// Pipeline: 4 register stages (1: r x n; 2: indices, weights, wrap; 3: the two rows'
// products; 4: addresses), one sample a cycle; every stage advances while the last is
// empty or taken. Latency 4 cycles.
`default_nettype none

module rast_texture_address #(
  parameter int TexW       = 28,  // texture coordinate s, t: 1 + I + F of interp.texcoord_format, signed
  parameter int TexFrac    = 20,  // F of interp.texcoord_format
  parameter int WeightBits = 8,   // texture.weight_bits: B, 1..8
  parameter int SizeW      = 15,  // a level's side, texels: 1 .. 2^(SizeW-1)
  parameter int AddrW      = 42   // a byte address in the memory system
) (
  input  wire logic                   clk_i,
  input  wire logic                   rst_ni,      // asynchronous reset, active low
  input  wire logic                   in_valid_i,
  output      logic                   in_ready_o,
  input  wire logic signed [TexW-1:0] s_i,         // raw interp.texcoord_format
  input  wire logic signed [TexW-1:0] t_i,
  input  wire logic [SizeW-1:0]       width_i,     // this level's W, H
  input  wire logic [SizeW-1:0]       height_i,
  input  wire logic                   bilinear_i,  // 4 texels and weights; else nearest, 1 texel
  input  wire logic [1:0]             wrap_s_i,    // 0 repeat, 1 clamp, 2 mirror
  input  wire logic [1:0]             wrap_t_i,
  input  wire logic [1:0]             layout_i,    // 0 linear, 1 tiled, 2 morton
  input  wire logic [1:0]             format_i,    // 0 rgba8888, 1 rgb565, 2 l8
  input  wire logic [AddrW-1:0]       base_i,      // the level's byte address
  output      logic                   out_valid_o,
  input  wire logic                   out_ready_i,
  output      logic [4*(SizeW-1)-1:0] i_o,         // i0, i1, i0, i1 (texel k at [k*(SizeW-1) +: SizeW-1])
  output      logic [4*(SizeW-1)-1:0] j_o,         // j0, j0, j1, j1
  output      logic [7:0]             alpha_o,     // weight of i1, /256
  output      logic [7:0]             beta_o,      // weight of j1, /256
  output      logic [4*AddrW-1:0]     addr_o       // texel k's byte address at [k*AddrW +: AddrW]
);
  localparam int F = TexFrac, B = WeightBits;
  localparam int IxW = SizeW - 1;            // a wrapped index, 0 .. 2^(SizeW-1) - 1
  localparam int ProdW = F + SizeW;          // r n, 2^-F texels
  localparam int XW = ProdW + B + 1;         // r n 2^B - 2^(F+B-1) + 2^(F-1), signed
  localparam int PW = 2 * IxW;               // a texel's offset in its level, texels

  if (WeightBits < 1 || WeightBits > 8) begin : g_check_b
    $error("rast_texture_address: WeightBits (%0d) must be in 1..8", WeightBits);
  end
  if (TexW <= TexFrac || TexFrac < 1) begin : g_check_f
    $error("rast_texture_address: TexFrac (%0d) must be in 1..TexW - 1", TexFrac);
  end

  logic en;
  logic v1_q, v2_q, v3_q, v4_q;
  assign en = !v4_q || out_ready_i;
  assign in_ready_o = en;
  assign out_valid_o = v4_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) {v1_q, v2_q, v3_q, v4_q} <= 4'b0000;
    else if (en) {v1_q, v2_q, v3_q, v4_q} <= {in_valid_i, v1_q, v2_q, v3_q};
  end

  // Side data of stages 1 and 2 (the axes' own registers are below).
  logic [SizeW-1:0] w1_q, w2_q;
  logic bil1_q;
  logic [1:0] lay1_q, lay2_q, lay3_q, fmt1_q, fmt2_q, fmt3_q;
  logic [AddrW-1:0] base1_q, base2_q, base3_q;
  always_ff @(posedge clk_i) begin
    if (en && in_valid_i) begin
      w1_q <= width_i;
      bil1_q <= bilinear_i;
      lay1_q <= layout_i;
      fmt1_q <= format_i;
      base1_q <= base_i;
    end
    if (en && v1_q) {w2_q, lay2_q, fmt2_q, base2_q} <= {w1_q, lay1_q, fmt1_q, base1_q};
    if (en && v2_q) {lay3_q, fmt3_q, base3_q} <= {lay2_q, fmt2_q, base2_q};
  end

  // ---- Stages 1 and 2, an axis each: 0 is s (W), 1 is t (H) ----
  // The wrapped index of q n + ip (ip in [-1, n]; see the top).
  function automatic logic [IxW-1:0] wrap(input logic signed [SizeW:0] ip, input logic [SizeW-1:0] n,
                                          input logic [1:0] mode, input logic qneg, input logic qzero,
                                          input logic qodd);
    logic [IxW-1:0] off, last, clamped;  // i mod n; n - 1; clamp(i', 0, n - 1)
    logic odd;                          // the repeat of i is odd (mirror)
    last = IxW'(n - 1'b1);
    if (ip < 0) begin
      off = last;
      odd = !qodd;
      clamped = '0;
    end else if (ip >= $signed({1'b0, n})) begin
      off = '0;
      odd = !qodd;
      clamped = last;
    end else begin
      off = IxW'(ip);
      odd = qodd;
      clamped = off;
    end
    case (mode)
      2'd1: wrap = qneg ? '0 : !qzero ? last : clamped;
      2'd2: wrap = odd ? last - off : off;
      default: wrap = off;
    endcase
  endfunction

  logic [2*IxW-1:0] ix0_q, ix1_q;  // wrapped i0, i1 of axis a at [a*IxW +: IxW] (j0, j1 at a = 1)
  logic [15:0] wt_q;               // alpha, beta at [a*8 +: 8]
  for (genvar a = 0; a < 2; a++) begin : g_axis
    logic signed [TexW-1:0] c;
    logic [SizeW-1:0] n_in;
    logic [1:0] wrap_in;
    assign c = a == 0 ? s_i : t_i;
    assign n_in = a == 0 ? width_i : height_i;
    assign wrap_in = a == 0 ? wrap_s_i : wrap_t_i;

    logic [ProdW-1:0] prod_q;    // r n
    logic [SizeW-1:0] n1_q;
    logic [1:0] wrap1_q;
    logic qneg_q, qzero_q, qodd_q;  // q < 0, q = 0, q odd
    always_ff @(posedge clk_i) begin
      if (en && in_valid_i) begin
        prod_q <= ProdW'(c[F-1:0]) * ProdW'(n_in);
        n1_q <= n_in;
        wrap1_q <= wrap_in;
        qneg_q <= c[TexW-1];
        qzero_q <= c[TexW-1:F] == '0;
        qodd_q <= c[F];
      end
    end

    // i0' and i1' (signed, SizeW + 1 bits: -1 .. n) and the weight.
    logic signed [XW-1:0] xb;
    logic signed [SizeW:0] i0p, i1p;
    logic [7:0] wt;
    always_comb begin
      xb = (XW'(prod_q) <<< B) + XW'(1 << (F - 1)) - (XW'(1) <<< (F + B - 1));
      xb = xb >>> F;  // floor(x 2^B + 1/2)
      if (bil1_q) begin
        i0p = (SizeW + 1)'(xb >>> B);
        wt = 8'(xb[B-1:0]) << (8 - B);
      end else begin
        i0p = (SizeW + 1)'(prod_q >> F);
        wt = 8'd0;
      end
      i1p = i0p + 1'b1;
    end

    always_ff @(posedge clk_i) begin
      if (en && v1_q) begin
        ix0_q[a*IxW +: IxW] <= wrap(i0p, n1_q, wrap1_q, qneg_q, qzero_q, qodd_q);
        ix1_q[a*IxW +: IxW] <= wrap(i1p, n1_q, wrap1_q, qneg_q, qzero_q, qodd_q);
        wt_q[a*8 +: 8] <= wt;
      end
    end
  end

  // ---- Stage 3: the two rows' products (linear j W, tiled (j >> 2) tiles_x) ----
  logic [IxW-1:0] i0_3q, i1_3q, j0_3q, j1_3q;
  logic [7:0] alpha_3q, beta_3q;
  logic [PW-1:0] row0_q, row1_q;
  logic tiled2;
  logic [SizeW-1:0] mul_b;
  logic [IxW-1:0] j0, j1;
  logic [IxW-1:0] jr0, jr1;         // the rows' multiplicands: j, or j >> 2 tiled
  assign {j0, j1} = {ix0_q[IxW +: IxW], ix1_q[IxW +: IxW]};
  assign jr0 = tiled2 ? j0 >> 2 : j0;
  assign jr1 = tiled2 ? j1 >> 2 : j1;
  assign tiled2 = lay2_q == 2'd1;
  assign mul_b = tiled2 ? (w2_q + SizeW'(3)) >> 2 : w2_q;  // tiles_x or W
  always_ff @(posedge clk_i) begin
    if (en && v2_q) begin
      {i0_3q, i1_3q, j0_3q, j1_3q} <= {ix0_q[0 +: IxW], ix1_q[0 +: IxW], j0, j1};
      {alpha_3q, beta_3q} <= {wt_q[7:0], wt_q[15:8]};
      row0_q <= PW'(jr0) * PW'(mul_b);
      row1_q <= PW'(jr1) * PW'(mul_b);
    end
  end

  // ---- Stage 4: the four texels' addresses ----
  function automatic logic [PW-1:0] morton(input logic [IxW-1:0] x, input logic [IxW-1:0] y);
    for (int k = 0; k < IxW; k++) begin
      morton[2*k] = x[k];
      morton[2*k+1] = y[k];
    end
  endfunction

  logic [4*PW-1:0] p;          // texel k's offset in texels at [k*PW +: PW]
  logic [4*AddrW-1:0] addr;
  logic [IxW-1:0] x, y;
  logic [PW-1:0] row;
  always_comb begin
    p = '0;
    addr = '0;
    for (int k = 0; k < 4; k++) begin
      x = (k & 1) != 0 ? i1_3q : i0_3q;
      y = (k & 2) != 0 ? j1_3q : j0_3q;
      row = (k & 2) != 0 ? row1_q : row0_q;
      case (lay3_q)
        2'd1: p[k*PW +: PW] = ((row + PW'(x[IxW-1:2])) << 4) | PW'({y[1:0], x[1:0]});
        2'd2: p[k*PW +: PW] = morton(x, y);
        default: p[k*PW +: PW] = row + PW'(x);
      endcase
      addr[k*AddrW +: AddrW] = base3_q + (AddrW'(p[k*PW +: PW]) << (fmt3_q == 2'd0 ? 2 : fmt3_q == 2'd1 ? 1 : 0));
    end
  end
  always_ff @(posedge clk_i) begin
    if (en && v3_q) begin
      i_o <= {i1_3q, i0_3q, i1_3q, i0_3q};
      j_o <= {j1_3q, j1_3q, j0_3q, j0_3q};
      alpha_o <= alpha_3q;
      beta_o <= beta_3q;
      addr_o <= addr;
    end
  end
endmodule

`default_nettype wire
