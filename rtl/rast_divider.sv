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
//   lane then costs the Verilator model a test instead of QW subtractions.
// - Shift-register form: the dividend R = 2 num + den (RW = NumW + 1 bits) is held as
//   {p, low}: p (DW = DenW + 1 bits) the partial remainder, low (QW bits) the dividend's
//   bits not yet brought down, whose vacated bottom bits fill with quotient bits. A step
//   shifts {p, low} left by one, subtracts d = 2 den from the top DW + 1 bits if it fits
//   and sets the new bottom bit. p < d holds throughout (at the start because
//   q < 2^QW, i.e. R < d 2^QW), so every subtract and compare is DW + 1 bits wide, not
//   RW + 1 (a whole-dividend restoring step): the same quotient with no separate
//   quotient register, and a verilated model keeps each operand in one 64-bit word
//   (DW + 1 <= 64) instead of multi-word arithmetic; after QW steps low holds the
//   quotient, and a stage after the last step keeps only low.
`default_nettype none

// The verilated model's divider form unless RAST_DIVIDER_STEPS asks for the circuit.
`ifdef VERILATOR
`ifndef RAST_DIVIDER_STEPS
`define RAST_DIVIDER_SIM_FORM
`endif
`endif

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
  localparam int DW     = DenW + 1;                      // derived: 2 den; partial remainder p

  // Elaboration-time check: the QW restoring steps are exact only when NumW = DenW + QW.
  if (NumW != DenW + QW) begin : g_check_widths
    $error("rast_divider: NumW (%0d) must equal DenW + QW (%0d + %0d)", NumW, DenW, QW);
  end

  // Stage s's steps [s*Steps, min((s+1)*Steps, QW)) on {p, low} with divisor d: p and
  // low after them. A task with two outputs, not a function returning {p, low}: the
  // verilated model then keeps p (DW bits) and low (QW bits) in one machine word each
  // instead of packing and unpacking a DW + QW-bit (multi-word) result every stage.
  task automatic stage_steps(input logic [DW-1:0] p_in, input logic [QW-1:0] low_in, input logic [DW-1:0] d,
                             input int s, output logic [DW-1:0] p_out, output logic [QW-1:0] low_out);
    logic [DW-1:0] p;
    logic [QW-1:0] low;
    logic [DW:0]   t;     // {p, next dividend bit}: < 2 d
    logic [DW+1:0] diff;  // t - d, its top bit the borrow
    p = p_in;
    low = low_in;
    for (int k = 0; k < QW; k++) begin
      if (k / Steps == s) begin
        t = {p, low[QW-1]};
        diff = {1'b0, t} - {2'b0, d};
        low = low << 1;
        if (!diff[DW+1]) begin
          p = diff[DW-1:0];  // t - d < d
          low[0] = 1'b1;
        end else begin
          p = t[DW-1:0];     // t < d
        end
      end
    end
    p_out = p;
    low_out = low;
  endtask

  logic [RW-1:0] r0;  // the dividend: 2 num + den
  logic [DW-1:0] d0;  // the divisor: 2 den
  assign r0 = {num_i, 1'b0} + RW'(den_i);
  assign d0 = {den_i, 1'b0};

  // The simulation form needs a 64-bit division for at least one quotient bit:
  // 2^ChunkW remainders below d < 2^DW fit 63 bits. Wider formats get the circuit.
`ifdef RAST_DIVIDER_SIM_FORM
  localparam bit SimForm = (DW <= 62);  // derived
`else
  localparam bit SimForm = 1'b0;        // derived
`endif
  if (Latency > 0 && SimForm) begin : g_line
    // ---- Simulation form (Verilator unless RAST_DIVIDER_STEPS is defined; DW <= 62) ----
    // The same ports, function and timing as g_pipe below: the quotient of a division
    // that enters on an en_i cycle appears at q_o Latency en_i cycles later; a division
    // entered without valid_i leaves an unread value. Computed at entry with 64-bit
    // machine divisions (ChunkW quotient bits each), then delayed in a ring of Stages
    // quotients: a verilated cycle costs a wanted division one computation and a ring
    // write, not Stages register stages of steps and copies (on desktop's 16 lanes x 4
    // dividers x 12 stages: 768 stage updates a busy cycle). Synthesis (Yosys) and a
    // build with RAST_DIVIDER_STEPS get g_pipe, the circuit; tb/rtl_divider checks the
    // two forms cycle for cycle on random operands, valids and stalls.
    localparam int ChunkW = 63 - DW;                        // derived: quotient bits a division
    localparam int Chunks = (QW + ChunkW - 1) / ChunkW;     // derived
    localparam int SlotW = (Stages > 1) ? $clog2(Stages) : 1;  // derived: ring index bits
    // floor(r / d) for r < d 2^QW: long division ChunkW quotient bits at a time, each a
    // 64-bit division of {remainder (< d < 2^DW), next bits} < 2^63.
    function automatic logic [QW-1:0] quotient(input logic [RW-1:0] r, input logic [DW-1:0] d);
      logic [63:0] rem, acc, qc;
      logic [QW-1:0] low, q, top;
      int n;
      rem = 64'(r[RW-1:QW]);
      low = r[QW-1:0];
      q = '0;
      for (int c = 0; c < Chunks; c++) begin
        n = (c == Chunks - 1) ? QW - c * ChunkW : ChunkW;
        top = low >> (QW - n);  // the next n dividend bits
        acc = (rem << n) | 64'(top);
        low = low << n;
        qc = acc / 64'(d);
        rem = acc - qc * 64'(d);
        q = (q << n) | QW'(qc);
      end
      quotient = q;
    endfunction
    logic [QW-1:0]   ring_q [Stages];  // quotients, oldest at slot_q
    // No reset: the first en_i cycle brings any start value into range, and no division
    // enters before the interpolator has left reset (en_i is high throughout reset).
    logic [SlotW-1:0] slot_q;
    always_ff @(posedge clk_i) begin
      if (en_i) begin
        if (valid_i) ring_q[slot_q] <= quotient(r0, d0);
        /* verilator lint_off UNSIGNED */  // one stage: always slot 0
        slot_q <= (slot_q >= SlotW'(Stages - 1)) ? '0 : slot_q + 1'b1;
        /* verilator lint_on UNSIGNED */
      end
    end
    assign q_o = ring_q[slot_q];
  end else if (Latency > 0) begin : g_pipe
    // Each stage's registers are its own variables (not one array indexed by stage): a
    // verilated model then updates them as plain words, without per-element
    // delayed-assignment bookkeeping.
    for (genvar s = 0; s < Stages; s++) begin : g_stage
      // (The last stage's v_q is not read: its low_q is the quotient.)
      /* verilator lint_off UNUSEDSIGNAL */
      logic [QW-1:0] low_q;  // dividend bits still to bring down, then quotient bits
      logic          v_q;    // holds a wanted division (no reset: it only skips work)
      /* verilator lint_on UNUSEDSIGNAL */
      logic [QW-1:0] low_in;
      logic          v_in;
      if (s == 0) begin : g_first
        assign {low_in, v_in} = {r0[QW-1:0], valid_i};
      end else begin : g_next
        assign {low_in, v_in} = {g_stage[s-1].low_q, g_stage[s-1].v_q};
      end
      always_ff @(posedge clk_i) begin
        if (en_i) v_q <= v_in;
      end
      if (s * Steps < QW) begin : g_steps
        // A stage with steps also holds the partial remainder and the divisor. (The last
        // such stage's p_q and d_q are not read: the quotient is complete.)
        /* verilator lint_off UNUSEDSIGNAL */
        logic [DW-1:0] p_q;  // partial remainder
        logic [DW-1:0] d_q;  // divisor
        /* verilator lint_on UNUSEDSIGNAL */
        logic [DW-1:0] p_in, d_in;
        if (s == 0) begin : g_first
          assign {p_in, d_in} = {r0[RW-1:QW], d0};
        end else begin : g_next
          assign {p_in, d_in} = {g_stage[s-1].g_steps.p_q, g_stage[s-1].g_steps.d_q};
        end
        // The steps are computed inside the clocked block, under the stage's valid: the
        // same registers and logic, but a verilated model then does an idle stage's
        // work only as a test.
        always_ff @(posedge clk_i) begin
          if (en_i && v_in) begin
            logic [DW-1:0] p;
            logic [QW-1:0] low;
            stage_steps(p_in, low_in, d_in, s, p, low);
            p_q   <= p;
            low_q <= low;
            d_q   <= d_in;
          end
        end
      end else begin : g_delay
        // After the last step (Latency > QW / Steps stages: colour's 8 steps over 12
        // stages): the quotient alone is delayed; no remainder or divisor is kept.
        always_ff @(posedge clk_i) begin
          if (en_i && v_in) low_q <= low_in;
        end
      end
    end
    assign q_o = g_stage[Stages-1].low_q;
  end else begin : g_comb
    /* verilator lint_off UNUSEDSIGNAL */
    logic [DW-1:0] p;  // the final remainder: not needed
    /* verilator lint_on UNUSEDSIGNAL */
    always_comb stage_steps(r0[RW-1:QW], r0[QW-1:0], d0, 0, p, q_o);
  end
endmodule

`undef RAST_DIVIDER_SIM_FORM

`default_nettype wire
