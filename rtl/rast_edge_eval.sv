// SPDX-License-Identifier: Apache-2.0
// rast_edge_eval: one edge function E(x, y) = a x + b y + c at one raw sample point.
//
// - a, b: CoefW = N + 2 bits; c and E: EdgeW = 2N + 3 bits; x, y: CoordW = N + 1 bits,
//   all signed two's complement (docs/fixed-point.md, "Datapath widths").
// - The products and the sum wrap modulo 2^EdgeW. That is exact: E at any sample of
//   the clipped bounding box is known to fit in EdgeW bits, and two's-complement
//   addition is exact modulo 2^EdgeW (fixed-point.md, "Derivation of the edge width").
// - Combinational; used by the coarse raster (footprint corners), the fine raster (one
//   per sample lane) and the interpolator (barycentric weights).
`default_nettype none

module rast_edge_eval #(
  parameter int CoordW = 24,  // sample coordinate bits (N + 1)
  parameter int CoefW  = 25,  // edge coefficient bits (N + 2)
  parameter int EdgeW  = 49   // edge value bits (2N + 3)
) (
  input  wire logic signed [CoefW-1:0]  a_i,  // dE/dx per raw unit
  input  wire logic signed [CoefW-1:0]  b_i,  // dE/dy per raw unit
  input  wire logic signed [EdgeW-1:0]  c_i,  // E(0, 0)
  input  wire logic signed [CoordW-1:0] x_i,  // sample x, raw, relative to the origin
  input  wire logic signed [CoordW-1:0] y_i,  // sample y, raw
  output      logic signed [EdgeW-1:0]  e_o   // E(x, y), exact
);
  // Sign-extend every operand to the result width so the multiply is EdgeW x EdgeW.
  logic signed [EdgeW-1:0] a_ext, b_ext, x_ext, y_ext;
  assign a_ext = {{(EdgeW - CoefW){a_i[CoefW-1]}}, a_i};
  assign b_ext = {{(EdgeW - CoefW){b_i[CoefW-1]}}, b_i};
  assign x_ext = {{(EdgeW - CoordW){x_i[CoordW-1]}}, x_i};
  assign y_ext = {{(EdgeW - CoordW){y_i[CoordW-1]}}, y_i};
  assign e_o   = a_ext * x_ext + b_ext * y_ext + c_i;
endmodule

`default_nettype wire
