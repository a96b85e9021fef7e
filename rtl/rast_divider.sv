// SPDX-License-Identifier: Apache-2.0
// rast_divider: q = round_half_up(num / den), exact, pipelined restoring division.
//
// - The rounding of ref interpolate (div_round, Rounding::HalfUp, operands >= 0):
//     q = floor((2 num + den) / (2 den))
//   with num < 2^NumW, den in (0, 2^DenW) and the caller's guarantee q < 2^QW (an
//   interpolated attribute lies between its vertex values), so NumW = DenW + QW and the
//   restoring division needs exactly QW steps of one subtract-and-compare each.
// - Latency register stages (interp.latency_cycles), the QW steps spread evenly over
//   them (ceil(QW / Latency) a stage); Latency = 0 is purely combinational. One
//   division enters per cycle (initiation interval 1) while en_i is high; en_i low
//   freezes every stage (the interpolator's backpressure).
`default_nettype none

module rast_divider #(
  parameter int NumW    = 56,  // numerator bits (unsigned)
  parameter int DenW    = 48,  // denominator bits (unsigned, > 0)
  parameter int QW      = 8,   // quotient bits
  parameter int Latency = 4    // register stages (0: combinational)
) (
  input  wire logic            clk_i,  // core clock
  input  wire logic            en_i,   // advance the pipeline
  input  wire logic [NumW-1:0] num_i,  // numerator
  input  wire logic [DenW-1:0] den_i,  // denominator
  output      logic [QW-1:0]   q_o     // quotient, Latency cycles later
);
  localparam int Stages = (Latency > 0) ? Latency : 1;   // derived
  localparam int Steps  = (QW + Stages - 1) / Stages;   // derived: quotient bits a stage
  localparam int RW     = NumW + 1;                      // derived: 2 num + den fits
  localparam int DW     = DenW + 1;                      // derived: 2 den

  // Elaboration-time check: the QW restoring steps are exact only when NumW = DenW + QW.
  if (NumW != DenW + QW) begin : g_check_widths
    $error("rast_divider: NumW (%0d) must equal DenW + QW (%0d + %0d)", NumW, DenW, QW);
  end

  // Stage s takes (remainder, divisor, quotient so far) and does steps
  // [s*Steps, (s+1)*Steps) of QW; stage outputs are registered when Latency > 0.
  logic [RW-1:0] r_c [Stages], r_q [Stages];
  logic [DW-1:0] d_q [Stages];
  logic [QW-1:0] q_c [Stages], q_q [Stages];

  always_comb begin
    for (int s = 0; s < Stages; s++) begin
      logic [RW-1:0] r;
      logic [DW-1:0] d;
      logic [QW-1:0] q;
      if (s == 0) begin
        r = {num_i, 1'b0} + RW'(den_i);
        d = {den_i, 1'b0};
        q = '0;
      end else begin
        r = r_q[s-1];
        d = d_q[s-1];
        q = q_q[s-1];
      end
      for (int t = 0; t < QW; t++) begin
        if (t / Steps == s) begin
          logic [RW:0] diff;
          // Quotient bit k = QW-1-t: subtract d << k if it fits.
          diff = {1'b0, r} - ((RW+1)'(d) << (QW - 1 - t));
          if (!diff[RW]) begin
            r = diff[RW-1:0];
            q[QW-1-t] = 1'b1;
          end
        end
      end
      r_c[s] = r;
      q_c[s] = q;
    end
  end

  if (Latency > 0) begin : g_pipe
    always_ff @(posedge clk_i) begin
      if (en_i) begin
        for (int s = 0; s < Stages; s++) begin
          r_q[s] <= r_c[s];
          q_q[s] <= q_c[s];
          d_q[s] <= (s == 0) ? {den_i, 1'b0} : d_q[s-1];
        end
      end
    end
    assign q_o = q_q[Stages-1];
  end else begin : g_comb
    always_comb begin
      for (int s = 0; s < Stages; s++) begin
        r_q[s] = '0;
        q_q[s] = '0;
        d_q[s] = '0;
      end
    end
    assign q_o = q_c[0];
  end
endmodule

`default_nettype wire
