// SPDX-License-Identifier: Apache-2.0
// rast_fp32_round: rounds an exact (or sticky-marked) result of the binary32 units to
// IEEE 754 binary32, round to nearest, ties to even.
//
// - The value is (-1)^sign_i * sig_i * 2^(exp_i - (SigW - 1)) plus, when sticky_i is
//   set, some nonzero amount below sig_i's last bit: sig_i's top bit is set (1.(SigW-1)
//   fixed point) or sig_i = 0, which gives a zero of sign sign_i (sticky_i must be 0).
// - Gradual underflow: below 2^-126 the significand is first shifted right to the
//   subnormal position (the bits shifted out join the sticky bit), then rounded once,
//   as x86-64 SSE without flush-to-zero; a subnormal that rounds up to 2^-126 becomes
//   the smallest normal through the carry into the exponent field.
// - Overflow: exp_i > 127, or a rounding carry out of 2^127 * (2 - 2^-23), gives an
//   infinity of sign sign_i (round to nearest never saturates at the largest finite).
// - Round-and-pack as one addition: {exponent field - 1, 0} + 24-bit significand (its
//   leading 1 adds the missing exponent unit) + the round-up bit, so a significand or a
//   subnormal rounding up to the next binade carries into the exponent by itself.
// - nan_i: the result is NaN (the caller's special cases); every unit returns this one
//   quiet NaN, 0x7FC00000 (SSE would return the first NaN operand quieted, or 0xFFC00000
//   for an invalid operation; callers and tests treat every NaN as one value).
// - Combinational.
`default_nettype none

module rast_fp32_round #(
  parameter int SigW = 26  // significand bits in (>= 26: 24 kept, a guard bit, a sticky bit)
) (
  input  wire logic              sign_i,    // sign of the result
  input  wire logic signed [9:0] exp_i,     // unbiased exponent of sig_i's top bit
  input  wire logic [SigW-1:0]   sig_i,     // significand, top bit set, or 0
  input  wire logic              sticky_i,  // nonzero bits below sig_i
  input  wire logic              nan_i,     // the result is NaN
  output      logic [31:0]       f_o        // binary32 result
);
  localparam int DW = $clog2(SigW + 1);  // derived: bits of the subnormal shift (0..SigW)
  localparam logic [31:0] QNaN = 32'h7FC0_0000;  // the one NaN of the binary32 units

  // Elaboration-time check: 24 kept bits, a guard bit and at least one sticky bit.
  if (SigW < 26) begin : g_check_width
    $error("rast_fp32_round: SigW (%0d) must be at least 26", SigW);
  end

  logic          tiny;      // exp_i < -126: the result is subnormal (or rounds up to 2^-126)
  logic signed [10:0] under;  // -126 - exp_i: how far below the normal range (> 0 when tiny)
  logic [DW-1:0] shift;     // the subnormal shift, clamped to SigW (all bits to sticky)
  logic [SigW-1:0] shifted; // sig_i >> shift
  logic          lost;      // nonzero bits shifted out
  logic [23:0]   kept;      // the 24 bits that survive rounding
  logic          guard;     // the first bit below them
  logic          rest;      // any nonzero bit below the guard bit
  logic          round_up;  // round to nearest, ties to even
  logic [7:0]    field_m1;  // exponent field - 1 (0 for a subnormal: its kept has no leading 1)
  logic [30:0]   field_frac;    // {exponent field, fraction} after rounding

  assign tiny  = exp_i < -10'sd126;
  assign under = -11'sd126 - 11'(exp_i);
  assign shift = !tiny ? '0 : (under >= $signed(11'(SigW))) ? DW'(SigW) : DW'(under);
  assign shifted = sig_i >> shift;
  assign lost  = (shifted << shift) != sig_i;
  assign kept  = shifted[SigW-1 -: 24];
  assign guard = shifted[SigW-25];
  assign rest  = (shifted[SigW-26:0] != '0) || lost || sticky_i;
  assign round_up = guard && (rest || kept[0]);
  assign field_m1 = tiny ? 8'd0 : 8'(exp_i + 10'sd126);
  assign field_frac = {field_m1, 23'd0} + {7'd0, kept} + {30'd0, round_up};

  always_comb begin
    if (nan_i) f_o = QNaN;
    else if (sig_i == '0) f_o = {sign_i, 31'd0};
    else if (exp_i > 10'sd127) f_o = {sign_i, 8'hFF, 23'd0};
    else f_o = {sign_i, field_frac};  // a carry out of 2^128 lands on {8'hFF, 0}: infinity
  end
endmodule

`default_nettype wire
