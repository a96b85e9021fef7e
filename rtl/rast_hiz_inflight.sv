// SPDX-License-Identifier: Apache-2.0
// rast_hiz_inflight: Hi-Z's interlock in rast_top (docs/depth-culling.md "The interlock").
// The tiles (and markers) coarse raster has sent and the ROP has not finished, so that a
// tile is tested only against blocks no tile in flight will still write: then rast_hiz
// holds exactly the writes HizTracker (model/ref/hiz.h) applies at zero lag, and every
// decision is the reference's.
//
// - An entry a tile sent (push_*): its footprint's block range {by1, bx1, by0, bx0}
//   (inclusive, block coordinates) and its Hi-Z accept; a marker's entry covers every
//   block (a depth clear reaches the table only at the ROP).
// - An entry ends when fine raster drops its tile (no covered pixel: fine_valid_i with
//   fine_drop_i, fine raster's tiles in send order) or when the ROP ends it (rop_end_i:
//   a batch's last group decided, its depth writes into rast_hiz in the same cycle, or a
//   marker taken): the ROP ends the oldest entry not yet ended, since it takes batches in
//   order and fine raster drops a tile before the ROP sees any later one.
// - Queries (combinational): wait_o[n] when an entry not ended overlaps query n's blocks.
//   An entry pushed or ended in a cycle counts from the next. marker_o: a marker's entry
//   is not ended (depth.hiz_sync = lagged holds the walk only for it: a depth clear moves
//   the bounds the unsafe way; docs/depth-culling.md "Lagged").
// - rop_accept_o: the Hi-Z accept of the oldest entry not ended (the batch whose group is
//   at the ROP's response: one group in flight, never two batches' in one group);
//   rop_accept_next_o the next one's (a batch whose first group the ROP issues in the
//   cycle the oldest's last response comes: rast_rop's read skips an accepted tile's depth).
// - Entries free from the oldest once ended (all ended ones before the oldest live one,
//   in a cycle). room_o: a push fits (Depth is sized so that it never binds: rast_top).
`default_nettype none

module rast_hiz_inflight #(
  parameter int PixelW    = 14,  // pixel index bits
  parameter int BlockLog2 = 3,   // log2 depth.hiz_block
  parameter int Depth     = 64,  // entries
  parameter int Queries   = 1    // query ports (walk lanes)
) (
  input  wire logic                        clk_i,         // core clock
  input  wire logic                        rst_ni,        // asynchronous reset, active low
  input  wire logic                        push_i,        // coarse raster sends a tile or marker
  input  wire logic                        push_all_i,    // a marker: every block
  input  wire logic [4*PixelW-1:0]         push_fp_i,     // the tile's footprint {y1, x1, y0, x0}
  input  wire logic                        push_accept_i, // the tile's Hi-Z accept
  output      logic                        room_o,        // a push fits
  input  wire logic                        fine_valid_i,  // fine raster finishes its oldest tile or marker
  input  wire logic                        fine_drop_i,   // ... without output (no covered pixel)
  input  wire logic                        rop_end_i,     // the ROP ends its oldest entry (a batch)
  input  wire logic                        rop_marker_i,  // ... (a marker; after rop_end_i's in the same cycle)
  output      logic                        rop_accept_o,  // that entry's accept
  output      logic                        rop_accept_next_o, // the next entry not ended's accept
  input  wire logic [Queries*4*PixelW-1:0] q_fp_i,        // query n's footprint at [n*4*PixelW +: 4*PixelW]
  output      logic [Queries-1:0]          wait_o,        // query n's blocks have an entry not ended
  output      logic                        marker_o,      // a marker's entry is not ended
  output      logic                        empty_o        // no entry
);
  localparam int PtrW = $clog2(Depth);      // derived
  localparam int CntW = $clog2(Depth + 1);  // derived
  localparam int BlkW = PixelW - BlockLog2; // derived: a block coordinate

  logic [4*BlkW-1:0] blk_q [Depth];  // {by1, bx1, by0, bx0}
  logic [Depth-1:0]  all_q, acc_q, ended_q;
  logic [PtrW-1:0]   head_q, fine_q;  // oldest entry; fine raster's next
  logic [CntW-1:0]   count_q;

  function automatic logic [4*BlkW-1:0] blocks_of(input logic [4*PixelW-1:0] fp);
    blocks_of = {BlkW'((fp[3*PixelW +: PixelW] - 1'b1) >> BlockLog2), BlkW'((fp[2*PixelW +: PixelW] - 1'b1) >> BlockLog2),
                 BlkW'(fp[PixelW +: PixelW] >> BlockLog2), BlkW'(fp[0 +: PixelW] >> BlockLog2)};
  endfunction

  // Entry i lives when it is among the count_q from head_q.
  logic [Depth-1:0] live;
  always_comb
    for (int i = 0; i < Depth; i++) live[i] = CntW'(PtrW'(PtrW'(i) - head_q)) < count_q;

  // The oldest entry not ended (rop_idx; found when any), how many ended lead it, and
  // the next one not ended (rop_idx2: a marker the ROP takes in the cycle a batch ends).
  logic [PtrW-1:0] rop_idx, rop_idx2;
  logic [CntW-1:0] lead;
  logic            rop_found, rop_found2;
  always_comb begin
    logic [PtrW-1:0] idx;
    rop_found = 1'b0;
    rop_found2 = 1'b0;
    rop_idx = head_q;
    rop_idx2 = head_q;
    lead = count_q;
    for (int k = 0; k < Depth; k++) begin
      idx = head_q + PtrW'(k);
      if (CntW'(k) < count_q && !ended_q[idx]) begin
        if (rop_found && !rop_found2) begin
          rop_found2 = 1'b1;
          rop_idx2 = idx;
        end
        if (!rop_found) begin
          rop_found = 1'b1;
          rop_idx = idx;
          lead = CntW'(k);
        end
      end
    end
  end
  // The entries the ROP ends this cycle: its batch's, then its marker's.
  logic end1, end2;
  assign end1 = (rop_end_i || rop_marker_i) && rop_found;
  assign end2 = rop_end_i && rop_marker_i && rop_found2;
  assign rop_accept_o = rop_found && acc_q[rop_idx];
  assign rop_accept_next_o = rop_found2 && acc_q[rop_idx2];
  assign room_o = count_q - lead != CntW'(Depth);
  assign empty_o = count_q == '0;

  for (genvar n = 0; n < Queries; n++) begin : g_query
    logic [4*BlkW-1:0] q;
    assign q = blocks_of(q_fp_i[n*4*PixelW +: 4*PixelW]);
    always_comb begin
      wait_o[n] = 1'b0;
      for (int i = 0; i < Depth; i++)
        if (live[i] && !ended_q[i] &&
            (all_q[i] || !(blk_q[i][2*BlkW +: BlkW] < q[0 +: BlkW] || blk_q[i][0 +: BlkW] > q[2*BlkW +: BlkW] ||
                           blk_q[i][3*BlkW +: BlkW] < q[BlkW +: BlkW] || blk_q[i][BlkW +: BlkW] > q[3*BlkW +: BlkW])))
          wait_o[n] = 1'b1;
    end
  end

  always_comb begin
    marker_o = 1'b0;
    for (int i = 0; i < Depth; i++)
      if (live[i] && !ended_q[i] && all_q[i]) marker_o = 1'b1;
  end

  logic [PtrW-1:0] tail;
  assign tail = head_q + PtrW'(count_q);
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      head_q <= '0;
      fine_q <= '0;
      count_q <= '0;
      ended_q <= '0;
    end else begin
      // The ended entries before the oldest live one leave; a push joins at the tail.
      head_q <= head_q + PtrW'(lead);
      count_q <= count_q - lead + CntW'(push_i);
      if (fine_valid_i) fine_q <= fine_q + 1'b1;
      for (int i = 0; i < Depth; i++) begin
        if (push_i && PtrW'(i) == tail) ended_q[i] <= 1'b0;
        if (fine_valid_i && fine_drop_i && PtrW'(i) == fine_q) ended_q[i] <= 1'b1;
        if (end1 && PtrW'(i) == rop_idx) ended_q[i] <= 1'b1;
        if (end2 && PtrW'(i) == rop_idx2) ended_q[i] <= 1'b1;
      end
    end
  end
  always_ff @(posedge clk_i) begin
    if (push_i) begin
      blk_q[tail] <= blocks_of(push_fp_i);
      all_q[tail] <= push_all_i;
      acc_q[tail] <= push_accept_i;
    end
  end
endmodule

`default_nettype wire
