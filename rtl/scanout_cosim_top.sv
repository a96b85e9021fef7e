// SPDX-License-Identifier: Apache-2.0
// scanout_cosim_top: scanout_top (rtl/scanout_top.sv) with the parameters of one config,
// from the header `rastsim export-rtl-scanout` writes (scanout_params.vh; the build's
// configure-time exporter writes <build>/tb/scanout/scanout_<config>/scanout_params.vh and
// verilates it as Vscanout_<config> for the scan-out tests, tb/scanout/CMakeLists.txt).
`default_nettype none

module scanout_cosim_top #(
`include "scanout_params.vh"
) (
  input  wire logic               clk_i,        // pixel clock
  input  wire logic               rst_ni,       // asynchronous reset, active low
  output      logic               fb_rd_o,      // framebuffer read port (see rtl/scanout_top.sv)
  output      logic [31:0]        fb_addr_o,
  input  wire logic [23:0]        fb_rdata_i,
  input  wire logic               fb_rvalid_i,
  input  wire logic [2:0]         pal_we_i,     // palette write port
  input  wire logic [7:0]         pal_waddr_i,
  input  wire logic [DacBits-1:0] pal_wdata_i,
  output      logic               hsync_o,      // video out
  output      logic               vsync_o,
  output      logic               blank_o,
  output      logic [DacBits-1:0] dac_r_o,
  output      logic [DacBits-1:0] dac_g_o,
  output      logic [DacBits-1:0] dac_b_o
);
  scanout_top #(
    .HActive(HActive), .HFrontPorch(HFrontPorch), .HSync(HSync), .HBackPorch(HBackPorch),
    .VActive(VActive), .VFrontPorch(VFrontPorch), .VSync(VSync), .VBackPorch(VBackPorch),
    .HSyncPositive(HSyncPositive), .VSyncPositive(VSyncPositive),
    .FbWidth(FbWidth), .FbHeight(FbHeight), .DacBits(DacBits)
  ) u_scanout (.*);
endmodule

`default_nettype wire
