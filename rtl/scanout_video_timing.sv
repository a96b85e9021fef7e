// SPDX-License-Identifier: Apache-2.0
// scanout_video_timing: raster-scan counters and the sync / active flags of one mode.
//
// - hcount_o counts pixel clocks 0 .. HTotal-1 a line, vcount_o lines 0 .. VTotal-1 a
//   frame; both start at the first active pixel (the counter convention of
//   model/config/video_timing.h).
// - A line is [active | front porch | sync | back porch]; so is a frame, in lines.
//   vsync changes at hcount 0.
// - active_o, hsync_o and vsync_o are decoded from the registered counters in the same
//   cycle; syncs carry the configured polarity.
`default_nettype none

module scanout_video_timing #(
  parameter int HActive       = 128,  // active pixels a line
  parameter int HFrontPorch   = 8,    // px from the last active pixel to hsync
  parameter int HSync         = 16,   // hsync width, px
  parameter int HBackPorch    = 8,    // px from the end of hsync to the next line
  parameter int VActive       = 128,  // active lines a frame
  parameter int VFrontPorch   = 2,    // lines from the last active line to vsync
  parameter int VSync         = 2,    // vsync width, lines
  parameter int VBackPorch    = 4,    // lines from the end of vsync to the next frame
  parameter int HSyncPositive = 0,    // 1: hsync is high during the pulse
  parameter int VSyncPositive = 0,    // 1: vsync is high during the pulse
  localparam int HTotal = HActive + HFrontPorch + HSync + HBackPorch,  // derived
  localparam int VTotal = VActive + VFrontPorch + VSync + VBackPorch,  // derived
  localparam int HW = $clog2(HTotal),  // derived: counter bits
  localparam int VW = $clog2(VTotal)   // derived
) (
  input  wire logic          clk_i,     // pixel clock
  input  wire logic          rst_ni,    // asynchronous reset, active low
  output      logic [HW-1:0] hcount_o,  // pixel position in the line
  output      logic [VW-1:0] vcount_o,  // line position in the frame
  output      logic          active_o,  // (hcount, vcount) is in the active area
  output      logic          hsync_o,   // hsync wire level, polarity applied
  output      logic          vsync_o    // vsync wire level, polarity applied
);
  // Derived: the sized boundaries the counters are compared with.
  localparam logic [HW-1:0] HLast      = HW'(HTotal - 1);
  localparam logic [VW-1:0] VLast      = VW'(VTotal - 1);
  localparam logic [HW-1:0] HAct       = HW'(HActive);
  localparam logic [VW-1:0] VAct       = VW'(VActive);
  localparam logic [HW-1:0] HSyncStart = HW'(HActive + HFrontPorch);
  localparam logic [HW-1:0] HSyncEnd   = HW'(HActive + HFrontPorch + HSync);
  localparam logic [VW-1:0] VSyncStart = VW'(VActive + VFrontPorch);
  localparam logic [VW-1:0] VSyncEnd   = VW'(VActive + VFrontPorch + VSync);

  logic [HW-1:0] hcount_q;
  logic [VW-1:0] vcount_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      hcount_q <= '0;
      vcount_q <= '0;
    end else if (hcount_q == HLast) begin
      hcount_q <= '0;
      vcount_q <= (vcount_q == VLast) ? '0 : vcount_q + 1'b1;
    end else begin
      hcount_q <= hcount_q + 1'b1;
    end
  end

  logic hsync_on, vsync_on;
  assign hsync_on = (hcount_q >= HSyncStart) && (hcount_q < HSyncEnd);
  assign vsync_on = (vcount_q >= VSyncStart) && (vcount_q < VSyncEnd);

  assign hcount_o = hcount_q;
  assign vcount_o = vcount_q;
  assign active_o = (hcount_q < HAct) && (vcount_q < VAct);
  assign hsync_o  = hsync_on ^ (HSyncPositive == 0);
  assign vsync_o  = vsync_on ^ (VSyncPositive == 0);
endmodule

`default_nettype wire
