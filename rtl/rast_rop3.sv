// SPDX-License-Identifier: Apache-2.0
// rast_rop3: the ternary raster operation, bit by bit over a pixel.
//
// - Result bit k = bit number (P[k]<<2 | S[k]<<1 | D[k]) of the 8-bit code (the notes' truth
//   table; e.g. F0 = PATCOPY, CC = SRCCOPY, AA = D, 66 = SRCINVERT).
// - reads_d_o / reads_s_o tell the blit engine whether the code depends on D (read-modify-write
//   needed) or S (a source read needed).
// Purely combinational.
`default_nettype none

module rast_rop3 #(
  parameter int Width = 24  // bits of a pixel (all colour channels; alpha is not combined)
) (
  input  wire logic [7:0]       code_i,     // ROP3 code
  input  wire logic [Width-1:0] p_i,        // pattern pixel
  input  wire logic [Width-1:0] s_i,        // source pixel
  input  wire logic [Width-1:0] d_i,        // destination pixel
  output      logic [Width-1:0] r_o,        // result pixel
  output      logic             reads_d_o,  // the result depends on D
  output      logic             reads_s_o   // the result depends on S
);
  // The same 8:1 mux a bit, as a tree of word-wide 2:1 selects: by D (code bits in
  // pairs), then S, then P. (Was a generate of Width one-bit lookups
  // code_i[{p_i[k], s_i[k], d_i[k]}]: the same circuit, but a verilated model evaluated
  // it as Width bit extracts; this is 7 word selects.)
  logic [Width-1:0] by_d [4];  // index {p, s}: code bit {p, s, D[k]} at bit k
  logic [Width-1:0] by_s [2];  // index p: code bit {p, S[k], D[k]}
  for (genvar ps = 0; ps < 4; ps++) begin : g_d
    assign by_d[ps] = (d_i & {Width{code_i[2*ps+1]}}) | (~d_i & {Width{code_i[2*ps]}});
  end
  for (genvar pp = 0; pp < 2; pp++) begin : g_s
    assign by_s[pp] = (s_i & by_d[2*pp+1]) | (~s_i & by_d[2*pp]);
  end
  assign r_o = (p_i & by_s[1]) | (~p_i & by_s[0]);
  // Code bits with D = 1 are the odd ones; with S = 1 bits 2, 3, 6, 7.
  assign reads_d_o = ((code_i >> 1) & 8'h55) != (code_i & 8'h55);
  assign reads_s_o = ((code_i >> 2) & 8'h33) != (code_i & 8'h33);
endmodule

`default_nettype wire
