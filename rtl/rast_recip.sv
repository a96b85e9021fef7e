// SPDX-License-Identifier: Apache-2.0
// rast_recip: the per-pixel reciprocal unit of perspective-correct interpolation
// (interp.recip = "newton"), bit-exact with the reference's recip_newton(d, SEED_BITS,
// ITERATIONS) (model/ref/recip.h, docs/clip-space.md "Perspective-correct interpolation").
//
// - In: a normalised divisor d in [2^39, 2^40), the value x = d / 2^40 in [1/2, 1).
// - Seed: a table of 2^SEED_BITS entries, indexed by the SEED_BITS bits of d below its
//   leading one (bit 39). Entry i is round_nearest_even(2^(2b+3) / (2^(b+1) + 2i + 1)),
//   b = SEED_BITS: 1 / (the midpoint of its interval of x) with b + 1 fraction bits,
//   b + 2 bits wide. The entries are computed at elaboration (seed_entry below), not
//   written out; the divisor is odd, so no entry is a tie.
// - ITERATIONS Newton-Raphson steps, unsigned with 40 fraction bits, products truncated:
//     p = (d * y) >> 40          40 x 42-bit product, 42 bits kept (x y < 2)
//     c = 2^41 - p               2 - x y
//     y = (y * c) >> 40          42 x 42-bit product, 42 bits kept
// - Out: y ~ 2^80 / d in units of 2^-40, an approximation of 1 / x in (1, 2]: 42 bits unsigned.
// - Pipeline: one register stage for the table look-up, then two a step (the first
//   multiply with the subtraction, the second multiply): latency 1 + 2 * ITERATIONS
//   cycles (5 at the default 8 bits, 2 steps), one result a cycle. The stages advance
//   together while the output is taken or empty: in_ready_o = out_ready_i || !out_valid_o;
//   with STATIC = 1 (a stage of a static pipeline: rast_interpolate_persp) only while
//   out_ready_i, its enable, is high, bubbles included, so a result leaves exactly
//   1 + 2 ITERATIONS enabled cycles after its divisor entered.
// - A step's products are computed only while its stage holds a divisor (the verilated
//   model then skips an idle unit's multiplies; the data mean something only with valid).
// - Units: the table (a multiplexer of constants) and 2 * ITERATIONS multipliers.
`default_nettype none

module rast_recip #(
  parameter int SEED_BITS  = 8,  // interp.recip_seed_bits: index bits of the seed table (1..16)
  parameter int ITERATIONS = 2,  // interp.recip_iterations: Newton-Raphson steps (0..4)
  parameter int STATIC     = 0   // 1: the stages advance only with out_ready_i (see above)
) (
  input  wire logic        clk_i,        // core clock
  input  wire logic        rst_ni,       // asynchronous reset, active low
  input  wire logic        in_valid_i,   // a divisor on d_i
  output      logic        in_ready_o,   // it is taken this cycle
  input  wire logic [39:0] d_i,          // normalised divisor, bit 39 set: x = d / 2^40
  output      logic        out_valid_o,  // a reciprocal on y_o
  input  wire logic        out_ready_i,  // the consumer takes it this cycle
  output      logic [41:0] y_o           // ~2^80 / d: 1 / x with 40 fraction bits
);
  localparam int F = 40;                      // fraction bits of d and y
  localparam int YW = 42;                     // width of y, p and c
  localparam int EW = SEED_BITS + 2;          // width of a seed entry
  localparam int Entries = 2 ** SEED_BITS;    // seed table entries
  localparam int Stages = 1 + 2 * ITERATIONS; // the latency, cycles

  // Elaboration-time checks (the range of interp.recip_seed_bits; a step count >= 0).
  if (SEED_BITS < 1 || SEED_BITS > 16) begin : g_check_seed_bits
    $error("rast_recip: SEED_BITS (%0d) must be in 1..16", SEED_BITS);
  end
  if (ITERATIONS < 0) begin : g_check_iterations
    $error("rast_recip: ITERATIONS (%0d) must be at least 0", ITERATIONS);
  end

  // Seed entry `index` in units of 2^-(SEED_BITS + 1), rounded to nearest even (the
  // reference's recip_seed_entry). 2^(2b+3) <= 2^35 and the divisor below 2^18: 64-bit
  // arithmetic is exact.
  function automatic logic [63:0] seed_entry(input logic [63:0] index);
    logic [63:0] num, den, q, r;
    num = 64'd1 << (2 * SEED_BITS + 3);
    den = (64'd1 << (SEED_BITS + 1)) + 2 * index + 1;
    q = num / den;
    r = num - q * den;
    if (2 * r > den || (2 * r == den && q[0])) q = q + 1;
    seed_entry = q;
  endfunction

  // ---- The valid bits: stage s holds a divisor (reset to empty) ----
  logic              advance;  // every stage moves on this cycle
  logic [Stages-1:0] v_q;      // bit s: stage s holds a divisor
  assign advance = out_ready_i || (STATIC == 0 && !v_q[Stages-1]);
  assign in_ready_o = advance;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) v_q <= '0;
    else if (advance) v_q <= (v_q << 1) | Stages'(in_valid_i);
  end
  assign out_valid_o = v_q[Stages-1];

  // ---- Stage 0: the seed ----
  // Two nested loops of at most 256 entries: Verilator refuses to unroll a generate loop
  // of more than 1024 (its --unroll-count), and 16 index bits make 65,536 entries.
  localparam int Row = Entries < 256 ? Entries : 256;  // entries an inner loop
  logic [EW-1:0] seed_table [Entries];
  for (genvar hi = 0; hi < Entries / Row; hi++) begin : g_seed_row
    for (genvar lo = 0; lo < Row; lo++) begin : g_seed
      localparam int I = hi * Row + lo;
      localparam logic [EW-1:0] Entry = EW'(seed_entry(64'(I)));
      assign seed_table[I] = Entry;
    end
  end
  logic [SEED_BITS-1:0] index;  // the bits of d below its leading one
  logic [YW-1:0]        seed;   // the entry with 40 fraction bits
  logic [YW-1:0]        y0_q;
  assign index = d_i[F-2 -: SEED_BITS];
  assign seed = YW'(seed_table[index]) << (F - 1 - SEED_BITS);
  // Data registers load only with a divisor (no reset: read only while its valid is set).
  always_ff @(posedge clk_i) begin
    if (advance && in_valid_i) y0_q <= seed;
  end

  if (ITERATIONS == 0) begin : g_seed_only
    assign y_o = y0_q;
    wire unused_ok = &{1'b0, d_i};  // only the index bits of d decide a seed
  end else begin : g_steps
    // Step k's inputs, registered by stage 2k: d (stage 0 and each step's second stage
    // pass it on) and y (slice ITERATIONS: the result).
    logic [ITERATIONS*F-1:0]      d_bus;
    logic [(ITERATIONS+1)*YW-1:0] y_bus;
    logic [F-1:0]                 d0_q;
    always_ff @(posedge clk_i) begin
      if (advance && in_valid_i) d0_q <= d_i;
    end
    assign d_bus[F-1:0] = d0_q;
    assign y_bus[YW-1:0] = y0_q;

    for (genvar k = 0; k < ITERATIONS; k++) begin : g_step
      logic [F-1:0]  d;               // x = d / 2^40
      logic [YW-1:0] y, p, c, y_next;
      logic [YW-1:0] y1_q, c1_q;      // after the first multiply (stage 2k + 1)
      logic [YW-1:0] y2_q;            // after the second (stage 2k + 2)
      assign d = d_bus[k*F +: F];
      assign y = y_bus[k*YW +: YW];
      always_comb begin
        p = '0;
        c = '0;
        y_next = '0;
        if (v_q[2*k]) begin
          p = YW'((82'(d) * 82'(y)) >> F);
          c = (YW'(2) << F) - p;
        end
        if (v_q[2*k+1]) y_next = YW'((84'(y1_q) * 84'(c1_q)) >> F);
      end
      always_ff @(posedge clk_i) begin
        if (advance) begin
          if (v_q[2*k]) {y1_q, c1_q} <= {y, c};
          if (v_q[2*k+1]) y2_q <= y_next;
        end
      end
      assign y_bus[(k+1)*YW +: YW] = y2_q;
      if (k + 1 < ITERATIONS) begin : g_pass_d  // d waits beside the step for the next one
        logic [F-1:0] d1_q, d2_q;
        always_ff @(posedge clk_i) begin
          if (advance) begin
            if (v_q[2*k]) d1_q <= d;
            if (v_q[2*k+1]) d2_q <= d1_q;
          end
        end
        assign d_bus[(k+1)*F +: F] = d2_q;
      end
    end
    assign y_o = y_bus[ITERATIONS*YW +: YW];
  end
endmodule

`default_nettype wire
