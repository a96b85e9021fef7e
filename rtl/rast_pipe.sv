// SPDX-License-Identifier: Apache-2.0
// rast_pipe: a delay line of Latency register stages with a common enable, for the
// side data (valid, pixel, flags) that travels next to rast_divider's pipeline.
// Latency = 0 is a wire. The top bit of d_i is the transaction's valid bit: it resets
// to 0, and occupied_o says some stage holds a valid one (for idle detection).
// - A stage's other Width - 1 bits load only with a valid transaction (en_i and the
//   incoming valid bit set) and have no reset: q_o's data bits are meaningful only
//   while its valid bit is set (the interpolator's reader looks at them only then).
//   An empty beat then moves one bit a stage instead of Width; in a verilated model
//   the wide side data (hundreds of bits with 16 lanes) is copied only for real beats.
// - Each stage's registers are their own variables (a generate block a stage, not an
//   array indexed by stage): a verilated model updates them as plain words.
`default_nettype none

module rast_pipe #(
  parameter int Width   = 2,  // bits carried, the valid bit included (>= 2)
  parameter int Latency = 1   // register stages
) (
  input  wire logic             clk_i,   // core clock
  input  wire logic             rst_ni,  // asynchronous reset, active low
  input  wire logic             en_i,    // advance
  input  wire logic [Width-1:0] d_i,     // in: {valid, data}
  output      logic [Width-1:0] q_o,     // out, Latency enabled cycles later (data valid with the valid bit)
  output      logic             occupied_o  // a stage holds a transaction (d_i[Width-1] set)
);
  if (Latency > 0) begin : g_pipe
    logic [Latency-1:0] occ;  // stage s holds a valid transaction
    for (genvar s = 0; s < Latency; s++) begin : g_stage
      // (The last stage's data_q is read through q_o; every stage's v_q through occ.)
      logic             v_q;     // valid bit
      logic [Width-2:0] data_q;  // the rest, loaded with a valid transaction
      logic             v_in;
      logic [Width-2:0] data_in;
      if (s == 0) begin : g_first
        assign {v_in, data_in} = d_i;
      end else begin : g_next
        assign {v_in, data_in} = {g_stage[s-1].v_q, g_stage[s-1].data_q};
      end
      always_ff @(posedge clk_i or negedge rst_ni) begin
        if (!rst_ni) v_q <= 1'b0;
        else if (en_i) v_q <= v_in;
      end
      always_ff @(posedge clk_i) begin
        if (en_i && v_in) data_q <= data_in;
      end
      assign occ[s] = v_q;
    end
    assign q_o = {g_stage[Latency-1].v_q, g_stage[Latency-1].data_q};
    assign occupied_o = |occ;
  end else begin : g_wire
    assign q_o = d_i;
    assign occupied_o = 1'b0;
  end
endmodule

`default_nettype wire
