// SPDX-License-Identifier: Apache-2.0
// rast_pipe: a delay line of Latency register stages with a common enable, for the
// side data (valid, pixel, flags) that travels next to rast_divider's pipeline.
// Latency = 0 is a wire. Stages reset to 0 so the valid bits start clear. The top bit
// of d_i is the transaction's valid bit: occupied_o says some stage holds a valid one
// (for idle detection).
`default_nettype none

module rast_pipe #(
  parameter int Width   = 1,  // bits carried
  parameter int Latency = 1   // register stages
) (
  input  wire logic             clk_i,   // core clock
  input  wire logic             rst_ni,  // asynchronous reset, active low
  input  wire logic             en_i,    // advance
  input  wire logic [Width-1:0] d_i,     // in
  output      logic [Width-1:0] q_o,     // out, Latency enabled cycles later
  output      logic             occupied_o  // a stage holds a transaction (d_i[Width-1] set)
);
  if (Latency > 0) begin : g_pipe
    logic [Width-1:0] stage_q [Latency];
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        for (int s = 0; s < Latency; s++) stage_q[s] <= '0;
      end else if (en_i) begin
        for (int s = 0; s < Latency; s++) stage_q[s] <= (s == 0) ? d_i : stage_q[s-1];
      end
    end
    assign q_o = stage_q[Latency-1];
    always_comb begin
      occupied_o = 1'b0;
      for (int s = 0; s < Latency; s++) occupied_o = occupied_o | stage_q[s][Width-1];
    end
  end else begin : g_wire
    assign q_o = d_i;
    assign occupied_o = 1'b0;
  end
endmodule

`default_nettype wire
