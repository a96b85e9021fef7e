// SPDX-License-Identifier: Apache-2.0
// rast_fp32_recip: IEEE 754 binary32 reciprocal, f = 1 / w, correctly rounded (round to
// nearest even): bit-exact with the C++ float division 1.0f / w on x86-64 SSE without
// flush-to-zero or denormals-are-zero.
//
// - Specials: 1 / +-0 = +-inf, 1 / +-inf = +-0, NaN in gives rast_fp32_round's one
//   quiet NaN. Overflow: 1 / w for |w| <= 2^-128 (a subnormal w) is +-inf.
//   Underflow: |w| > 2^126 gives a subnormal result, rounded once (gradual underflow).
// - Datapath: w = m * 2^e with m the normalised significand (1.23, rast_fp32_unpack),
//   so 1 / w = (1 / m) * 2^-e. The digit recurrence (radix-2 restoring division) of
//   2^48 by m_int = m * 2^23 (24 bits, in [2^23, 2^24)) gives Q = floor(2^48 / m_int)
//   in (2^24, 2^25], one quotient bit a step over 26 steps, each a 25-bit compare and
//   subtract of the partial remainder R (R < m_int); R = 0 at the end says whether the
//   quotient is exact. Q = 2^25 only for m = 1 (w a power of two: exactly 2^-e);
//   otherwise Q has 25 significant bits, 24 to keep and a guard bit, and the remainder
//   is the sticky bit, so rast_fp32_round rounds the exact quotient correctly, with no
//   Newton iteration or error bound to argue.
// - Combinational: 26 subtract-and-select steps in a chain (the unit's critical path;
//   rast_front_end_xform gives it a pipeline stage of its own).
`default_nettype none

module rast_fp32_recip (
  input  wire logic [31:0] w_i,  // binary32 divisor
  output      logic [31:0] f_o   // binary32 1 / w
);
  localparam int QW = 26;  // quotient bits: floor(2^48 / m_int) <= 2^25

  logic              sw, zw, iw, nw;  // sign and class
  logic signed [9:0] ew;              // unbiased exponent (-149..127)
  logic [23:0]       mw;              // normalised significand m_int
  rast_fp32_unpack u_w (.f_i(w_i), .sign_o(sw), .exp_o(ew), .sig_o(mw), .zero_o(zw), .inf_o(iw), .nan_o(nw));

  // Restoring division of 2^48 by mw: the dividend's leading part 2^48 >> QW = 2^22 is
  // below mw (>= 2^23), and every bit brought down after it is 0.
  logic [QW-1:0] q;    // quotient floor(2^48 / mw)
  logic [23:0]   rem;  // remainder 2^48 - q * mw
  always_comb begin
    logic [24:0] t;  // 2 R: < 2 mw < 2^25
    rem = 24'h40_0000;  // 2^22
    q = '0;
    for (int i = QW - 1; i >= 0; i--) begin
      t = {rem, 1'b0};
      if (t >= {1'b0, mw}) begin
        t = t - {1'b0, mw};
        q[i] = 1'b1;
      end
      rem = t[23:0];
    end
  end

  // 1 / w = Q * 2^(-e - 25): Q = 2^25 is exactly 2^-e; otherwise Q's leading 1 is bit 24
  // and the result's exponent -e - 1.
  logic [QW-1:0]     sig;      // Q normalised, 1.25
  logic signed [9:0] exp;      // unbiased exponent of sig's top bit (-128..149)
  logic [31:0]       rounded;  // the finite nonzero reciprocal, rounded
  assign sig = q[QW-1] ? q : {q[QW-2:0], 1'b0};
  assign exp = q[QW-1] ? -ew : -ew - 10'sd1;
  logic nan;  // the result is NaN
  assign nan = nw;
  rast_fp32_round #(.SigW(QW)) u_round (.sign_i(sw), .exp_i(exp), .sig_i(sig), .sticky_i(rem != '0), .nan_i(nan), .f_o(rounded));

  always_comb begin
    if (nan) f_o = rounded;  // rast_fp32_round's NaN
    else if (zw) f_o = {sw, 8'hFF, 23'd0};
    else if (iw) f_o = {sw, 31'd0};
    else f_o = rounded;
  end
endmodule

`default_nettype wire
