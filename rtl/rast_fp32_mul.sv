// SPDX-License-Identifier: Apache-2.0
// rast_fp32_mul: IEEE 754 binary32 multiplication, f = a * b, round to nearest even.
//
// - Bit-exact with a C++ float product on x86-64 SSE without flush-to-zero or
//   denormals-are-zero: subnormal operands and results (gradual underflow), overflow to
//   infinity, signed zeros (the sign is always sign_a ^ sign_b).
// - NaN: any NaN operand, and inf * 0, give rast_fp32_round's one quiet NaN.
// - Datapath: the 24 x 24-bit product of the normalised significands (rast_fp32_unpack)
//   is exact in 48 bits, in [1, 4) as 2.46 fixed point; a one-bit normalisation puts its
//   leading 1 on top, and rast_fp32_round rounds it once (no sticky bit: nothing was
//   dropped before rounding).
// - Combinational.
`default_nettype none

module rast_fp32_mul (
  input  wire logic [31:0] a_i,  // binary32 operand
  input  wire logic [31:0] b_i,  // binary32 operand
  output      logic [31:0] f_o   // binary32 a * b
);

  logic              sa, sb, za, zb, ia, ib, na, nb;  // signs and classes
  logic signed [9:0] ea, eb;                          // unbiased exponents
  logic [23:0]       ma, mb;                          // normalised significands, 1.23
  rast_fp32_unpack u_a (.f_i(a_i), .sign_o(sa), .exp_o(ea), .sig_o(ma), .zero_o(za), .inf_o(ia), .nan_o(na));
  rast_fp32_unpack u_b (.f_i(b_i), .sign_o(sb), .exp_o(eb), .sig_o(mb), .zero_o(zb), .inf_o(ib), .nan_o(nb));

  logic              sign;      // sign of every non-NaN result
  logic [47:0]       product;   // ma * mb, 2.46 fixed point in [1, 4)
  logic [47:0]       sig;       // product normalised, 1.47
  logic signed [9:0] exp;       // unbiased exponent of sig's top bit (-298..255)
  logic [31:0]       rounded;   // the finite product, rounded
  assign sign    = sa ^ sb;
  assign product = ma * mb;
  assign sig     = product[47] ? product : {product[46:0], 1'b0};
  assign exp     = ea + eb + (product[47] ? 10'sd1 : 10'sd0);

  logic nan;  // the result is NaN
  assign nan = na || nb || (ia && zb) || (za && ib);
  rast_fp32_round #(.SigW(48)) u_round (.sign_i(sign), .exp_i(exp), .sig_i(sig), .sticky_i(1'b0), .nan_i(nan), .f_o(rounded));

  always_comb begin
    if (nan) f_o = rounded;  // rast_fp32_round's NaN
    else if (ia || ib) f_o = {sign, 8'hFF, 23'd0};
    else if (za || zb) f_o = {sign, 31'd0};
    else f_o = rounded;
  end
endmodule

`default_nettype wire
