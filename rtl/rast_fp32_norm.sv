// SPDX-License-Identifier: Apache-2.0
// rast_fp32_norm: left-normalises a significand for the binary32 units (rast_fp32_*).
//
// - v_o = v_i << shift_o, shift_o the number of leading zeros of v_i, so v_o's top bit
//   is set; v_i = 0 gives shift_o = 0 and v_o = 0 (callers treat zero apart).
// - Combinational: a priority encoder (leading-one detector) and a barrel shifter.
//   Used on a subnormal operand's 24-bit significand (rast_fp32_unpack) and on the
//   adder's 28-bit sum after a cancellation (rast_fp32_add).
`default_nettype none

module rast_fp32_norm #(
  parameter int W = 24  // significand bits (>= 2)
) (
  input  wire logic [W-1:0]         v_i,      // significand, unsigned
  output      logic [W-1:0]         v_o,      // v_i shifted left until its top bit is set
  output      logic [$clog2(W)-1:0] shift_o   // leading zeros of v_i (0 for v_i = 0)
);
  localparam int CW = $clog2(W);  // derived: shift count bits

  always_comb begin
    shift_o = '0;
    // Scanning upwards, the highest set bit writes last.
    for (int i = 0; i < W; i++) begin
      if (v_i[i]) shift_o = CW'(W - 1 - i);
    end
    v_o = v_i << shift_o;
  end
endmodule

`default_nettype wire
