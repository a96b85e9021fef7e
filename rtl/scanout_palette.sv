// SPDX-License-Identifier: Apache-2.0
// RAMDAC palette of one channel: 256 entries of DacBits, one write port (host loads the
// table: linear or gamma ramp, model/ref/dac.h) and one registered read port (the
// pixel path: framebuffer byte in, DAC code out one cycle later).
`default_nettype none

module scanout_palette #(
  parameter integer DacBits = 8  // code width
) (
  input  wire               clk_i,    // pixel clock
  input  wire               we_i,     // write enable (host port)
  input  wire [7:0]         waddr_i,  // entry to write
  input  wire [DacBits-1:0] wdata_i,  // code to store
  input  wire [7:0]         raddr_i,  // framebuffer byte to look up
  output reg  [DacBits-1:0] rdata_o   // its code, registered
);

  reg [DacBits-1:0] mem_q [256];

  always_ff @(posedge clk_i) begin
    if (we_i) mem_q[waddr_i] <= wdata_i;
    rdata_o <= mem_q[raddr_i];
  end

endmodule

`default_nettype wire
