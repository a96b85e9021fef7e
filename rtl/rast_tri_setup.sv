// SPDX-License-Identifier: Apache-2.0
// rast_tri_setup: triangle setup of snapped fixed-point vertices (ref: model/ref/tri_setup.cpp).
//
// - Doubled signed area (exact, EdgeW bits); zero area is culled, and per cull_mode_i
//   the back or front faces (front_ccw_i says which winding is front).
// - Three edges E_i = a x + b y + c, edge i from vertex i to vertex i+1, negated for a
//   counter-clockwise triangle so the interior is E > 0; fill-rule bias per fill_rule_i
//   (1 = the edge does not own its samples: covered needs E - 1 >= 0).
// - Fill rule, cull mode and front face are run-time inputs (raster state, static while
//   the pipeline is busy), encoded as model/ref/raster_state.h's enums: fill rule
//   0 top_left, 1 bottom_right, 2 inclusive, 3 exclusive; cull 0 none, 1 back, 2 front.
// - Bounding box of the pixel centres inside the vertices' extent, widened by the
//   sample offsets' box (box_i, multisampling: a pixel is in the box when some sample
//   position centre + d_s may be inside; all zero with one sample), clipped to the clip
//   rectangle (viewport, framebuffer and scissor, given with every triangle); an empty
//   box is culled (nothing to traverse).
// - Timing: one triangle every SetupInterval cycles (setup.interval_cycles); a culled
//   triangle costs the same and produces nothing. A marker (a state command travelling
//   in order with the triangles) costs one cycle. The remaining latency
//   (setup.latency_cycles - interval) is the output FIFO's (rast_fifo Latency).
// - Attributes (colour, depth) pass through untouched (AttrW opaque bits).
`default_nettype none

module rast_tri_setup #(
  parameter int CoordW        = 24,  // N + 1
  parameter int CoordFrac     = 16,  // F
  parameter int CoefW         = 25,  // N + 2
  parameter int EdgeW         = 49,  // 2N + 3
  parameter int AreaW         = 48,  // 2N + 2
  parameter int PixelW        = 14,  // pixel index bits
  parameter int AttrW         = 8,   // pass-through attribute bits
  parameter int SampleOffW    = 17,  // sample offset bits, signed raw (F + 1)
  parameter int SetupInterval = 1    // cycles per triangle
) (
  input  wire logic                  clk_i,         // core clock
  input  wire logic                  rst_ni,        // asynchronous reset, active low
  input  wire logic [1:0]            fill_rule_i,   // 0 top_left, 1 bottom_right, 2 inclusive, 3 exclusive (static)
  input  wire logic [1:0]            cull_mode_i,   // 0 none, 1 back, 2 front (3: as none) (static)
  input  wire logic                  front_ccw_i,   // 1: counter-clockwise on screen is front (static)
  input  wire logic [4*SampleOffW-1:0] box_i,       // sample offset box {dy_max, dy_min, dx_max, dx_min}, raw (static)
  input  wire logic                  in_valid_i,    // triangle or marker in
  output      logic                  in_ready_o,    // taken this cycle
  input  wire logic                  in_marker_i,   // a marker, not a triangle
  input  wire logic [3*CoordW-1:0]   in_x_i,        // vertex k x at [k*CoordW +: CoordW], raw
  input  wire logic [3*CoordW-1:0]   in_y_i,        // vertex k y, raw
  input  wire logic [4*PixelW-1:0]   in_clip_i,     // clip rect {y1, x1, y0, x0}, half-open px
  input  wire logic [2*PixelW-1:0]   in_origin_i,   // pixel of raw (0, 0): {y, x}
  input  wire logic [AttrW-1:0]      in_attr_i,     // pass-through attributes
  output      logic                  out_valid_o,   // set-up triangle or marker out
  input  wire logic                  out_ready_i,   // taken this cycle
  output      logic                  out_marker_o,  // a marker
  output      logic [3*CoefW-1:0]    out_a_o,       // edge i a at [i*CoefW +: CoefW]
  output      logic [3*CoefW-1:0]    out_b_o,       // edge i b
  output      logic [3*EdgeW-1:0]    out_c_o,       // edge i c at [i*EdgeW +: EdgeW]
  output      logic [2:0]            out_bias_o,    // edge i: 1 = bias -1 (does not own)
  output      logic [AreaW-1:0]      out_area2_o,   // doubled area, > 0, unsigned
  output      logic [4*PixelW-1:0]   out_bbox_o,    // clipped box {y1, x1, y0, x0}
  output      logic [2*PixelW-1:0]   out_origin_o,  // as in_origin_i
  output      logic [AttrW-1:0]      out_attr_o,    // as in_attr_i
  output      logic                  busy_o,        // working on a triangle
  output      logic                  done_o         // finishes its current triangle or marker this cycle (stage statistics)
);
  localparam int CntW = $clog2(SetupInterval + 1);  // derived: interval counter bits
  localparam int BoxW = PixelW + CoordW + 2;         // derived: signed box arithmetic

  // ---- Hold registers: the triangle being set up when the interval is > 1 ----
  logic                busy_q;
  logic [CntW-1:0]     cnt_q;  // cycles left, including this one
  logic                hold_marker_q;
  logic [3*CoordW-1:0] hold_x_q, hold_y_q;
  logic [4*PixelW-1:0] hold_clip_q;
  logic [2*PixelW-1:0] hold_origin_q;
  logic [AttrW-1:0]    hold_attr_q;

  logic                cur_valid, cur_marker;
  logic [3*CoordW-1:0] cur_x, cur_y;
  logic [4*PixelW-1:0] cur_clip;
  logic [2*PixelW-1:0] cur_origin;
  logic [CntW-1:0]     in_cost, left;
  logic                last, culled, done;

  assign cur_valid  = busy_q || in_valid_i;
  assign cur_marker = busy_q ? hold_marker_q : in_marker_i;
  assign cur_x      = busy_q ? hold_x_q : in_x_i;
  assign cur_y      = busy_q ? hold_y_q : in_y_i;
  assign cur_clip   = busy_q ? hold_clip_q : in_clip_i;
  assign cur_origin = busy_q ? hold_origin_q : in_origin_i;
  assign out_attr_o = busy_q ? hold_attr_q : in_attr_i;
  assign out_origin_o = cur_origin;
  assign out_marker_o = cur_marker;

  assign in_cost = in_marker_i ? CntW'(1) : CntW'(SetupInterval);
  assign left    = busy_q ? cnt_q : in_cost;
  assign last    = (left == CntW'(1));
  assign out_valid_o = cur_valid && last && (cur_marker || !culled);
  assign done        = cur_valid && last && (!out_valid_o || out_ready_i);
  // A fresh triangle is taken at once when it needs several cycles (it moves to the
  // hold registers), or in its only cycle when that cycle completes.
  assign in_ready_o  = !busy_q && (!last || done);
  assign busy_o      = busy_q;
  assign done_o      = done;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      busy_q <= 1'b0;
      cnt_q  <= '0;
    end else if (!busy_q) begin
      if (in_valid_i && !last) begin
        busy_q <= 1'b1;
        cnt_q  <= in_cost - 1'b1;
      end
    end else if (!last) begin
      cnt_q <= cnt_q - 1'b1;
    end else if (done) begin
      busy_q <= 1'b0;
    end
  end

  always_ff @(posedge clk_i) begin
    if (!busy_q && in_valid_i && !last) begin
      hold_marker_q <= in_marker_i;
      hold_x_q      <= in_x_i;
      hold_y_q      <= in_y_i;
      hold_clip_q   <= in_clip_i;
      hold_origin_q <= in_origin_i;
      hold_attr_q   <= in_attr_i;
    end
  end

  // ---- Area, orientation, cull ----
  logic signed [CoordW-1:0] vx [3], vy [3];
  logic signed [EdgeW-1:0]  dx1, dy1, dx2, dy2, area2;
  logic                     neg, front, facing_culled;
  always_comb begin
    for (int k = 0; k < 3; k++) begin
      vx[k] = cur_x[k*CoordW +: CoordW];
      vy[k] = cur_y[k*CoordW +: CoordW];
    end
  end
  assign dx1   = EdgeW'(vx[1]) - EdgeW'(vx[0]);
  assign dy1   = EdgeW'(vy[1]) - EdgeW'(vy[0]);
  assign dx2   = EdgeW'(vx[2]) - EdgeW'(vx[0]);
  assign dy2   = EdgeW'(vy[2]) - EdgeW'(vy[0]);
  // |area2| <= L^2 < 2^(2N+2): exact in EdgeW bits although the products wrap.
  assign area2 = dx1 * dy2 - dy1 * dx2;
  assign neg   = area2[EdgeW-1];          // counter-clockwise on screen
  assign front = (neg == front_ccw_i);
  assign facing_culled = (cull_mode_i == 2'd1 && !front) || (cull_mode_i == 2'd2 && front);
  assign out_area2_o = neg ? AreaW'(-area2) : AreaW'(area2);

  // ---- Edges and fill-rule bias ----
  always_comb begin
    for (int i = 0; i < 3; i++) begin
      logic signed [CoefW-1:0] a, b;
      logic signed [EdgeW-1:0] c;
      logic                    owns;
      // Edge i from vertex i to j = i + 1: a = y_i - y_j, b = x_j - x_i (negated when
      // the triangle is counter-clockwise, so the interior is E > 0).
      a = neg ? CoefW'(vy[(i+1)%3]) - CoefW'(vy[i]) : CoefW'(vy[i]) - CoefW'(vy[(i+1)%3]);
      b = neg ? CoefW'(vx[i]) - CoefW'(vx[(i+1)%3]) : CoefW'(vx[(i+1)%3]) - CoefW'(vx[i]);
      c = -(EdgeW'(a) * EdgeW'(vx[i]) + EdgeW'(b) * EdgeW'(vy[i]));
      case (fill_rule_i)
        2'd0:    owns = (a > 0) || (a == 0 && b > 0);  // top-left
        2'd1:    owns = (a < 0) || (a == 0 && b < 0);  // bottom-right
        2'd2:    owns = 1'b1;                          // inclusive
        default: owns = 1'b0;                          // exclusive
      endcase
      out_a_o[i*CoefW +: CoefW] = a;
      out_b_o[i*CoefW +: CoefW] = b;
      out_c_o[i*EdgeW +: EdgeW] = c;
      out_bias_o[i] = !owns;
    end
  end

  // ---- Bounding box of covered pixel centres, clipped ----
  logic signed [BoxW-1:0] lo [2], hi [2], bmin [2], bmax [2], clip0 [2], clip1 [2];
  logic                   box_empty;
  always_comb begin
    box_empty = 1'b0;
    for (int d = 0; d < 2; d++) begin  // d = 0: x, 1: y
      logic signed [CoordW-1:0] v0, v1, v2, mn, mx;
      logic signed [BoxW-1:0]   org, half, mnw, mxw;
      logic signed [SampleOffW-1:0] dmin, dmax;
      v0 = d == 0 ? vx[0] : vy[0];
      v1 = d == 0 ? vx[1] : vy[1];
      v2 = d == 0 ? vx[2] : vy[2];
      mn = (v0 < v1) ? ((v0 < v2) ? v0 : v2) : ((v1 < v2) ? v1 : v2);
      mx = (v0 > v1) ? ((v0 > v2) ? v0 : v2) : ((v1 > v2) ? v1 : v2);
      dmin = box_i[(2*d)*SampleOffW +: SampleOffW];
      dmax = box_i[(2*d+1)*SampleOffW +: SampleOffW];
      // Sample s of pixel p sits at centre(p) + d_s: p may hold a covered sample when
      // centre(p) is in [mn - d_max, mx - d_min].
      mnw  = BoxW'(mn) - BoxW'(dmax);
      mxw  = BoxW'(mx) - BoxW'(dmin);
      org  = BoxW'(cur_origin[d*PixelW +: PixelW]);
      half = BoxW'(1) <<< (CoordFrac - 1);
      // First pixel whose centre is >= mnw: origin + ceil((mnw - 1/2) / 2^F);
      // last pixel whose centre is <= mxw: origin + floor((mxw - 1/2) / 2^F).
      lo[d] = org - ((half - mnw) >>> CoordFrac);
      hi[d] = org + ((mxw - half) >>> CoordFrac) + BoxW'(1);
      clip0[d] = BoxW'(cur_clip[d*PixelW +: PixelW]);
      clip1[d] = BoxW'(cur_clip[(d+2)*PixelW +: PixelW]);
      bmin[d] = (lo[d] > clip0[d]) ? lo[d] : clip0[d];
      bmax[d] = (hi[d] < clip1[d]) ? hi[d] : clip1[d];
      if (bmin[d] >= bmax[d]) box_empty = 1'b1;
      out_bbox_o[d*PixelW +: PixelW]     = PixelW'(bmin[d]);
      out_bbox_o[(d+2)*PixelW +: PixelW] = PixelW'(bmax[d]);
    end
  end

  assign culled = (area2 == '0) || facing_culled || box_empty;
endmodule

`default_nettype wire
