// SPDX-License-Identifier: Apache-2.0
// rast_line: index-method line unit (Bresenham or midpoint, chosen per line).
//
// - Accepts one line (signed pixel indices of both end pixels) on a valid/ready stream.
// - Emits one pixel a cycle (x, y, last) in drawing order from (x0, y0) to (x1, y1), both
//   end pixels included.
// - Octants and direction as model/ref/line_raster.h: major axis x when |dY| <= |dX|
//   (ties x-major), else y; the notes' algorithm runs on (a, b) = (|d major|, |d minor|)
//   from the start endpoint and is reflected back (major = M0 + sM*i, minor = m0 + sm*j,
//   s = sign of the delta, +1 for 0).
// - Decision P1 = 2b - a; Bresenham steps the minor axis when P >= 0, midpoint when P > 0.
// Timing: 1 set-up cycle (the accept cycle) then max(|dX|, |dY|) + 1 pixels at 1/cycle.
`default_nettype none

module rast_line #(
  parameter int Width = 16  // bits of a signed pixel index
) (
  input  wire logic                    clk_i,        // core clock
  input  wire logic                    rst_ni,       // asynchronous reset, active low
  input  wire logic                    in_valid_i,   // a line is offered
  output      logic                    in_ready_o,   // the unit is idle and takes it
  input  wire logic signed [Width-1:0] x0_i,         // start pixel x index
  input  wire logic signed [Width-1:0] y0_i,         // start pixel y index
  input  wire logic signed [Width-1:0] x1_i,         // end pixel x index
  input  wire logic signed [Width-1:0] y1_i,         // end pixel y index
  input  wire logic                    midpoint_i,   // 1: midpoint (tie stays), 0: Bresenham
  output      logic                    out_valid_o,  // a pixel is presented
  input  wire logic                    out_ready_i,  // the consumer takes it
  output      logic signed [Width-1:0] out_x_o,      // pixel x index
  output      logic signed [Width-1:0] out_y_o,      // pixel y index
  output      logic                    out_last_o    // the line's end pixel
);
  // Derived: deltas need one more bit; the decision variable spans +-2*max(a, b).
  localparam int DW = Width + 1;  // bits of a delta / magnitude (derived)
  localparam int PW = Width + 3;  // bits of the decision variable (derived)

  // Set-up (combinational on the offered line).
  logic signed [DW-1:0] dx_c, dy_c, adx_c, ady_c;
  logic                 x_major_c;
  logic signed [DW-1:0] a_c, b_c;
  assign dx_c      = DW'(x1_i) - DW'(x0_i);
  assign dy_c      = DW'(y1_i) - DW'(y0_i);
  assign adx_c     = dx_c < 0 ? -dx_c : dx_c;
  assign ady_c     = dy_c < 0 ? -dy_c : dy_c;
  assign x_major_c = ady_c <= adx_c;
  assign a_c       = x_major_c ? adx_c : ady_c;
  assign b_c       = x_major_c ? ady_c : adx_c;

  // Walk state.
  logic                    busy_q;     // a line is being walked
  logic                    x_major_q;  // major axis is x
  logic                    neg_maj_q;  // major delta < 0
  logic                    neg_min_q;  // minor delta < 0
  logic                    tie_step_q; // Bresenham: step on P == 0
  logic signed [Width-1:0] maj_q;      // current major coordinate
  logic signed [Width-1:0] min_q;      // current minor coordinate
  logic        [DW-1:0]    left_q;     // pixels left after the current one
  logic signed [PW-1:0]    p_q;        // decision variable
  logic signed [PW-1:0]    inc_e_q;    // 2b: increment when staying
  logic signed [PW-1:0]    inc_d_q;    // 2b - 2a: increment when stepping

  logic step_c, fire_c, last_c;
  assign step_c = p_q > 0 || (p_q == 0 && tie_step_q);
  assign fire_c = busy_q && out_ready_i;
  assign last_c = left_q == '0;

  assign in_ready_o  = !busy_q;
  assign out_valid_o = busy_q;
  assign out_x_o     = x_major_q ? maj_q : min_q;
  assign out_y_o     = x_major_q ? min_q : maj_q;
  assign out_last_o  = last_c;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) busy_q <= 1'b0;
    else if (!busy_q) busy_q <= in_valid_i;
    else if (fire_c && last_c) busy_q <= 1'b0;
  end

  always_ff @(posedge clk_i) begin
    if (!busy_q && in_valid_i) begin
      x_major_q  <= x_major_c;
      neg_maj_q  <= x_major_c ? dx_c < 0 : dy_c < 0;
      neg_min_q  <= x_major_c ? dy_c < 0 : dx_c < 0;
      tie_step_q <= !midpoint_i;
      maj_q      <= x_major_c ? x0_i : y0_i;
      min_q      <= x_major_c ? y0_i : x0_i;
      left_q     <= a_c;
      p_q        <= 2 * PW'(b_c) - PW'(a_c);
      inc_e_q    <= 2 * PW'(b_c);
      inc_d_q    <= 2 * PW'(b_c) - 2 * PW'(a_c);
    end else if (fire_c && !last_c) begin
      maj_q  <= neg_maj_q ? maj_q - 1'b1 : maj_q + 1'b1;
      left_q <= left_q - 1'b1;
      if (step_c) begin
        min_q <= neg_min_q ? min_q - 1'b1 : min_q + 1'b1;
        p_q   <= p_q + inc_d_q;
      end else begin
        p_q <= p_q + inc_e_q;
      end
    end
  end
endmodule

`default_nettype wire
