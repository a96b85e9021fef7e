// SPDX-License-Identifier: Apache-2.0
// Video timing generator: raster-scan counters and the sync / active flags of one mode.
//
// - hcount_o counts pixel clocks 0 .. HTotal-1 a line, vcount_o lines 0 .. VTotal-1 a
//   frame; both start at the first active pixel (the counter convention of
//   model/ref/video_timing.h).
// - A line is [active | front porch | sync | back porch]; so is a frame, in lines.
//   vsync changes at hcount 0.
// - active_o, hsync_o and vsync_o are decoded from the registered counters in the same
//   cycle; syncs carry the configured polarity.
// Every value is a parameter exported from the config (rtl/generated/*_scanout_params.vh).
`default_nettype none

module video_timing #(
  parameter integer HActive     = 128,  // active pixels a line
  parameter integer HFrontPorch = 8,    // px from the last active pixel to hsync
  parameter integer HSync       = 16,   // hsync width, px
  parameter integer HBackPorch  = 8,    // px from the end of hsync to the next line
  parameter integer VActive     = 128,  // active lines a frame
  parameter integer VFrontPorch = 2,    // lines from the last active line to vsync
  parameter integer VSync       = 2,    // vsync width, lines
  parameter integer VBackPorch  = 4,    // lines from the end of vsync to the next frame
  parameter integer HSyncPositive = 0,  // 1: hsync is high during the pulse
  parameter integer VSyncPositive = 0,  // 1: vsync is high during the pulse
  // Derived: totals and counter widths.
  localparam integer HTotal = HActive + HFrontPorch + HSync + HBackPorch,
  localparam integer VTotal = VActive + VFrontPorch + VSync + VBackPorch,
  localparam integer HW = $clog2(HTotal),
  localparam integer VW = $clog2(VTotal)
) (
  input  wire          clk_i,     // pixel clock
  input  wire          rst_ni,    // asynchronous reset, active low
  output reg  [HW-1:0] hcount_o,  // pixel position in the line
  output reg  [VW-1:0] vcount_o,  // line position in the frame
  output wire          active_o,  // (hcount, vcount) is in the active area
  output wire          hsync_o,   // hsync wire level, polarity applied
  output wire          vsync_o    // vsync wire level, polarity applied
);

  // Derived: the sized boundaries the counters are compared with.
  localparam [HW-1:0] H_LAST       = HW'(HTotal - 1);
  localparam [VW-1:0] V_LAST       = VW'(VTotal - 1);
  localparam [HW-1:0] H_ACT        = HW'(HActive);
  localparam [VW-1:0] V_ACT        = VW'(VActive);
  localparam [HW-1:0] H_SYNC_START = HW'(HActive + HFrontPorch);
  localparam [HW-1:0] H_SYNC_END   = HW'(HActive + HFrontPorch + HSync);
  localparam [VW-1:0] V_SYNC_START = VW'(VActive + VFrontPorch);
  localparam [VW-1:0] V_SYNC_END   = VW'(VActive + VFrontPorch + VSync);

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      hcount_o <= '0;
      vcount_o <= '0;
    end else if (hcount_o == H_LAST) begin
      hcount_o <= '0;
      vcount_o <= (vcount_o == V_LAST) ? '0 : vcount_o + 1'b1;
    end else begin
      hcount_o <= hcount_o + 1'b1;
    end
  end

  wire hsync_on = (hcount_o >= H_SYNC_START) && (hcount_o < H_SYNC_END);
  wire vsync_on = (vcount_o >= V_SYNC_START) && (vcount_o < V_SYNC_END);

  assign active_o = (hcount_o < H_ACT) && (vcount_o < V_ACT);
  assign hsync_o  = hsync_on ^ (HSyncPositive == 0);
  assign vsync_o  = vsync_on ^ (VSyncPositive == 0);

endmodule

`default_nettype wire
