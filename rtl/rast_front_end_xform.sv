// SPDX-License-Identifier: Apache-2.0
// rast_front_end_xform: the geometry front end's per-vertex transform in binary32
// (docs/clip-space.md, "Operation order"): the division by w and the viewport transform
// of a clip-space vertex with w > 0, each operation rounded to nearest even, no fused
// multiply-add, bit-exact with the reference model's float arithmetic:
//     q   = 1 / w
//     x_w = (x * q) * (W / 2) + (X + W / 2)
//     y_w = (y * q) * (H / 2) + (Y + H / 2)
//     z_w = (z * q) * (F - N) + N
// - The primitive's state (viewport_xform X Y W H and depth_range N F, as binary32) is
//   held on its ports while the primitive's vertices pass; W / 2, H / 2, X + W / 2,
//   Y + H / 2 and F - N are computed from it (combinationally: they change once a
//   primitive, not a vertex).
// - Four pipeline stages, one per dependent operation: the reciprocal, x * q, the scale,
//   the offset. Latency 4 cycles, one vertex a cycle; the stages advance together while
//   the output is free (out_ready_i) or empty, so in_ready_o = out_ready_i || !out_valid_o.
// - Units per vertex: 1 rast_fp32_recip, 6 rast_fp32_mul, 3 rast_fp32_add; for the
//   primitive's state: 2 rast_fp32_mul, 3 rast_fp32_add.
`default_nettype none

module rast_front_end_xform (
  input  wire logic        clk_i,         // core clock
  input  wire logic        rst_ni,        // asynchronous reset, active low
  // The primitive's state, binary32, stable while its vertices pass.
  input  wire logic [31:0] vp_x_i,        // viewport_xform X (pixels)
  input  wire logic [31:0] vp_y_i,        // viewport_xform Y (pixels)
  input  wire logic [31:0] vp_w_i,        // viewport_xform W (pixels)
  input  wire logic [31:0] vp_h_i,        // viewport_xform H (pixels)
  input  wire logic [31:0] depth_near_i,  // depth_range N
  input  wire logic [31:0] depth_far_i,   // depth_range F
  // Clip-space vertices in (binary32).
  input  wire logic        in_valid_i,    // a vertex on x_i .. w_i
  output      logic        in_ready_o,    // it is taken this cycle
  input  wire logic [31:0] x_i,           // clip-space x
  input  wire logic [31:0] y_i,           // clip-space y
  input  wire logic [31:0] z_i,           // clip-space z
  input  wire logic [31:0] w_i,           // clip-space w (> 0 after clipping)
  // Window-space vertices out (binary32), 4 cycles after they entered.
  output      logic        out_valid_o,   // a vertex on x_w_o .. inv_w_o
  input  wire logic        out_ready_i,   // the consumer takes it this cycle
  output      logic [31:0] x_w_o,         // window x, pixels
  output      logic [31:0] y_w_o,         // window y, pixels (y down)
  output      logic [31:0] z_w_o,         // depth in [N, F]
  output      logic [31:0] inv_w_o        // q = 1 / w, the perspective weight
);
  localparam logic [31:0] Half = 32'h3F00_0000;  // binary32 0.5: W * 0.5 = W / 2 exactly rounded
  localparam logic [31:0] SignBit = 32'h8000_0000;

  // ---- The primitive's constants ----
  logic [31:0] half_w, half_h, center_x, center_y, depth_scale;
  rast_fp32_mul u_half_w (.a_i(vp_w_i), .b_i(Half), .f_o(half_w));
  rast_fp32_mul u_half_h (.a_i(vp_h_i), .b_i(Half), .f_o(half_h));
  rast_fp32_add u_center_x (.a_i(vp_x_i), .b_i(half_w), .f_o(center_x));
  rast_fp32_add u_center_y (.a_i(vp_y_i), .b_i(half_h), .f_o(center_y));
  rast_fp32_add u_depth_scale (.a_i(depth_far_i), .b_i(depth_near_i ^ SignBit), .f_o(depth_scale));  // F - N

  // ---- The pipeline: stage s's registers hold the results of operation s ----
  logic advance;  // every stage moves on this cycle
  logic v1_q, v2_q, v3_q, v4_q;  // stage holds a vertex (reset to empty)
  assign advance = out_ready_i || !v4_q;
  assign in_ready_o = advance;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) {v1_q, v2_q, v3_q, v4_q} <= 4'b0;
    else if (advance) {v1_q, v2_q, v3_q, v4_q} <= {in_valid_i, v1_q, v2_q, v3_q};
  end

  // Stage 1: q = 1 / w; x, y, z wait beside it.
  logic [31:0] q, q1_q, x1_q, y1_q, z1_q;
  rast_fp32_recip u_recip (.w_i(w_i), .f_o(q));
  // Stage 2: x * q, y * q, z * q.
  logic [31:0] xq, yq, zq, q2_q, xq2_q, yq2_q, zq2_q;
  rast_fp32_mul u_xq (.a_i(x1_q), .b_i(q1_q), .f_o(xq));
  rast_fp32_mul u_yq (.a_i(y1_q), .b_i(q1_q), .f_o(yq));
  rast_fp32_mul u_zq (.a_i(z1_q), .b_i(q1_q), .f_o(zq));
  // Stage 3: the scale, W / 2, H / 2, F - N.
  logic [31:0] xs, ys, zs, q3_q, xs3_q, ys3_q, zs3_q;
  rast_fp32_mul u_xs (.a_i(xq2_q), .b_i(half_w), .f_o(xs));
  rast_fp32_mul u_ys (.a_i(yq2_q), .b_i(half_h), .f_o(ys));
  rast_fp32_mul u_zs (.a_i(zq2_q), .b_i(depth_scale), .f_o(zs));
  // Stage 4: the offset, X + W / 2, Y + H / 2, N.
  logic [31:0] xw, yw, zw, q4_q, xw4_q, yw4_q, zw4_q;
  rast_fp32_add u_xw (.a_i(xs3_q), .b_i(center_x), .f_o(xw));
  rast_fp32_add u_yw (.a_i(ys3_q), .b_i(center_y), .f_o(yw));
  rast_fp32_add u_zw (.a_i(zs3_q), .b_i(depth_near_i), .f_o(zw));

  // Data registers load only with a vertex (no reset: read only while its valid is set).
  always_ff @(posedge clk_i) begin
    if (advance) begin
      if (in_valid_i) {q1_q, x1_q, y1_q, z1_q} <= {q, x_i, y_i, z_i};
      if (v1_q) {q2_q, xq2_q, yq2_q, zq2_q} <= {q1_q, xq, yq, zq};
      if (v2_q) {q3_q, xs3_q, ys3_q, zs3_q} <= {q2_q, xs, ys, zs};
      if (v3_q) {q4_q, xw4_q, yw4_q, zw4_q} <= {q3_q, xw, yw, zw};
    end
  end
  assign out_valid_o = v4_q;
  assign {x_w_o, y_w_o, z_w_o, inv_w_o} = {xw4_q, yw4_q, zw4_q, q4_q};
endmodule

`default_nettype wire
