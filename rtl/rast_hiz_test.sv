// SPDX-License-Identifier: Apache-2.0
// rast_hiz_test: hierarchical Z's tile test (ref: model/ref/hiz.cpp tile_depth_range and
// HizTable::test; docs/depth-culling.md "The tile's depth range", "The test").
//
// - The plane's depth numerator num = E1 z0 + E2 z1 + E0 z2 (the edge opposite each vertex
//   is its weight, as rast_interpolate) at the footprint's four corner pixel centres;
//   nmin, nmax their smallest and largest (num is linear in the sample position).
// - The reference's range is lo = max(min z_k, floor(nmin / A)), hi = min(max z_k,
//   ceil(nmax / A)) (A = area2 > 0), clamped to [-1, 2^D]. No divider: each comparison
//   the test needs is one multiply-compare, exact for integers K and A > 0:
//     lo >= K  <=>  min z_k >= K  or  nmin >= K A      (floor(n / A) >= K <=> n >= K A)
//     hi <= K  <=>  max z_k <= K  or  nmax <= K A      (ceil(n / A) <= K <=> n <= K A)
//   with K in [-1, 2^D] (the clamp keeps every such comparison the exact one).
// - Against the footprint's bounds (Bmin the nearest stored depth, minmax only; Bmax the
//   farthest), depth function f (ref DepthFunc encoding):
//     less:    cull lo >= Bmax,   accept hi <= Bmin - 1
//     lequal:  cull lo >= Bmax+1, accept hi <= Bmin
//     greater: cull hi <= Bmin,   accept lo >= Bmax+1   (minmax only)
//     gequal:  cull hi <= Bmin-1, accept lo >= Bmax     (minmax only)
//   so one multiply against Bmax (+1) and one against Bmin (-1). A cull wins over an
//   accept; another function is not handled (handled_o low: the tile is drawn untested).
// - Widths: num is signed NumW = EdgeW + DepthW + 2 bits (three products of an EdgeW-bit
//   edge value and a DepthW-bit depth); K A fits NumW bits (K <= 2^D, A < 2^AreaW,
//   AreaW = EdgeW - 1). Combinational: the test is in coarse raster's classify cycle.
`default_nettype none

module rast_hiz_test #(
  parameter int CoordW    = 24,  // N + 1
  parameter int CoordFrac = 16,  // F
  parameter int CoefW     = 25,  // N + 2
  parameter int EdgeW     = 49,  // 2N + 3
  parameter int AreaW     = 48,  // 2N + 2
  parameter int DepthW    = 24,  // D = raster.depth_bits
  parameter int PixelW    = 14   // pixel index bits
) (
  input  wire logic                minmax_i,      // depth.hiz = minmax (else max)
  input  wire logic [2:0]          depth_func_i,  // raster.depth_func as ref DepthFunc
  input  wire logic [3*CoefW-1:0]  a_i,           // edge a (rast_tri_setup layout)
  input  wire logic [3*CoefW-1:0]  b_i,           // edge b
  input  wire logic [3*EdgeW-1:0]  c_i,           // edge c
  input  wire logic [AreaW-1:0]    area2_i,       // doubled area, > 0
  input  wire logic [3*DepthW-1:0] z_i,           // vertex depths, unorm, vertex k at [k*DepthW +: DepthW]
  input  wire logic [2*PixelW-1:0] origin_i,      // pixel of raw (0, 0): {y, x}
  input  wire logic [4*PixelW-1:0] fp_i,          // footprint {y1, x1, y0, x0}, half-open, not empty
  input  wire logic [DepthW-1:0]   bound_min_i,   // nearest stored depth of the blocks fp overlaps
  input  wire logic [DepthW-1:0]   bound_max_i,   // farthest
  output      logic                handled_o,     // the function is one the mode tests
  output      logic                cull_o,        // every fragment of the tile fails
  output      logic                accept_o       // every fragment passes (minmax; not culled)
);
  localparam int NumW = EdgeW + DepthW + 2;  // derived: signed depth numerator
  localparam logic [2:0] FLess = 3'd1, FLEqual = 3'd2, FGreater = 3'd4, FGEqual = 3'd5;

  logic [CoordW-1:0] sx [2], sy [2];  // corner pixel centres: x0, x1 - 1; y0, y1 - 1
  rast_sample #(.PixelW(PixelW), .CoordW(CoordW), .CoordFrac(CoordFrac)) u_sx0 (
    .p_i(fp_i[0 +: PixelW]), .origin_i(origin_i[0 +: PixelW]), .s_o(sx[0]));
  rast_sample #(.PixelW(PixelW), .CoordW(CoordW), .CoordFrac(CoordFrac)) u_sx1 (
    .p_i(fp_i[2*PixelW +: PixelW] - 1'b1), .origin_i(origin_i[0 +: PixelW]), .s_o(sx[1]));
  rast_sample #(.PixelW(PixelW), .CoordW(CoordW), .CoordFrac(CoordFrac)) u_sy0 (
    .p_i(fp_i[PixelW +: PixelW]), .origin_i(origin_i[PixelW +: PixelW]), .s_o(sy[0]));
  rast_sample #(.PixelW(PixelW), .CoordW(CoordW), .CoordFrac(CoordFrac)) u_sy1 (
    .p_i(fp_i[3*PixelW +: PixelW] - 1'b1), .origin_i(origin_i[PixelW +: PixelW]), .s_o(sy[1]));

  // Corner k = {j, i}: x sx[i], y sy[j].
  logic signed [NumW-1:0] num [4];
  for (genvar k = 0; k < 4; k++) begin : g_corner
    logic signed [EdgeW-1:0] e [3];
    for (genvar i = 0; i < 3; i++) begin : g_edge
      rast_edge_eval #(.CoordW(CoordW), .CoefW(CoefW), .EdgeW(EdgeW)) u_eval (
        .a_i(a_i[i*CoefW +: CoefW]), .b_i(b_i[i*CoefW +: CoefW]), .c_i(c_i[i*EdgeW +: EdgeW]),
        .x_i(sx[k % 2]), .y_i(sy[k / 2]), .e_o(e[i]));
    end
    always_comb begin
      num[k] = '0;
      for (int v = 0; v < 3; v++)
        num[k] = num[k] + NumW'(e[(v+1)%3]) * $signed({{(NumW - DepthW){1'b0}}, z_i[v*DepthW +: DepthW]});
    end
  end

  logic signed [NumW-1:0] nmin, nmax;
  logic [DepthW-1:0]      zv_min, zv_max;  // the vertex depths' range
  always_comb begin
    nmin = num[0];
    nmax = num[0];
    for (int k = 1; k < 4; k++) begin
      if (num[k] < nmin) nmin = num[k];
      if (num[k] > nmax) nmax = num[k];
    end
    zv_min = z_i[0 +: DepthW];
    zv_max = z_i[0 +: DepthW];
    for (int v = 1; v < 3; v++) begin
      if (z_i[v*DepthW +: DepthW] < zv_min) zv_min = z_i[v*DepthW +: DepthW];
      if (z_i[v*DepthW +: DepthW] > zv_max) zv_max = z_i[v*DepthW +: DepthW];
    end
  end

  // K_lo = Bmax (+1 for lequal, greater), K_hi = Bmin (-1 for less, gequal): signed, D + 2 bits.
  localparam int KW = DepthW + 2;  // derived: -1 .. 2^D
  logic signed [KW-1:0]   k_lo, k_hi;
  logic signed [NumW-1:0] ka_lo, ka_hi;
  logic                   ge_lo, le_hi;  // lo >= K_lo, hi <= K_hi
  assign k_lo = $signed({2'b00, bound_max_i}) + KW'(depth_func_i == FLEqual || depth_func_i == FGreater);
  assign k_hi = $signed({2'b00, bound_min_i}) - KW'(depth_func_i == FLess || depth_func_i == FGEqual);
  assign ka_lo = NumW'(k_lo) * $signed({1'b0, area2_i});
  assign ka_hi = NumW'(k_hi) * $signed({1'b0, area2_i});
  assign ge_lo = $signed({2'b00, zv_min}) >= k_lo || nmin >= ka_lo;
  assign le_hi = $signed({2'b00, zv_max}) <= k_hi || nmax <= ka_hi;

  logic near_func;  // less, lequal: cull on the far bound
  assign near_func = depth_func_i == FLess || depth_func_i == FLEqual;
  assign handled_o = near_func || (minmax_i && (depth_func_i == FGreater || depth_func_i == FGEqual));
  assign cull_o    = handled_o && (near_func ? ge_lo : le_hi);
  assign accept_o  = handled_o && minmax_i && !cull_o && (near_func ? le_hi : ge_lo);
endmodule

`default_nettype wire
