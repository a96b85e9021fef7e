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
// - valid_i: the division entering this cycle is wanted. A stage holding no wanted
//   division keeps its registers (no steps, no load): the result of an unwanted
//   division is never read (the interpolator reads only its picked lanes); an idle
//   lane then costs the Verilator model a test instead of QW wide subtractions.
`default_nettype none

module rast_divider #(
  parameter int NumW    = 56,  // numerator bits (unsigned)
  parameter int DenW    = 48,  // denominator bits (unsigned, > 0)
  parameter int QW      = 8,   // quotient bits
  parameter int Latency = 4    // register stages (0: combinational)
) (
  input  wire logic            clk_i,  // core clock
  input  wire logic            en_i,   // advance the pipeline
  input  wire logic            valid_i,  // num_i / den_i are a wanted division
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
  // Returns {remainder, quotient so far} after stage s's steps.
  function automatic logic [RW+QW-1:0] stage_steps(input logic [RW-1:0] r_in, input logic [DW-1:0] d,
                                                   input logic [QW-1:0] q_in, input int s);
    logic [RW-1:0] r;
    logic [QW-1:0] q;
    logic [RW:0]   diff;
    r = r_in;
    q = q_in;
    for (int t = 0; t < QW; t++) begin
      if (t / Steps == s) begin
        // Quotient bit k = QW-1-t: subtract d << k if it fits.
        diff = {1'b0, r} - ((RW+1)'(d) << (QW - 1 - t));
        if (!diff[RW]) begin
          r = diff[RW-1:0];
          q[QW-1-t] = 1'b1;
        end
      end
    end
    stage_steps = {r, q};
  endfunction

  logic [RW-1:0] r0;  // stage 0's remainder: 2 num + den
  logic [DW-1:0] d0;  // the divisor: 2 den
  assign r0 = {num_i, 1'b0} + RW'(den_i);
  assign d0 = {den_i, 1'b0};

  if (Latency > 0) begin : g_pipe
    // (With one stage only q_q is read: the others' last entries are unused.)
    /* verilator lint_off UNUSEDSIGNAL */
    logic [RW-1:0] r_q [Stages];
    logic [DW-1:0] d_q [Stages];
    logic [QW-1:0] q_q [Stages];
    logic          v_q [Stages];  // stage s holds a wanted division (no reset: it only skips work)
    /* verilator lint_on UNUSEDSIGNAL */
    // The steps are computed inside the clocked block, under the stage's valid: the same
    // registers and logic, but a verilated model then does an idle stage's work only as
    // a test (in a combinational block it evaluated every stage of every lane a cycle).
    for (genvar s = 0; s < Stages; s++) begin : g_stage
      logic [RW-1:0] r_in;
      logic [DW-1:0] d_in;
      logic [QW-1:0] q_in;
      logic          v_in;
      if (s == 0) begin : g_first
        assign {r_in, d_in, q_in, v_in} = {r0, d0, QW'(0), valid_i};
      end else begin : g_next
        assign {r_in, d_in, q_in, v_in} = {r_q[s-1], d_q[s-1], q_q[s-1], v_q[s-1]};
      end
      always_ff @(posedge clk_i) begin
        if (en_i) begin
          v_q[s] <= v_in;
          if (v_in) begin
            logic [RW+QW-1:0] rq;
            rq = stage_steps(r_in, d_in, q_in, s);
            r_q[s] <= rq[RW+QW-1:QW];
            q_q[s] <= rq[QW-1:0];
            d_q[s] <= d_in;
          end
        end
      end
    end
    assign q_o = q_q[Stages-1];
  end else begin : g_comb
    logic [RW+QW-1:0] rq;
    assign rq  = stage_steps(r0, d0, '0, 0);
    assign q_o = rq[QW-1:0];
  end
endmodule

`default_nettype wire
