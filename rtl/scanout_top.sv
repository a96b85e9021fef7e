// SPDX-License-Identifier: Apache-2.0
// scanout_top: framebuffer read in raster order -> palette -> DAC codes, with sync and
// BLANK aligned to the codes. Pixel for pixel the reference scan-out
// (model/display/scanout.cpp), Latency pixel clocks later.
//
// - Cycle 0: the timing generator's position; an active pixel inside the framebuffer
//   issues a read of pixel index vcount * FbWidth + hcount.
// - Cycle 1: the framebuffer returns {R, G, B} (a synchronous RAM, read latency 1) with
//   fb_rvalid_i; the bytes address the three palettes.
// - Cycle 2: codes out. A pixel without data (outside the framebuffer, or fb_rvalid_i
//   low: an underrun) goes out blank: BLANK high, codes 0.
// - Every parameter comes from the config through the exported header
//   scanout_params.vh (`rastsim export-rtl-scanout`, model/rtlsim/rtl_params.cpp).
`default_nettype none

module scanout_top #(
  parameter int HActive       = 128,  // timing: see scanout_video_timing.sv
  parameter int HFrontPorch   = 8,
  parameter int HSync         = 16,
  parameter int HBackPorch    = 8,
  parameter int VActive       = 128,
  parameter int VFrontPorch   = 2,
  parameter int VSync         = 2,
  parameter int VBackPorch    = 4,
  parameter int HSyncPositive = 0,
  parameter int VSyncPositive = 0,
  parameter int FbWidth       = 128,  // framebuffer size, px
  parameter int FbHeight      = 128,
  parameter int DacBits       = 8     // code width a channel
) (
  input  wire logic               clk_i,        // pixel clock
  input  wire logic               rst_ni,       // asynchronous reset, active low
  // Framebuffer read port (synchronous RAM, one pixel a clock).
  output      logic               fb_rd_o,      // read this cycle
  output      logic [31:0]        fb_addr_o,    // pixel index y * FbWidth + x
  input  wire logic [23:0]        fb_rdata_i,   // {R, G, B}, the cycle after fb_rd_o
  input  wire logic               fb_rvalid_i,  // fb_rdata_i holds the pixel asked for
  // Palette write port (host), one enable a channel.
  input  wire logic [2:0]         pal_we_i,     // write R, G, B palette
  input  wire logic [7:0]         pal_waddr_i,  // entry
  input  wire logic [DacBits-1:0] pal_wdata_i,  // code
  // Video out, to the DAC.
  output      logic               hsync_o,      // hsync wire level
  output      logic               vsync_o,      // vsync wire level
  output      logic               blank_o,      // BLANK: DAC held at 0 V
  output      logic [DacBits-1:0] dac_r_o,      // codes, 0 while blank
  output      logic [DacBits-1:0] dac_g_o,
  output      logic [DacBits-1:0] dac_b_o
);
  // Pixel clocks from a timing position to its video out: the framebuffer RAM's read
  // and the palette's, one each. Public: the testbench aligns the reference with it.
  localparam int Latency /*verilator public*/ = 2;
  // Derived: counter widths of the timing generator.
  localparam int HW = $clog2(HActive + HFrontPorch + HSync + HBackPorch);
  localparam int VW = $clog2(VActive + VFrontPorch + VSync + VBackPorch);

  logic [HW-1:0] hcount;
  logic [VW-1:0] vcount;
  logic          active, hsync, vsync;

  scanout_video_timing #(
    .HActive(HActive), .HFrontPorch(HFrontPorch), .HSync(HSync), .HBackPorch(HBackPorch),
    .VActive(VActive), .VFrontPorch(VFrontPorch), .VSync(VSync), .VBackPorch(VBackPorch),
    .HSyncPositive(HSyncPositive), .VSyncPositive(VSyncPositive)
  ) u_timing (
    .clk_i, .rst_ni,
    .hcount_o(hcount), .vcount_o(vcount), .active_o(active), .hsync_o(hsync), .vsync_o(vsync)
  );

  // ---- cycle 0: framebuffer read ----
  logic in_fb;
  assign in_fb     = ({{(32 - HW){1'b0}}, hcount} < FbWidth) && ({{(32 - VW){1'b0}}, vcount} < FbHeight);
  assign fb_rd_o   = active && in_fb;
  assign fb_addr_o = {{(32 - VW){1'b0}}, vcount} * FbWidth + {{(32 - HW){1'b0}}, hcount};

  // ---- cycle 1: data back, palette lookup ----
  logic rd_q, hsync_q, vsync_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      rd_q    <= 1'b0;
      hsync_q <= HSyncPositive == 0;  // idle level
      vsync_q <= VSyncPositive == 0;
    end else begin
      rd_q    <= fb_rd_o;
      hsync_q <= hsync;
      vsync_q <= vsync;
    end
  end

  logic [DacBits-1:0] code_r, code_g, code_b;
  scanout_palette #(.DacBits(DacBits)) u_pal_r (
    .clk_i, .we_i(pal_we_i[0]), .waddr_i(pal_waddr_i), .wdata_i(pal_wdata_i),
    .raddr_i(fb_rdata_i[23:16]), .rdata_o(code_r));
  scanout_palette #(.DacBits(DacBits)) u_pal_g (
    .clk_i, .we_i(pal_we_i[1]), .waddr_i(pal_waddr_i), .wdata_i(pal_wdata_i),
    .raddr_i(fb_rdata_i[15:8]), .rdata_o(code_g));
  scanout_palette #(.DacBits(DacBits)) u_pal_b (
    .clk_i, .we_i(pal_we_i[2]), .waddr_i(pal_waddr_i), .wdata_i(pal_wdata_i),
    .raddr_i(fb_rdata_i[7:0]), .rdata_o(code_b));

  // ---- cycle 2: video out ----
  logic blank_q, hsync_out_q, vsync_out_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      blank_q     <= 1'b1;
      hsync_out_q <= HSyncPositive == 0;
      vsync_out_q <= VSyncPositive == 0;
    end else begin
      blank_q     <= !(rd_q && fb_rvalid_i);
      hsync_out_q <= hsync_q;
      vsync_out_q <= vsync_q;
    end
  end

  assign blank_o = blank_q;
  assign hsync_o = hsync_out_q;
  assign vsync_o = vsync_out_q;
  assign dac_r_o = blank_q ? '0 : code_r;
  assign dac_g_o = blank_q ? '0 : code_g;
  assign dac_b_o = blank_q ? '0 : code_b;
endmodule

`default_nettype wire
