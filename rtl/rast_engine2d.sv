// SPDX-License-Identifier: Apache-2.0
// rast_engine2d: the 2D engine. Executes the 2D front end's operations (model/ref/draw2d.h,
// Op2d) with the pattern (rast_pattern) and ROP3 (rast_rop3) on a framebuffer port; index
// lines walk through its line unit (rast_line). docs/rtl-2d.md; timing as
// TimingParams::engine2d_op_cycles (docs/2d.md, "Timing").
//
// - Operation port (valid/ready): kind 0 span (row y0, [x0, x1), clipped), 1 pixel
//   (x0, y0), 2 line (x0, y0) -> (x1, y1), 3 blit (w x h from (sx, sy) to (x0, y0),
//   clipped). An operation taken in cycle t works in cycles t+1 .. t+C (C its cost) and
//   the next may be taken in cycle t+C: back to back, no bubble.
// - A beat writes up to lanes_i pixels of one row (span) or one pixel (pixel, line,
//   blit). A beat whose ROP3 code reads D takes rmw_i cycles (read, wait, write in the
//   last), else 1.
//   span: span_setup_i cycles, then ceil(n / lanes_i) beats;
//   pixel: one beat, written when inside the clip box;
//   line: 1 cycle to load the line unit, then one beat a pixel, clipped pixels walked;
//   blit: per row span_setup_i cycles, then a byte-credit gate: each cycle adds
//   blit_bytes_i, a pixel moves when the credit reaches its bytes (4 + 4 per S and D
//   read), at most one a cycle, so a row of w takes max(w, ceil(w * bytes / blit_bytes_i))
//   cycles. Rows bottom to top when the copy moves down, pixels right to left when it
//   moves right along its rows.
// - Memory port (docs/rtl-2d.md, "Memory port"): a read channel and a write channel,
//   each valid/ready, on the addresses mem_x_o/mem_y_o (lane k at x + k) and
//   mem_sx_o/mem_sy_o (blit source), which hold while a request waits. A read asks for D
//   of the lanes in rd_lanes_o and S when rd_src_o; its response (rd_rvalid_i with
//   rd_d_i, rd_s_i) may come in the cycle the read is taken (a memory that answers at
//   once) or any number of cycles later. A write carries byte enables (3 a lane) and the
//   operation's last write is marked (wr_last_o). The engine stalls until a read is
//   answered and a write taken: a beat whose code reads D sends its read in its first
//   cycle and writes in its last, or later when the response or the write's ready comes
//   late; a blit pixel reads and writes when its credit fires, held until both are done.
//   With a memory that takes every request and answers at once the timing above holds
//   cycle for cycle.
`default_nettype none

module rast_engine2d #(
  // Public: the testbench checks them against its table (model/rtlsim/rtl_params.cpp,
  // Engine2dRtlParams), which takes LanesMax from the config schema.
  parameter int Width    /*verilator public*/ = 20,  // bits of a signed pixel index
  parameter int LanesMax /*verilator public*/ = 8    // largest engine2d.fill_pixels_per_cycle
) (
  input  wire logic                       clk_i,            // core clock
  input  wire logic                       rst_ni,           // asynchronous reset, active low
  // Timing (run-time, from the config: engine2d.*)
  input  wire logic [3:0]                 lanes_i,          // fill_pixels_per_cycle, 1..LanesMax
  input  wire logic [6:0]                 span_setup_i,     // span_setup_cycles, 0..64
  input  wire logic [4:0]                 rmw_i,            // rmw_cycles, 2..16
  input  wire logic [3:0]                 blit_bytes_i,     // blit_bytes_per_cycle, 1..8
  // The command's paint state (held while its operations run)
  input  wire logic [7:0]                 rop3_i,           // ROP3 code
  input  wire logic [23:0]                fg_i,             // current colour {b, g, r}
  input  wire logic [23:0]                bg_i,             // bgcolor {b, g, r}
  input  wire logic [63:0]                pattern_i,        // 8x8 pattern, row 0 in bits 63:56
  input  wire logic                       pattern_solid_i,  // pattern solid: fg everywhere
  input  wire logic signed [Width-1:0]    clip_x0_i,        // clip box [x0, x1) x [y0, y1)
  input  wire logic signed [Width-1:0]    clip_y0_i,
  input  wire logic signed [Width-1:0]    clip_x1_i,
  input  wire logic signed [Width-1:0]    clip_y1_i,
  // Operation port
  input  wire logic                       in_valid_i,
  output      logic                       in_ready_o,
  input  wire logic [1:0]                 op_kind_i,        // 0 span, 1 pixel, 2 line, 3 blit
  input  wire logic [1:0]                 op_paint_i,       // span P: 0 pattern, 1 fg, 2 bg
  input  wire logic                       op_midpoint_i,    // line: midpoint (1) or Bresenham
  input  wire logic signed [Width-1:0]    op_x0_i,
  input  wire logic signed [Width-1:0]    op_y0_i,
  input  wire logic signed [Width-1:0]    op_x1_i,
  input  wire logic signed [Width-1:0]    op_y1_i,
  input  wire logic signed [Width-1:0]    op_sx_i,
  input  wire logic signed [Width-1:0]    op_sy_i,
  input  wire logic        [Width-1:0]    op_w_i,
  input  wire logic        [Width-1:0]    op_h_i,
  // Memory port: addresses (both channels)
  output      logic signed [Width-1:0]    mem_x_o,          // destination of lane 0
  output      logic signed [Width-1:0]    mem_y_o,
  output      logic signed [Width-1:0]    mem_sx_o,         // blit source
  output      logic signed [Width-1:0]    mem_sy_o,
  // Read request and response
  output      logic                       rd_valid_o,
  input  wire logic                       rd_ready_i,
  output      logic [LanesMax-1:0]        rd_lanes_o,       // D read of lane k
  output      logic                       rd_src_o,         // S read (blit)
  input  wire logic                       rd_rvalid_i,      // the response: in or after the read's cycle
  input  wire logic [LanesMax*24-1:0]     rd_d_i,           // D of each lane {b, g, r}
  input  wire logic [23:0]                rd_s_i,           // S {b, g, r}
  // Write request
  output      logic                       wr_valid_o,
  input  wire logic                       wr_ready_i,
  output      logic [LanesMax*3-1:0]      wr_be_o,          // lane k's bytes at 3k .. 3k+2 ({b, g, r} low first)
  output      logic [LanesMax*24-1:0]     wr_data_o,
  output      logic                       wr_last_o,        // the operation's last write
  output      logic                       idle_o            // no operation in progress
);
  typedef enum logic [2:0] {Idle, Setup, Span, Pixel, LineLoad, Line, Blit} state_e;

  localparam int CW = 8;  // bits of the blit byte credit (< 2 * 12)
  // Credit kept at most this: a pixel needs at most 12 bytes and one moves a cycle at
  // most, so a larger credit changes no firing (and a code reading 4 or 8 bytes a pixel
  // at 8 bytes a cycle would otherwise grow it by up to 4 a cycle until it wrapped).
  localparam logic [CW-1:0] CreditMax = CW'(16);

  state_e                  state_q;
  logic [1:0]              kind_q, paint_q;
  logic                    midpoint_q;
  logic signed [Width-1:0] x_q, y_q, x1_q, y1_q, sx_q, sy_q;
  logic        [Width-1:0] left_q;      // span: pixels left; blit: pixels left in the row
  logic        [Width-1:0] w_q, h_q;    // blit size
  logic        [Width-1:0] i_q, j_q;    // blit pixel in row, row
  logic        [6:0]       setup_q;     // set-up cycles left
  logic        [4:0]       wait_q;      // cycles into the current beat
  logic        [CW-1:0]    credit_q;    // blit byte credit

  // ROP3 operand use, and the beat length.
  logic reads_d_c, reads_s_c;
  assign reads_d_c = ((rop3_i >> 1) & 8'h55) != (rop3_i & 8'h55);
  assign reads_s_c = ((rop3_i >> 2) & 8'h33) != (rop3_i & 8'h33);
  logic [4:0] beat_len_c;
  assign beat_len_c = reads_d_c ? rmw_i : 5'd1;
  logic beat_end_c;  // the current beat writes this cycle
  assign beat_end_c = wait_q + 5'd1 == beat_len_c;

  // Blit bytes per pixel and the credit gate.
  logic [CW-1:0] blit_pixel_bytes_c, credit_next_c;
  logic          blit_fire_c;
  assign blit_pixel_bytes_c = CW'(4) + (reads_s_c ? CW'(4) : CW'(0)) + (reads_d_c ? CW'(4) : CW'(0));
  assign credit_next_c      = credit_q + CW'(blit_bytes_i);
  assign blit_fire_c        = credit_next_c >= blit_pixel_bytes_c;
  logic [CW-1:0] credit_left_c;  // after a pixel moves, saturated at CreditMax
  assign credit_left_c = (credit_next_c - blit_pixel_bytes_c > CreditMax) ? CreditMax
                                                                          : credit_next_c - blit_pixel_bytes_c;

  // Blit walk order: rows up when the copy moves down, right to left when it moves right
  // along the same rows.
  logic rows_up_q, right_to_left_q;
  logic [Width-1:0] bx_c, by_c;  // offset of the current blit pixel in the rectangle
  assign bx_c = right_to_left_q ? w_q - 1'b1 - i_q : i_q;
  assign by_c = rows_up_q ? h_q - 1'b1 - j_q : j_q;

  // The line unit.
  logic                    line_in_ready, line_out_valid, line_out_ready, line_last;
  logic signed [Width-1:0] line_x, line_y;
  rast_line #(.Width(Width)) u_line (
    .clk_i, .rst_ni,
    .in_valid_i(state_q == LineLoad), .in_ready_o(line_in_ready),
    .x0_i(x_q), .y0_i(y_q), .x1_i(x1_q), .y1_i(y1_q), .midpoint_i(midpoint_q),
    .out_valid_o(line_out_valid), .out_ready_i(line_out_ready),
    .out_x_o(line_x), .out_y_o(line_y), .out_last_o(line_last));
  assign line_out_ready = state_q == Line && beat_end_c && go_c;

  // Lanes of this beat (span only; the others use lane 0).
  logic [Width-1:0] lanes_c;
  assign lanes_c = left_q < Width'(lanes_i) ? left_q : Width'(lanes_i);

  // Addresses.
  always_comb begin
    mem_x_o  = x_q;
    mem_y_o  = y_q;
    mem_sx_o = sx_q + $signed(bx_c);
    mem_sy_o = sy_q + $signed(by_c);
    unique case (state_q)
      Line:    begin mem_x_o = line_x; mem_y_o = line_y; end
      Blit:    begin mem_x_o = x_q + $signed(bx_c); mem_y_o = y_q + $signed(by_c); end
      default: ;
    endcase
  end

  logic inside_c;  // lane 0 inside the clip box (pixels and line pixels)
  assign inside_c = mem_x_o >= clip_x0_i && mem_x_o < clip_x1_i && mem_y_o >= clip_y0_i && mem_y_o < clip_y1_i;

  // The memory port's read: which beats read, the request, and the data (held from the
  // response, or the response itself in the cycle it comes).
  logic [LanesMax-1:0]     lane_c;       // lanes this beat reads and writes
  logic                    act_c;        // the beat's write cycle (a blit pixel: its firing)
  logic                    go_c;         // the engine moves on this cycle: no access, or the write taken
  logic                    needs_read_c; // the current beat reads D or S
  logic                    rd_taken_q;   // the beat's read was taken, its response not yet come
  logic                    have_q;       // the beat's response is held in d_q, s_q
  logic [LanesMax*24-1:0]  d_q, d_c;
  logic [23:0]             s_q, s_c;
  logic                    rsp_c;        // the beat's response comes this cycle
  logic                    data_ok_c;    // the beat's write has its data
  always_comb begin
    needs_read_c = 1'b0;
    unique case (state_q)
      Span, Pixel: needs_read_c = reads_d_c;
      Line:        needs_read_c = reads_d_c && line_out_valid;
      Blit:        needs_read_c = (reads_d_c || reads_s_c) && blit_fire_c;
      default: ;
    endcase
  end
  assign rd_valid_o = needs_read_c && !rd_taken_q && !have_q;
  assign rd_lanes_o = reads_d_c ? lane_c : '0;
  assign rd_src_o   = state_q == Blit && reads_s_c;
  assign rsp_c      = rd_rvalid_i && !have_q && (rd_taken_q || (rd_valid_o && rd_ready_i));
  assign d_c        = have_q ? d_q : rd_d_i;
  assign s_c        = have_q ? s_q : rd_s_i;
  assign data_ok_c  = !needs_read_c || have_q || rsp_c;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      rd_taken_q <= 1'b0;
      have_q     <= 1'b0;
    end else if (act_c && go_c) begin  // the beat's write taken: the next beat reads anew
      rd_taken_q <= 1'b0;
      have_q     <= 1'b0;
    end else begin
      if (rd_valid_o && rd_ready_i && !rsp_c) rd_taken_q <= 1'b1;
      if (rsp_c) begin
        rd_taken_q <= 1'b0;
        have_q     <= 1'b1;
      end
    end
  end
  always_ff @(posedge clk_i) if (rsp_c) begin
    d_q <= rd_d_i;
    s_q <= rd_s_i;
  end

  // Pattern and ROP3 per lane.
  logic [63:0] pattern_c;
  always_comb begin
    pattern_c = pattern_i;
    if (pattern_solid_i) pattern_c = '1;
    if (state_q == Span && paint_q == 2'd1) pattern_c = '1;
    if (state_q == Span && paint_q == 2'd2) pattern_c = '0;
  end
  for (genvar k = 0; k < LanesMax; k++) begin : g_lane
    logic [2:0]       lx;  // lane x mod 8
    logic [23:0]      p, r;
    logic             rd, rs;
    assign lx = mem_x_o[2:0] + 3'(k);
    rast_pattern #(.Width(24)) u_pattern (
      .pattern_i(pattern_c), .x_i(lx), .y_i(mem_y_o[2:0]), .fg_i, .bg_i, .p_o(p));
    rast_rop3 #(.Width(24)) u_rop3 (
      .code_i(rop3_i), .p_i(p), .s_i(state_q == Blit ? s_c : 24'd0), .d_i(d_c[k*24 +: 24]),
      .r_o(r), .reads_d_o(rd), .reads_s_o(rs));
    assign wr_data_o[k*24 +: 24] = r;
    assign lane_c[k]            = state_q == Span ? Width'(k) < lanes_c : (k == 0 && (state_q == Blit || inside_c));
    assign wr_be_o[k*3 +: 3]    = {3{lane_c[k]}};
    wire unused_ok = &{1'b0, rd, rs};
  end

  // Writes, and the operation's last cycle.
  logic last_c;
  always_comb begin
    act_c    = 1'b0;
    last_c   = 1'b0;
    unique case (state_q)
      Span:  begin act_c = beat_end_c; last_c = beat_end_c && left_q <= Width'(lanes_i); end
      Pixel: begin act_c = beat_end_c; last_c = beat_end_c; end
      Line:  begin act_c = beat_end_c && line_out_valid; last_c = beat_end_c && line_last; end
      Blit:  begin
        act_c    = blit_fire_c;
        last_c   = blit_fire_c && i_q + 1'b1 == w_q && j_q + 1'b1 == h_q;
      end
      default: ;
    endcase
  end

  assign wr_valid_o = act_c && data_ok_c;
  assign wr_last_o  = last_c;
  assign go_c       = !act_c || (wr_valid_o && wr_ready_i);
  assign in_ready_o = state_q == Idle || (last_c && go_c);
  assign idle_o     = state_q == Idle;

  // The first state of a taken operation.
  function automatic state_e first_state(input logic [1:0] kind, input logic [6:0] setup);
    unique case (kind)
      2'd0:    first_state = setup != 0 ? Setup : Span;
      2'd1:    first_state = Pixel;
      2'd2:    first_state = LineLoad;
      default: first_state = setup != 0 ? Setup : Blit;
    endcase
  endfunction

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      state_q <= Idle;
    end else if (in_valid_i && in_ready_o) begin
      state_q <= first_state(op_kind_i, span_setup_i);
    end else if (go_c) begin
      unique case (state_q)
        Setup:    if (setup_q == 7'd1) state_q <= kind_q == 2'd0 ? Span : Blit;
        LineLoad: state_q <= Line;
        Blit:     if (blit_fire_c && i_q + 1'b1 == w_q && span_setup_i != 0) state_q <= last_c ? Idle : Setup;
                  else if (last_c) state_q <= Idle;
        default:  if (last_c) state_q <= Idle;
      endcase
    end
  end

  always_ff @(posedge clk_i) begin
    if (in_valid_i && in_ready_o) begin
      kind_q          <= op_kind_i;
      paint_q         <= op_paint_i;
      midpoint_q      <= op_midpoint_i;
      x_q             <= op_x0_i;
      y_q             <= op_y0_i;
      x1_q            <= op_x1_i;
      y1_q            <= op_y1_i;
      sx_q            <= op_sx_i;
      sy_q            <= op_sy_i;
      w_q             <= op_w_i;
      h_q             <= op_h_i;
      left_q          <= Width'(op_x1_i - op_x0_i);
      i_q             <= '0;
      j_q             <= '0;
      setup_q         <= span_setup_i;
      wait_q          <= '0;
      credit_q        <= '0;
      rows_up_q       <= op_y0_i > op_sy_i;
      right_to_left_q <= op_y0_i == op_sy_i && op_x0_i > op_sx_i;
    end else if (go_c) begin
      unique case (state_q)
        Setup: setup_q <= setup_q - 1'b1;
        Span: begin
          wait_q <= beat_end_c ? '0 : wait_q + 1'b1;
          if (beat_end_c) begin
            x_q    <= x_q + $signed(lanes_c);
            left_q <= left_q - lanes_c;
          end
        end
        Pixel, Line: wait_q <= beat_end_c ? '0 : wait_q + 1'b1;
        Blit: begin
          credit_q <= blit_fire_c ? credit_left_c : credit_next_c;
          if (blit_fire_c) begin
            if (i_q + 1'b1 == w_q) begin  // row done: the next row starts with its set-up
              i_q      <= '0;
              j_q      <= j_q + 1'b1;
              setup_q  <= span_setup_i;
              credit_q <= '0;
            end else begin
              i_q <= i_q + 1'b1;
            end
          end
        end
        default: ;
      endcase
    end
  end

  wire unused_ok = &{1'b0, line_in_ready};
endmodule

`default_nettype wire
