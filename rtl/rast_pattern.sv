// SPDX-License-Identifier: Apache-2.0
// rast_pattern: the P operand of a fill or blit from the 8x8 mono pattern.
//
// - The pattern is 64 bits as written in `pattern HEX16`: row 0 in bits 63:56, most
//   significant bit = leftmost pixel, so pixel (x mod 8, y mod 8) is bit 63 - (8y + x),
//   i.e. bit ~{y, x} of a 6-bit index.
// - Screen-anchored: the caller passes the low three bits of the destination x and y.
// - 1 bits take fg_i (the current colour), 0 bits bg_i (bgcolor). Combinational.
`default_nettype none

module rast_pattern #(
  parameter int Width = 24  // bits of a pixel
) (
  input  wire logic [63:0]      pattern_i,  // 8x8 mono pattern, row 0 in bits 63:56
  input  wire logic [2:0]       x_i,        // destination x mod 8
  input  wire logic [2:0]       y_i,        // destination y mod 8
  input  wire logic [Width-1:0] fg_i,       // colour of 1 bits
  input  wire logic [Width-1:0] bg_i,       // colour of 0 bits
  output      logic [Width-1:0] p_o         // pattern pixel
);
  logic [5:0] bit_c;  // bit index of the pixel in pattern_i
  assign bit_c = ~{y_i, x_i};
  assign p_o   = pattern_i[bit_c] ? fg_i : bg_i;
endmodule

`default_nettype wire
