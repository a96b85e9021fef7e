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
  // The same function as a sum of minterms over whole words: code bit m = {p, s, d}
  // contributes the bits where P, S and D equal m's. (Was a generate of Width one-bit
  // lookups code_i[{p_i[k], s_i[k], d_i[k]}]: the same 8:1 mux a bit in hardware, but
  // a verilated model evaluated it as Width bit extracts; this is 8 word operations.)
  always_comb begin
    r_o = '0;
    for (int m = 0; m < 8; m++)
      if (code_i[m])
        r_o = r_o | (((m & 4) != 0 ? p_i : ~p_i) & ((m & 2) != 0 ? s_i : ~s_i) & ((m & 1) != 0 ? d_i : ~d_i));
  end
  // Code bits with D = 1 are the odd ones; with S = 1 bits 2, 3, 6, 7.
  assign reads_d_o = ((code_i >> 1) & 8'h55) != (code_i & 8'h55);
  assign reads_s_o = ((code_i >> 2) & 8'h33) != (code_i & 8'h33);
endmodule

`default_nettype wire
