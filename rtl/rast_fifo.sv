// SPDX-License-Identifier: Apache-2.0
// rast_fifo: the bounded FIFO between two raster stages (valid/ready on both sides).
//
// - Depth entries of Width bits; a full FIFO deasserts in_ready_o, which is how a slow
//   stage stalls the ones before it (fifo.*_depth in the config).
// - A push and a pop in the same cycle are allowed when full (in_ready_o = !full ||
//   pop), so a FIFO that is drained every cycle never costs a bubble: the timing of the
//   SystemC model's sc_fifo (model/sc/link.h), where a read frees the slot at once.
// - Latency > 0: an entry may leave only Latency cycles after the cycle it became
//   visible (a per-entry countdown). This is the SystemC model's "ready time" of a
//   transaction written into a FIFO before its pipeline latency has elapsed
//   (setup.latency_cycles - setup.interval_cycles): the entry occupies a slot at once,
//   as in the model, and is visible to the reader once the latency has passed.
`default_nettype none

module rast_fifo #(
  parameter int Width   = 8,  // bits of one entry
  parameter int Depth   = 4,  // entries (>= 1)
  parameter int Latency = 0   // cycles an entry waits before it may leave
) (
  input  wire logic             clk_i,        // core clock
  input  wire logic             rst_ni,       // asynchronous reset, active low
  input  wire logic             in_valid_i,   // writer has an entry
  output      logic             in_ready_o,   // FIFO takes it this cycle
  input  wire logic [Width-1:0] in_data_i,    // the entry
  output      logic             out_valid_o,  // head entry present and ready
  input  wire logic             out_ready_i,  // reader takes the head this cycle
  output      logic [Width-1:0] out_data_o,   // head entry
  output      logic             empty_o       // no entry at all (for idle detection)
);
  localparam int PtrW = (Depth > 1) ? $clog2(Depth) : 1;        // derived: pointer bits
  localparam int CntW = $clog2(Depth + 1);                       // derived: count bits
  localparam int WaitW = (Latency > 0) ? $clog2(Latency + 1) : 1;  // derived: countdown bits
  localparam logic [PtrW-1:0] LastPtr = PtrW'(Depth - 1);        // derived

  // Elaboration-time check.
  if (Depth < 1) begin : g_check_depth
    $error("rast_fifo: Depth (%0d) must be at least 1", Depth);
  end

  logic [Width-1:0] mem_q [Depth];
  logic [WaitW-1:0] wait_q [Depth];
  logic [PtrW-1:0]  rd_q, wr_q;
  logic [CntW-1:0]  count_q;
  logic             push, pop, full;

  assign full        = (count_q == CntW'(Depth));
  assign empty_o     = (count_q == '0);
  assign out_valid_o = !empty_o && (wait_q[rd_q] == '0);
  assign out_data_o  = mem_q[rd_q];
  assign pop         = out_valid_o && out_ready_i;
  assign in_ready_o  = !full || pop;
  assign push        = in_valid_i && in_ready_o;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      rd_q    <= '0;
      wr_q    <= '0;
      count_q <= '0;
      for (int i = 0; i < Depth; i++) wait_q[i] <= '0;
    end else begin
      // Countdown of every waiting entry (free slots count down harmlessly).
      for (int i = 0; i < Depth; i++)
        if (wait_q[i] != '0) wait_q[i] <= wait_q[i] - 1'b1;
      if (push) begin
        mem_q[wr_q]  <= in_data_i;
        wait_q[wr_q] <= WaitW'(Latency);
        wr_q         <= (wr_q == LastPtr) ? '0 : wr_q + 1'b1;
      end
      if (pop) rd_q <= (rd_q == LastPtr) ? '0 : rd_q + 1'b1;
      if (push && !pop) count_q <= count_q + 1'b1;
      else if (pop && !push) count_q <= count_q - 1'b1;
    end
  end
endmodule

`default_nettype wire
