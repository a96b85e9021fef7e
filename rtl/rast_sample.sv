// SPDX-License-Identifier: Apache-2.0
// rast_sample: raw s.I.F coordinate of a pixel centre, relative to the viewport origin.
//
//   sample = ((p - origin) << F) + 2^(F-1)        (ref: SetupTriangle::sample_x)
//
// p and origin are PixelW-bit unsigned pixel indices. The result is exact in CoordW
// bits for every pixel inside the viewport (the viewport fits the format, see
// docs/fixed-point.md), which is the only place the raster stages evaluate samples.
`default_nettype none

module rast_sample #(
  parameter int PixelW    = 14,  // pixel index bits
  parameter int CoordW    = 24,  // raw coordinate bits (N + 1)
  parameter int CoordFrac = 16   // F
) (
  input  wire logic [PixelW-1:0] p_i,       // pixel column or row
  input  wire logic [PixelW-1:0] origin_i,  // pixel of raw 0 (viewport centre)
  output      logic [CoordW-1:0] s_o        // raw coordinate of the pixel centre
);
  localparam int WideW = PixelW + 1 + CoordW;  // derived: holds (p - origin) << F
  logic signed [WideW-1:0] diff;
  assign diff = WideW'(p_i) - WideW'(origin_i);
  // Narrowing to CoordW bits drops only sign copies (the value fits).
  assign s_o  = CoordW'((diff <<< CoordFrac) + (WideW'(1) <<< (CoordFrac - 1)));
endmodule

`default_nettype wire
