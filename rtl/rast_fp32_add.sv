// SPDX-License-Identifier: Apache-2.0
// rast_fp32_add: IEEE 754 binary32 addition, f = a + b, round to nearest even.
//
// - Bit-exact with a C++ float sum on x86-64 SSE without flush-to-zero or
//   denormals-are-zero: subnormal operands and results, overflow to infinity, signed
//   zeros (x + (-x) = +0; -0 + -0 = -0; x + 0 = x). Subtraction is a + b with b's sign
//   bit flipped, which IEEE defines to be the same operation.
// - NaN: any NaN operand, and inf + (-inf), give rast_fp32_round's one quiet NaN.
// - Datapath (the classic guard/round/sticky adder): the larger magnitude's significand
//   and the smaller one, aligned to it, in 27 bits each (24 + 3 below: guard, round and
//   a sticky bit that ORs every bit the alignment shifts out). A sum or difference in 28
//   bits is then normalised (rast_fp32_norm: a carry shifts right by one, a cancellation
//   left) and rounded once (rast_fp32_round). The sticky bit never misleads the rounding:
//   an alignment of 0 or 1 loses no bit, and after a larger one a difference loses at
//   most one leading bit, so the sticky bit stays below the guard bit.
// - Combinational.
`default_nettype none

module rast_fp32_add (
  input  wire logic [31:0] a_i,  // binary32 operand
  input  wire logic [31:0] b_i,  // binary32 operand
  output      logic [31:0] f_o   // binary32 a + b
);

  logic              sa, sb, za, zb, ia, ib, na, nb;  // signs and classes
  logic signed [9:0] ea, eb;                          // unbiased exponents
  logic [23:0]       ma, mb;                          // normalised significands, 1.23
  rast_fp32_unpack u_a (.f_i(a_i), .sign_o(sa), .exp_o(ea), .sig_o(ma), .zero_o(za), .inf_o(ia), .nan_o(na));
  rast_fp32_unpack u_b (.f_i(b_i), .sign_o(sb), .exp_o(eb), .sig_o(mb), .zero_o(zb), .inf_o(ib), .nan_o(nb));

  // The larger magnitude is the base; the other is aligned to its exponent.
  logic              a_big;     // |a| >= |b|
  logic              sign;      // the base's sign: the sum's, unless it cancels to 0
  logic signed [9:0] e_big;     // the base's exponent
  logic [9:0]        diff;      // e_big - the other's exponent (0..276)
  logic [26:0]       big, other, aligned;  // 1.26 fixed point at e_big
  logic [4:0]        shift;     // diff clamped to 27 (everything shifted out)
  logic              lost;      // nonzero bits shifted out of other
  logic [27:0]       sum;       // big +- aligned, 2.26 fixed point at e_big
  logic [27:0]       sig;       // sum normalised, 1.27
  logic [4:0]        lz;        // its leading zeros (0: a carry into bit 27)
  logic signed [9:0] exp;       // unbiased exponent of sig's top bit
  logic [31:0]       rounded;   // the finite nonzero sum, rounded
  assign a_big   = (ea > eb) || (ea == eb && ma >= mb);
  assign sign    = a_big ? sa : sb;
  assign e_big   = a_big ? ea : eb;
  assign diff    = 10'(a_big ? ea - eb : eb - ea);
  assign big     = {a_big ? ma : mb, 3'd0};
  assign other   = {a_big ? mb : ma, 3'd0};
  assign shift   = (diff > 10'd27) ? 5'd27 : 5'(diff);
  assign lost    = ((other >> shift) << shift) != other;
  assign aligned = (other >> shift) | {26'd0, lost};
  assign sum     = (sa ^ sb) ? {1'b0, big} - {1'b0, aligned} : {1'b0, big} + {1'b0, aligned};

  rast_fp32_norm #(.W(28)) u_norm (.v_i(sum), .v_o(sig), .shift_o(lz));
  assign exp = e_big + 10'sd1 - $signed({5'd0, lz});
  logic nan;  // the result is NaN
  assign nan = na || nb || (ia && ib && sa != sb);
  rast_fp32_round #(.SigW(28)) u_round (.sign_i(sign), .exp_i(exp), .sig_i(sig), .sticky_i(1'b0), .nan_i(nan), .f_o(rounded));

  always_comb begin
    if (nan) f_o = rounded;  // rast_fp32_round's NaN
    else if (ia) f_o = a_i;
    else if (ib) f_o = b_i;
    else if (za && zb) f_o = {sa && sb, 31'd0};  // +0 unless both are -0
    else if (za) f_o = b_i;
    else if (zb) f_o = a_i;
    else if (sum == '0) f_o = 32'd0;  // exact cancellation: +0 when rounding to nearest
    else f_o = rounded;
  end
endmodule

`default_nettype wire
