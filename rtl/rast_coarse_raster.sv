// SPDX-License-Identifier: Apache-2.0
// rast_coarse_raster: tile walk with early-out / early-in (ref: model/ref/coarse_raster.cpp,
// classify_tile; model: model/sc/coarse_raster.cpp).
//
// - Walks, row by row, every tile (2^tile_log2_i pixels square, aligned to the
//   framebuffer origin) overlapping the triangle's clipped bounding box. A tile's
//   footprint is the tile clipped to the box.
// - Per edge, two corner evaluations of the footprint's pixel-centre grid, picked by
//   the signs of a and b: max(E) - bias < 0 on some edge rejects the tile; min(E) - bias
//   >= 0 on every edge accepts it whole; otherwise it is partial. With one sample
//   exact: the same samples and bias as the per-pixel test. With several (box_i, the
//   sample offsets' box; zero for one sample) the two corners move by the box,
//   (x_hi + dx_max, y_hi + dy_max) and (x_lo + dx_min, y_lo + dy_min), so both decisions
//   hold for every sample of the footprint (conservative, as ref classify_tile).
// - Timing: classifies TilesPerCycle tiles a cycle; rejected tiles cost only their
//   share of a cycle; an accepted or partial tile is pushed to the tile FIFO in the
//   cycle that classified it. With TilesPerCycle > 1, at most one surviving tile leaves
//   a cycle: the walk resumes after it the next cycle (docs/rtl.md). A triangle costs
//   max(1, cycles of its walk); a marker one cycle. The input is popped in the walk's
//   last cycle, so the head entry is the triangle being walked (no copy).
// - Hi-Z (rast_top, depth.hiz; docs/depth-culling.md "RTL"): every lane's footprint leaves
//   on lane_fp_o; rast_top answers, for each lane, lane_wait_i (a tile in flight to the
//   ROP touches its blocks: the table is not yet the one HizTracker tests against),
//   lane_cull_i and lane_accept_i (rast_hiz_test against the table). A culled lane that
//   need not wait is consumed like a rejected one (its slot taken, nothing sent); the first
//   lane neither rejected nor so culled stops the window: sent (with out_hiz_accept_o) when
//   it need not wait, else the walk moves to it without sending and tries it again next
//   cycle (its window starts there). Tied low, the walk is the one above.
`default_nettype none

module rast_coarse_raster #(
  parameter int CoordW        = 24,  // N + 1
  parameter int CoordFrac     = 16,  // F
  parameter int CoefW         = 25,  // N + 2
  parameter int EdgeW         = 49,  // 2N + 3
  parameter int PixelW        = 14,  // pixel index bits
  parameter int TileLog2W     = 3,   // tile_log2_i bits
  parameter int SampleOffW    = 17,  // sample offset bits, signed raw (F + 1)
  parameter int TilesPerCycle = 1    // tiles classified per cycle
) (
  input  wire logic                 clk_i,         // core clock
  input  wire logic                 rst_ni,        // asynchronous reset, active low
  input  wire logic [TileLog2W-1:0] tile_log2_i,   // log2 tile size, 1..TileLog2Max (static)
  input  wire logic [4*SampleOffW-1:0] box_i,      // sample offset box {dy_max, dy_min, dx_max, dx_min} (static)
  input  wire logic                 in_valid_i,    // set-up triangle or marker at the head
  output      logic                 in_ready_o,    // pop the head (last cycle of its walk)
  input  wire logic                 in_marker_i,   // head is a marker
  input  wire logic [3*CoefW-1:0]   in_a_i,        // edge a (rast_tri_setup layout)
  input  wire logic [3*CoefW-1:0]   in_b_i,        // edge b
  input  wire logic [3*EdgeW-1:0]   in_c_i,        // edge c
  input  wire logic [2:0]           in_bias_i,     // 1 = bias -1
  input  wire logic [4*PixelW-1:0]  in_bbox_i,     // clipped box {y1, x1, y0, x0}
  input  wire logic [2*PixelW-1:0]  in_origin_i,   // pixel of raw (0, 0): {y, x}
  output      logic                 out_valid_o,   // surviving tile or marker
  input  wire logic                 out_ready_i,   // tile FIFO takes it
  output      logic                 out_marker_o,  // a marker
  output      logic                 out_accepted_o,  // 1 accepted (early-in), 0 partial
  output      logic [4*PixelW-1:0]  out_fp_o,      // footprint {y1, x1, y0, x0}
  output      logic                 busy_o,        // a walk is in progress
  // Hi-Z hooks (rast_top; tied low without a table).
  output      logic [TilesPerCycle*4*PixelW-1:0] lane_fp_o,  // lane j's footprint at [j*4*PixelW +: 4*PixelW]
  output      logic [TilesPerCycle-1:0] lane_keep_o,   // lane j holds a triangle's tile not rejected (Hi-Z tests it)
  input  wire logic [TilesPerCycle-1:0] lane_wait_i,   // lane j's blocks have a tile in flight
  input  wire logic [TilesPerCycle-1:0] lane_cull_i,   // lane j culled (valid when not waiting)
  input  wire logic [TilesPerCycle-1:0] lane_accept_i, // lane j accepted (minmax)
  output      logic                 out_hiz_accept_o,  // the tile sent was accepted: the ROP tests it with always
  output      logic [$clog2(TilesPerCycle+1)-1:0] hiz_culled_o  // culled tiles consumed this cycle
);
  localparam int Lanes = TilesPerCycle;  // derived: tiles looked at per cycle

  // The sample offset box, sign-extended to coordinates (|d| <= 2^(F-1): a corner moved
  // by it stays inside the format, docs/rtl.md).
  logic [CoordW-1:0] box_c [4];
  always_comb
    for (int k = 0; k < 4; k++)
      box_c[k] = {{(CoordW - SampleOffW){box_i[k*SampleOffW + SampleOffW - 1]}}, box_i[k*SampleOffW +: SampleOffW]};

  logic [PixelW-1:0] bx0, by0, bx1, by1, ox, oy;
  logic [PixelW-1:0] tx_first, ty_first, tx_last, ty_last;  // tile index range, inclusive
  assign bx0 = in_bbox_i[0 +: PixelW];
  assign by0 = in_bbox_i[PixelW +: PixelW];
  assign bx1 = in_bbox_i[2*PixelW +: PixelW];
  assign by1 = in_bbox_i[3*PixelW +: PixelW];
  assign ox  = in_origin_i[0 +: PixelW];
  assign oy  = in_origin_i[PixelW +: PixelW];
  assign tx_first = bx0 >> tile_log2_i;
  assign ty_first = by0 >> tile_log2_i;
  assign tx_last  = (bx1 - 1'b1) >> tile_log2_i;
  assign ty_last  = (by1 - 1'b1) >> tile_log2_i;

  // ---- Walk position: the next tile to classify ----
  logic              walking_q;
  logic [PixelW-1:0] tx_q, ty_q;

  // Lane j looks at the j-th tile from the walk position, in walk order.
  logic [PixelW-1:0] lane_tx [Lanes+1], lane_ty [Lanes+1];
  logic [Lanes-1:0]  lane_in, lane_keep, lane_acc;
  logic [PixelW-1:0] lane_fp [Lanes][4];

  always_comb begin
    lane_tx[0] = walking_q ? tx_q : tx_first;
    lane_ty[0] = walking_q ? ty_q : ty_first;
    for (int j = 0; j < Lanes; j++) begin
      lane_in[j] = (lane_ty[j] <= ty_last);
      if (lane_tx[j] == tx_last) begin
        lane_tx[j+1] = tx_first;
        lane_ty[j+1] = lane_ty[j] + 1'b1;
      end else begin
        lane_tx[j+1] = lane_tx[j] + 1'b1;
        lane_ty[j+1] = lane_ty[j];
      end
    end
  end

  for (genvar j = 0; j < Lanes; j++) begin : g_lane
    logic [PixelW-1:0] x0, y0, x1, y1, tile_x0, tile_y0, tile_x1, tile_y1;
    logic [CoordW-1:0] cx_lo, cx_hi, cy_lo, cy_hi, sx_lo, sx_hi, sy_lo, sy_hi;
    logic [2:0]        reject, covers;
    assign tile_x0 = lane_tx[j] << tile_log2_i;
    assign tile_y0 = lane_ty[j] << tile_log2_i;
    assign tile_x1 = (lane_tx[j] + 1'b1) << tile_log2_i;
    assign tile_y1 = (lane_ty[j] + 1'b1) << tile_log2_i;
    assign x0 = (tile_x0 > bx0) ? tile_x0 : bx0;
    assign y0 = (tile_y0 > by0) ? tile_y0 : by0;
    assign x1 = (tile_x1 < bx1 && tile_x1 != '0) ? tile_x1 : bx1;  // != 0: wrapped past the top
    assign y1 = (tile_y1 < by1 && tile_y1 != '0) ? tile_y1 : by1;
    rast_sample #(.PixelW(PixelW), .CoordW(CoordW), .CoordFrac(CoordFrac)) u_sx_lo (.p_i(x0), .origin_i(ox), .s_o(cx_lo));
    rast_sample #(.PixelW(PixelW), .CoordW(CoordW), .CoordFrac(CoordFrac)) u_sx_hi (.p_i(x1 - 1'b1), .origin_i(ox), .s_o(cx_hi));
    rast_sample #(.PixelW(PixelW), .CoordW(CoordW), .CoordFrac(CoordFrac)) u_sy_lo (.p_i(y0), .origin_i(oy), .s_o(cy_lo));
    rast_sample #(.PixelW(PixelW), .CoordW(CoordW), .CoordFrac(CoordFrac)) u_sy_hi (.p_i(y1 - 1'b1), .origin_i(oy), .s_o(cy_hi));
    assign sx_lo = cx_lo + box_c[0];
    assign sx_hi = cx_hi + box_c[1];
    assign sy_lo = cy_lo + box_c[2];
    assign sy_hi = cy_hi + box_c[3];
    for (genvar i = 0; i < 3; i++) begin : g_edge
      logic signed [CoefW-1:0] a, b;
      logic signed [EdgeW-1:0] e_max, e_min, e_max_b, e_min_b;  // E, E + bias
      assign a = in_a_i[i*CoefW +: CoefW];
      assign b = in_b_i[i*CoefW +: CoefW];
      // Largest E at the corner the gradient points to, smallest at the opposite one.
      rast_edge_eval #(.CoordW(CoordW), .CoefW(CoefW), .EdgeW(EdgeW)) u_max (
        .a_i(a), .b_i(b), .c_i(in_c_i[i*EdgeW +: EdgeW]),
        .x_i(a >= 0 ? sx_hi : sx_lo), .y_i(b >= 0 ? sy_hi : sy_lo), .e_o(e_max));
      rast_edge_eval #(.CoordW(CoordW), .CoefW(CoefW), .EdgeW(EdgeW)) u_min (
        .a_i(a), .b_i(b), .c_i(in_c_i[i*EdgeW +: EdgeW]),
        .x_i(a >= 0 ? sx_lo : sx_hi), .y_i(b >= 0 ? sy_lo : sy_hi), .e_o(e_min));
      assign e_max_b   = e_max - EdgeW'(in_bias_i[i]);
      assign e_min_b   = e_min - EdgeW'(in_bias_i[i]);
      assign reject[i] = e_max_b[EdgeW-1];   // max(E + bias) < 0
      assign covers[i] = !e_min_b[EdgeW-1];  // min(E + bias) >= 0
    end
    assign lane_keep[j] = lane_in[j] && (reject == 3'b000);
    assign lane_acc[j]  = (covers == 3'b111);
    assign lane_fp[j][0] = x0;
    assign lane_fp[j][1] = y0;
    assign lane_fp[j][2] = x1;
    assign lane_fp[j][3] = y1;
    assign lane_fp_o[j*4*PixelW +: 4*PixelW] = {y1, x1, y0, x0};
  end

  // ---- The first surviving lane this cycle, and where the walk goes next ----
  // A lane stops the window when it is kept and not culled with a fresh table (a lane
  // that must wait stops it whatever its test says). hold: the stopping lane waits.
  logic             found, hold, walk_done, advance;
  logic [PixelW-1:0] next_tx, next_ty;
  logic [Lanes-1:0] lane_stop, lane_culled;
  localparam int CullW = $clog2(Lanes + 1);  // derived: hiz_culled_o bits
  logic [CullW-1:0] culled_n;
  assign lane_keep_o = in_valid_i && !in_marker_i ? lane_keep : '0;
  assign lane_stop = lane_keep & ~(lane_cull_i & ~lane_wait_i);
  assign lane_culled = lane_keep & lane_cull_i & ~lane_wait_i;
  always_comb begin
    found = 1'b0;
    hold = 1'b0;
    out_accepted_o = 1'b0;
    out_hiz_accept_o = 1'b0;
    out_fp_o = '0;
    next_tx = lane_tx[Lanes];
    next_ty = lane_ty[Lanes];
    culled_n = '0;
    for (int j = Lanes - 1; j >= 0; j--) begin
      if (lane_stop[j]) begin
        found = 1'b1;
        hold = lane_wait_i[j];
        out_accepted_o = lane_acc[j];
        out_hiz_accept_o = lane_accept_i[j];
        out_fp_o = {lane_fp[j][3], lane_fp[j][2], lane_fp[j][1], lane_fp[j][0]};
        next_tx = lane_wait_i[j] ? lane_tx[j] : lane_tx[j+1];
        next_ty = lane_wait_i[j] ? lane_ty[j] : lane_ty[j+1];
        culled_n = '0;
      end else if (lane_culled[j]) begin
        culled_n = culled_n + 1'b1;  // lanes before the stopping one (all when none stops)
      end
    end
  end
  assign walk_done    = (next_ty > ty_last);
  assign out_marker_o = in_marker_i;
  assign out_valid_o  = in_valid_i && (in_marker_i || (found && !hold));
  assign advance      = in_valid_i && (!out_valid_o || out_ready_i);
  assign in_ready_o   = advance && (in_marker_i || walk_done);
  assign busy_o       = walking_q;
  assign hiz_culled_o = advance && !in_marker_i ? culled_n : '0;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      walking_q <= 1'b0;
      tx_q <= '0;
      ty_q <= '0;
    end else if (advance) begin
      walking_q <= !in_ready_o;
      tx_q <= next_tx;
      ty_q <= next_ty;
    end
  end
endmodule

`default_nettype wire
