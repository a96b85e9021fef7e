// SPDX-License-Identifier: Apache-2.0
// Cosim top: the scan-out with the parameters of one config, from the header the build
// generates (`rastsim export-rtl-scanout`, <build>/rtl/generated/<config>_scanout_params.vh,
// named by the define SCANOUT_PARAMS_VH).
`default_nettype none

`include `SCANOUT_PARAMS_VH

module scanout_cosim_top (
  input  wire                clk_i,        // pixel clock
  input  wire                rst_ni,       // asynchronous reset, active low
  output wire                fb_rd_o,      // framebuffer read port (see rtl/scanout.v)
  output wire [31:0]         fb_addr_o,
  input  wire [23:0]         fb_rdata_i,
  input  wire                fb_rvalid_i,
  input  wire [2:0]          pal_we_i,     // palette write port
  input  wire [7:0]          pal_waddr_i,
  input  wire [DAC_BITS-1:0] pal_wdata_i,
  output wire                hsync_o,      // video out
  output wire                vsync_o,
  output wire                blank_o,
  output wire [DAC_BITS-1:0] dac_r_o,
  output wire [DAC_BITS-1:0] dac_g_o,
  output wire [DAC_BITS-1:0] dac_b_o
);

  scanout #(
    .HActive(H_ACTIVE), .HFrontPorch(H_FRONT_PORCH), .HSync(H_SYNC), .HBackPorch(H_BACK_PORCH),
    .VActive(V_ACTIVE), .VFrontPorch(V_FRONT_PORCH), .VSync(V_SYNC), .VBackPorch(V_BACK_PORCH),
    .HSyncPositive(H_SYNC_POSITIVE), .VSyncPositive(V_SYNC_POSITIVE),
    .FbWidth(FB_WIDTH), .FbHeight(FB_HEIGHT), .DacBits(DAC_BITS)
  ) u_scanout (.*);

endmodule

`default_nettype wire
