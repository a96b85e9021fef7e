// SPDX-License-Identifier: Apache-2.0
// rast_hold: the register a stage keeps its current transaction in.
//
// A stage takes the FIFO's head in the first cycle it works on it, freeing the FIFO
// slot at once, as the SystemC model's stages do (Stage::read pops before the work,
// model/sc/stage.h): the head passes through in that cycle (no added latency), and is
// kept here for the following cycles until the stage is done with it (out_ready_i).
`default_nettype none

module rast_hold #(
  parameter int Width = 8  // bits of one transaction
) (
  input  wire logic             clk_i,        // core clock
  input  wire logic             rst_ni,       // asynchronous reset, active low
  input  wire logic             in_valid_i,   // FIFO head present
  output      logic             in_ready_o,   // pop it (the register is free)
  input  wire logic [Width-1:0] in_data_i,    // FIFO head
  output      logic             out_valid_o,  // the stage's current transaction
  input  wire logic             out_ready_i,  // the stage is done with it this cycle
  output      logic [Width-1:0] out_data_o    // the transaction
);
  logic             held_q;
  logic [Width-1:0] data_q;
  assign in_ready_o  = !held_q;
  assign out_valid_o = held_q || in_valid_i;
  assign out_data_o  = held_q ? data_q : in_data_i;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) held_q <= 1'b0;
    else if (held_q) held_q <= !out_ready_i;
    else held_q <= in_valid_i && !out_ready_i;
  end
  always_ff @(posedge clk_i) begin
    if (!held_q && in_valid_i) data_q <= in_data_i;
  end
endmodule

`default_nettype wire
