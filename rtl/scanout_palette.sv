// SPDX-License-Identifier: Apache-2.0
// scanout_palette: the RAMDAC palette of one channel, 256 entries of DacBits, one write
// port (the host loads the table: linear or gamma ramp, model/display/dac.h) and one
// registered read port (the pixel path: framebuffer byte in, DAC code out one cycle
// later).
`default_nettype none

module scanout_palette #(
  parameter int DacBits = 8  // code width
) (
  input  wire logic               clk_i,    // pixel clock
  input  wire logic               we_i,     // write enable (host port)
  input  wire logic [7:0]         waddr_i,  // entry to write
  input  wire logic [DacBits-1:0] wdata_i,  // code to store
  input  wire logic [7:0]         raddr_i,  // framebuffer byte to look up
  output      logic [DacBits-1:0] rdata_o   // its code, registered
);
  logic [DacBits-1:0] mem_q [256];
  logic [DacBits-1:0] rdata_q;

  always_ff @(posedge clk_i) begin
    if (we_i) mem_q[waddr_i] <= wdata_i;
    rdata_q <= mem_q[raddr_i];
  end

  assign rdata_o = rdata_q;
endmodule

`default_nettype wire
