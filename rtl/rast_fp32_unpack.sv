// SPDX-License-Identifier: Apache-2.0
// rast_fp32_unpack: an IEEE 754 binary32 operand of the front end's arithmetic units
// (rast_fp32_mul, rast_fp32_add, rast_fp32_recip) split into its class, sign, unbiased
// exponent and normalised significand.
//
// - A finite nonzero operand is (-1)^sign_o * sig_o * 2^(exp_o - 23): sig_o has 24 bits
//   with its top bit set (1.23 fixed point), exp_o is signed, 10 bits: -126..127 for a
//   normal operand, -149..-127 for a subnormal one, whose significand is normalised here
//   (gradual underflow: subnormal inputs are values, not zeros, as SSE without DAZ).
// - zero_o, inf_o, nan_o classify the operand (exp_o and sig_o are then meaningless).
// - Combinational.
`default_nettype none

module rast_fp32_unpack (
  input  wire logic [31:0]       f_i,     // binary32 operand
  output      logic              sign_o,  // sign bit
  output      logic signed [9:0] exp_o,   // unbiased exponent of sig_o's top bit
  output      logic [23:0]       sig_o,   // normalised significand, 1.23
  output      logic              zero_o,  // +0 or -0
  output      logic              inf_o,   // +inf or -inf
  output      logic              nan_o    // any NaN
);
  logic [7:0]  biased;    // exponent field
  logic [22:0] frac;      // fraction field
  logic [23:0] sub_sig;   // a subnormal's significand, normalised
  logic [4:0]  sub_lz;    // its leading zeros in 0.23 form (1..23)
  assign {sign_o, biased, frac} = f_i;

  rast_fp32_norm #(.W(24)) u_norm (.v_i({1'b0, frac}), .v_o(sub_sig), .shift_o(sub_lz));

  assign zero_o = biased == 8'd0 && frac == 23'd0;
  assign inf_o  = biased == 8'hFF && frac == 23'd0;
  assign nan_o  = biased == 8'hFF && frac != 23'd0;
  // Normal: 1.frac * 2^(biased - 127). Subnormal: 0.frac * 2^-126, normalised by sub_lz.
  assign exp_o = (biased != 8'd0) ? $signed({2'b00, biased}) - 10'sd127 : -10'sd126 - $signed({5'b0, sub_lz});
  assign sig_o = (biased != 8'd0) ? {1'b1, frac} : sub_sig;
endmodule

`default_nettype wire
