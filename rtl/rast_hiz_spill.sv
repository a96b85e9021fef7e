// SPDX-License-Identifier: Apache-2.0
// rast_hiz_spill: Hi-Z's spilled entries (docs/depth-culling.md "Spilled table", docs/rtl.md
// "Spilled entries"): the blocks past rast_hiz's on-chip part (index i >= OnChip), read
// and written through the memory port hiz_mem_* that the testbench serves as the memory
// system's client `hiz`. Entry i lives at byte base_i + (i - OnChip) 2^EntryBytesLog2 (the
// reference's HizTable address), one request an entry.
//
// - Test reads (lane 0 of coarse raster's walk, q_*): q_go_i starts the reads of the
//   spilled blocks of the footprint, in the reference's order (row by row, left to right),
//   one request a cycle; their zmin / zmax merge into q_min_o / q_max_o, valid (q_valid_o)
//   once every response is in, until the tile is consumed (q_consume_i). rast_top_hiz
//   starts it only when the interlock frees the blocks and this unit is idle (busy_o
//   low), so memory holds every write-back of the tiles before.
// - Update engine: the ROP's depth writes to spilled blocks (a cycle's lanes, then the
//   batch's end, then a depth clear, a bundle in a FIFO) applied in order. A tile's first
//   write to a block reads its entry (the flush's read), the rule (rast_hiz_update) is
//   applied in a slot of the tile's blocks, and at the batch's end every slot is written
//   back in first-write order (the reference's flush: a read and a write a block written).
// - Depth clears move no byte (as the reference's): a fresh bit a spilled block, set by a
//   clear (and at reset, to the largest depth), makes a read of the block see the cleared
//   entry {c, c, empty layer}; its write-back clears the bit.
// - In memory an entry is {zmin, zmax, lmin, lmax, mask} (minmax) or {zmax, lmax, mask}
//   (max) from the top bit down, in the low bits of the port's 512; the mask's count is
//   its popcount.
`default_nettype none

module rast_hiz_spill #(
  parameter int DepthW         = 24,  // D = raster.depth_bits
  parameter int PixelW         = 14,  // pixel index bits
  parameter int BlockLog2      = 3,   // log2 depth.hiz_block
  parameter int MinMax         = 0,   // depth.hiz = minmax
  parameter int OnChip         = 64,  // entries on chip (rast_hiz's Blocks)
  parameter int SpillBlocks    = 192, // the display's blocks past them (fresh bits)
  parameter int EntryBytesLog2 = 4,   // log2 of an entry's bytes (ref hiz_entry_bytes)
  parameter int TileLog2Max    = 4,   // largest tile, log2 px
  parameter int WriteLanes     = 1,   // depth writes a cycle
  parameter int AddrW          = 40,  // byte address bits
  parameter int FifoDepth      = 512  // write bundles queued, a power of two (overflow: error_o)
) (
  input  wire logic                        clk_i,
  input  wire logic                        rst_ni,
  input  wire logic [PixelW-1:0]           fb_width_i,    // framebuffer width, px (static)
  input  wire logic [PixelW-1:0]           fb_height_i,   // framebuffer height, px (static)
  input  wire logic [AddrW-1:0]            base_i,        // depth.hiz_base (static)
  // Lane 0's test.
  input  wire logic [4*PixelW-1:0]         q_fp_i,        // its footprint {y1, x1, y0, x0}
  input  wire logic                        q_go_i,        // read its spilled entries now
  input  wire logic                        q_consume_i,   // the tile tested with them left the walk
  output      logic                        q_valid_o,     // its entries are in
  output      logic [DepthW-1:0]           q_min_o,       // nearest zmin of its spilled blocks
  output      logic [DepthW-1:0]           q_max_o,       // farthest zmax
  output      logic                        busy_o,        // writes not yet applied or written back
  // The ROP's depth writes (only where Hi-Z is on), its batch ends and depth clears.
  input  wire logic [WriteLanes-1:0]       wr_lanes_i,
  input  wire logic [WriteLanes*PixelW-1:0] wr_x_i,
  input  wire logic [WriteLanes*PixelW-1:0] wr_y_i,
  input  wire logic [WriteLanes*DepthW-1:0] wr_z_i,
  input  wire logic                        end_i,         // a batch ends (after this cycle's writes)
  input  wire logic                        clear_i,       // a depth clear (after the end)
  input  wire logic [DepthW-1:0]           clear_z_i,
  // The memory port (client hiz): requests in order, read responses in order.
  output      logic                        mem_req_valid_o,
  input  wire logic                        mem_req_ready_i,
  output      logic                        mem_req_write_o,  // a write-back
  output      logic                        mem_req_flush_o,  // a flush's read (else a test's)
  output      logic [AddrW-1:0]            mem_req_addr_o,
  output      logic [511:0]                mem_req_data_o,   // the entry (writes)
  input  wire logic                        mem_rsp_valid_i,
  input  wire logic [511:0]                mem_rsp_data_i,
  output      logic                        error_o           // the bundle FIFO overflowed (sticky)
);
  localparam int B       = 1 << BlockLog2;                 // derived: block edge, px
  localparam int MaskW   = B * B;                          // derived
  localparam int CntW    = 2 * BlockLog2 + 1;              // derived
  localparam int EntryW  = 4 * DepthW + MaskW + CntW;      // derived: rast_hiz's entry
  localparam int BlkW    = PixelW - BlockLog2 + 1;         // derived: a block coordinate
  localparam int IdxW    = 2 * BlkW;                       // derived: a block index
  localparam int SpanLog2 = TileLog2Max > BlockLog2 ? TileLog2Max - BlockLog2 : 0;  // derived
  localparam int Slots   = 1 << (2 * SpanLog2);            // derived: blocks a tile can write
  localparam int SlotW   = 2 * SpanLog2 + 1;               // derived: 0 .. Slots
  localparam int SIdxW   = SpanLog2 > 0 ? 2 * SpanLog2 : 1; // derived: a slot's index
  localparam int FreshW  = SpillBlocks > 1 ? $clog2(SpillBlocks) : 1;  // derived
  localparam int BundleW = WriteLanes * (2 * PixelW + DepthW + 1) + 2 + DepthW;  // derived

  logic [BlkW-1:0] nx;
  assign nx = BlkW'((fb_width_i + PixelW'(B - 1)) >> BlockLog2);

  // ---- Entry encoding and addresses ----
  function automatic logic [511:0] pack(input logic [EntryW-1:0] e);
    logic [DepthW-1:0] zmin, zmax, lmin, lmax;
    logic [MaskW-1:0] mask;
    /* verilator lint_off UNUSEDSIGNAL */
    logic [CntW-1:0] count;  // the mask's popcount: not stored
    /* verilator lint_on UNUSEDSIGNAL */
    {zmin, zmax, lmin, lmax, mask, count} = e;
    if (MinMax != 0) pack = 512'({zmin, zmax, lmin, lmax, mask});
    else pack = 512'({zmax, lmax, mask});
  endfunction
  /* verilator lint_off UNUSEDSIGNAL */  // the bits past the entry
  function automatic logic [EntryW-1:0] unpack(input logic [511:0] d);
  /* verilator lint_on UNUSEDSIGNAL */
    logic [DepthW-1:0] zmin, zmax, lmin, lmax;
    logic [MaskW-1:0] mask;
    logic [CntW-1:0] count;
    mask = d[0 +: MaskW];
    lmax = d[MaskW +: DepthW];
    if (MinMax != 0) begin
      lmin = d[MaskW + DepthW +: DepthW];
      zmax = d[MaskW + 2 * DepthW +: DepthW];
      zmin = d[MaskW + 3 * DepthW +: DepthW];
    end else begin
      lmin = '1;  // unused in max mode
      zmax = d[MaskW + DepthW +: DepthW];
      zmin = '0;
    end
    count = '0;
    for (int k = 0; k < MaskW; k++) count = count + CntW'(mask[k]);
    unpack = {zmin, zmax, lmin, lmax, mask, count};
  endfunction
  function automatic logic [AddrW-1:0] addr_of(input logic [IdxW-1:0] i);
    addr_of = base_i + (AddrW'(IdxW'(i - IdxW'(OnChip))) << EntryBytesLog2);
  endfunction
  /* verilator lint_off UNUSEDSIGNAL */  // an index below 2^FreshW (a spilled block's)
  function automatic logic [FreshW-1:0] fresh_idx(input logic [IdxW-1:0] i);
  /* verilator lint_on UNUSEDSIGNAL */
    fresh_idx = FreshW'(i - IdxW'(OnChip));
  endfunction

  logic [SpillBlocks-1:0] fresh_q;  // block OnChip + k reads as the cleared entry
  logic [DepthW-1:0]      cz_q;     // the last clear's depth
  logic [EntryW-1:0]      cleared;
  assign cleared = {cz_q, cz_q, {DepthW{1'b1}}, {DepthW{1'b0}}, {MaskW{1'b0}}, {CntW{1'b0}}};

  // ---- Test reads (lane 0) ----
  logic              f_active_q, f_valid_q, f_issued_q;
  logic [BlkW-1:0]   f_bx_q, f_by_q, f_bx0_q, f_bx1_q, f_by1_q;
  logic [IdxW-1:0]   f_pend_q [Slots];  // the spilled blocks read, in order
  logic [SlotW-1:0]  f_sent_q, f_got_q;
  logic [DepthW-1:0] f_min_q, f_max_q;
  logic [IdxW-1:0]   f_idx;
  logic              f_req, f_last, f_go, f_done;
  logic [BlkW-1:0]   f_bx, f_by, f_bx1, f_by1, f_bx0;  // the block requested this cycle, the footprint's
  // A test read's entry (the cleared one while the block is fresh): its zmin, zmax.
  /* verilator lint_off UNUSEDSIGNAL */
  logic [EntryW-1:0] f_rsp;
  /* verilator lint_on UNUSEDSIGNAL */
  assign f_rsp = fresh_q[fresh_idx(f_pend_q[SIdxW'(f_got_q)])] ? cleared : unpack(mem_rsp_data_i);
  // The footprint's spilled blocks are a suffix of its blocks in row-major order (index
  // >= OnChip): the reads start at the first, f_bx_s / f_by_s.
  logic [BlkW-1:0] q_bx0, q_by0, q_bx1, f_bx_s, f_by_s;
  assign q_bx0 = BlkW'(q_fp_i[0 +: PixelW] >> BlockLog2);
  assign q_by0 = BlkW'(q_fp_i[PixelW +: PixelW] >> BlockLog2);
  assign q_bx1 = BlkW'((q_fp_i[2*PixelW +: PixelW] - 1'b1) >> BlockLog2);
  always_comb begin
    logic [IdxW-1:0] row;
    f_bx_s = q_bx0;
    f_by_s = q_by0;
    for (int j = (1 << SpanLog2) - 1; j >= 0; j--) begin
      row = (IdxW)'(BlkW'(q_by0 + BlkW'(j))) * (IdxW)'(nx);  // the row's first index
      if (row + (IdxW)'(q_bx1) >= IdxW'(OnChip)) begin  // the row ends spilled: the last such row from the top
        f_by_s = q_by0 + BlkW'(j);
        f_bx_s = row + (IdxW)'(q_bx0) >= IdxW'(OnChip) ? q_bx0 : BlkW'(IdxW'(OnChip) - row);
      end
    end
  end
  // The first request goes out in the cycle the reads start (f_go), the rest one a cycle.
  assign f_go = q_go_i && !f_active_q && !f_valid_q;
  assign f_bx = f_go ? f_bx_s : f_bx_q;
  assign f_by = f_go ? f_by_s : f_by_q;
  assign f_bx0 = f_go ? q_bx0 : f_bx0_q;
  assign f_bx1 = f_go ? q_bx1 : f_bx1_q;
  assign f_by1 = f_go ? BlkW'((q_fp_i[3*PixelW +: PixelW] - 1'b1) >> BlockLog2) : f_by1_q;
  assign f_idx = (IdxW)'(f_by) * (IdxW)'(nx) + (IdxW)'(f_bx);
  assign f_req = f_go || (f_active_q && !f_issued_q);  // every block from the first on is spilled
  assign f_last = f_bx == f_bx1 && f_by == f_by1;
  // The last response: the lane is tested with it in its cycle (the SystemC walk goes on
  // when the last entry arrives), its zmin / zmax merged in.
  assign f_done = f_active_q && f_issued_q && mem_rsp_valid_i && f_got_q + 1'b1 == f_sent_q;
  assign q_valid_o = f_valid_q || f_done;
  assign q_min_o = f_done && f_rsp[EntryW-DepthW +: DepthW] < f_min_q ? f_rsp[EntryW-DepthW +: DepthW] : f_min_q;
  assign q_max_o = f_done && f_rsp[EntryW-2*DepthW +: DepthW] > f_max_q ? f_rsp[EntryW-2*DepthW +: DepthW] : f_max_q;

  // ---- The update engine's bundles ----
  logic in_push, in_ready, hd_valid, hd_pop, fifo_empty, dirty_q;
  logic [WriteLanes-1:0] spilled_lanes;
  logic [BundleW-1:0] in_bundle, hd;
  for (genvar j = 0; j < WriteLanes; j++) begin : g_in
    logic [IdxW-1:0] bi;
    assign bi = (IdxW)'(BlkW'(wr_y_i[j*PixelW +: PixelW] >> BlockLog2)) * (IdxW)'(nx) +
                (IdxW)'(BlkW'(wr_x_i[j*PixelW +: PixelW] >> BlockLog2));
    assign spilled_lanes[j] = wr_lanes_i[j] && bi >= IdxW'(OnChip);
    assign in_bundle[j*(2*PixelW+DepthW+1) +: 2*PixelW+DepthW+1] =
        {spilled_lanes[j], wr_z_i[j*DepthW +: DepthW], wr_y_i[j*PixelW +: PixelW], wr_x_i[j*PixelW +: PixelW]};
  end
  assign in_bundle[BundleW-1 -: DepthW+2] = {clear_z_i, clear_i, end_i && (dirty_q || |spilled_lanes)};
  // A bundle for a spilled write, a batch end with spilled writes since the last, a clear.
  assign in_push = |spilled_lanes || (end_i && (dirty_q || |spilled_lanes)) || clear_i;
  // The bundle FIFO: a circular buffer (FifoDepth a power of two; rast_fifo's per-entry
  // countdowns do not unroll at this depth).
  localparam int FPtrW = $clog2(FifoDepth);  // derived
  logic [BundleW-1:0] fifo_q [FifoDepth];
  logic [FPtrW:0]     rd_q, wr_q;  // one bit past the index: full vs empty
  assign fifo_empty = rd_q == wr_q;
  assign in_ready = !(rd_q[FPtrW] != wr_q[FPtrW] && rd_q[FPtrW-1:0] == wr_q[FPtrW-1:0]);
  assign hd_valid = !fifo_empty;
  assign hd = fifo_q[rd_q[FPtrW-1:0]];
  always_ff @(posedge clk_i) if (in_push && in_ready) fifo_q[wr_q[FPtrW-1:0]] <= in_bundle;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      rd_q <= '0;
      wr_q <= '0;
    end else begin
      if (in_push && in_ready) wr_q <= wr_q + 1'b1;
      if (hd_pop) rd_q <= rd_q + 1'b1;
    end
  end

  // The head bundle: its lanes not yet applied (e_done_q), then the write-backs, the clear.
  logic [WriteLanes-1:0] e_done_q, e_left;
  logic [IdxW-1:0]       s_tag_q [Slots];
  logic [EntryW-1:0]     s_ent_q [Slots];
  logic [SlotW-1:0]      s_n_q, s_wb_q;     // slots used; the next to write back
  logic                  e_wait_q;          // a flush read outstanding
  logic                  hd_end, hd_clear;
  logic [DepthW-1:0]     hd_cz;
  assign {hd_cz, hd_clear, hd_end} = hd[BundleW-1 -: DepthW+2];
  for (genvar j = 0; j < WriteLanes; j++) begin : g_left
    assign e_left[j] = hd_valid && hd[j*(2*PixelW+DepthW+1) + 2*PixelW + DepthW] && !e_done_q[j];
  end
  // The lowest lane left: its pixel, block and slot.
  logic [PixelW-1:0] e_x, e_y;
  logic [DepthW-1:0] e_z;
  logic [IdxW-1:0]   e_idx;
  logic [WriteLanes-1:0] e_lane;  // one-hot
  logic              e_hit;
  /* verilator lint_off UNUSEDSIGNAL */  // its top bit: Slots itself, a miss's (the slot count)
  logic [SlotW-1:0]  e_slot;
  /* verilator lint_on UNUSEDSIGNAL */
  always_comb begin
    e_lane = '0;
    {e_z, e_y, e_x} = '0;
    for (int j = WriteLanes - 1; j >= 0; j--)
      if (e_left[j]) begin
        e_lane = WriteLanes'(1) << j;
        {e_z, e_y, e_x} = hd[j*(2*PixelW+DepthW+1) +: 2*PixelW+DepthW];
      end
    e_idx = (IdxW)'(BlkW'(e_y >> BlockLog2)) * (IdxW)'(nx) + (IdxW)'(BlkW'(e_x >> BlockLog2));
    e_hit = 1'b0;
    e_slot = s_n_q;
    for (int k = Slots - 1; k >= 0; k--)
      if (SlotW'(k) < s_n_q && s_tag_q[k] == e_idx) begin
        e_hit = 1'b1;
        e_slot = SlotW'(k);
      end
  end
  // The engine's step this cycle: apply a write (its slot's entry, or the flush read's
  // response), issue a flush read, write a slot back, or finish the bundle.
  logic e_apply, e_read, e_wb, e_port;
  logic [EntryW-1:0] e_old, e_new;
  /* verilator lint_off UNUSEDSIGNAL */
  logic e_done;  // layer completions: counted by the reference, not here
  /* verilator lint_on UNUSEDSIGNAL */
  assign e_port = !f_active_q;  // the test reads hold the port while they run
  assign e_apply = |e_lane && (e_hit || (e_wait_q && mem_rsp_valid_i));
  assign e_read = |e_lane && !e_hit && !e_wait_q && e_port;
  assign e_wb = hd_valid && !(|e_left) && hd_end && s_wb_q < s_n_q && e_port;
  // A bundle without an end leaves with its last write; an end's after its write-backs.
  assign hd_pop = hd_valid && (hd_end ? !(|e_left) && s_wb_q == s_n_q : !(|(e_left & ~(e_apply ? e_lane : '0))));
  assign e_old = e_hit ? s_ent_q[SIdxW'(e_slot)] : fresh_q[fresh_idx(e_idx)] ? cleared : unpack(mem_rsp_data_i);
  rast_hiz_update #(.DepthW(DepthW), .PixelW(PixelW), .BlockLog2(BlockLog2)) u_update (
    .fb_width_i, .fb_height_i, .e_i(e_old), .x_i(e_x), .y_i(e_y), .z_i(e_z), .e_o(e_new), .done_o(e_done));
  assign busy_o = !fifo_empty || e_wait_q;

  // ---- The port: the test reads while they run, else the engine ----
  always_comb begin
    mem_req_valid_o = 1'b0;
    mem_req_write_o = 1'b0;
    mem_req_flush_o = 1'b0;
    mem_req_addr_o = addr_of(f_idx);
    mem_req_data_o = '0;
    if (f_req) begin
      mem_req_valid_o = 1'b1;
    end else if (e_read) begin
      mem_req_valid_o = 1'b1;
      mem_req_flush_o = 1'b1;
      mem_req_addr_o = addr_of(e_idx);
    end else if (e_wb) begin
      mem_req_valid_o = 1'b1;
      mem_req_write_o = 1'b1;
      mem_req_addr_o = addr_of(s_tag_q[SIdxW'(s_wb_q)]);
      mem_req_data_o = pack(s_ent_q[SIdxW'(s_wb_q)]);
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      fresh_q <= '1;
      cz_q <= '1;
      {f_active_q, f_valid_q, f_issued_q} <= '0;
      {f_sent_q, f_got_q} <= '0;
      e_done_q <= '0;
      e_wait_q <= 1'b0;
      {s_n_q, s_wb_q} <= '0;
      dirty_q <= 1'b0;
      error_o <= 1'b0;
    end else begin
      if (in_push && !in_ready) error_o <= 1'b1;
      if (end_i) dirty_q <= 1'b0;
      if (|spilled_lanes && !end_i) dirty_q <= 1'b1;
      // Test reads: walk the footprint's blocks, a request a spilled one.
      if (f_go) begin
        f_active_q <= 1'b1;
        f_issued_q <= 1'b0;
        {f_sent_q, f_got_q} <= '0;
        f_bx_q <= f_bx;
        f_by_q <= f_by;
        f_bx0_q <= f_bx0;
        f_bx1_q <= f_bx1;
        f_by1_q <= f_by1;
        f_min_q <= '1;
        f_max_q <= '0;
      end
      if (f_go || f_active_q) begin
        if (f_req && mem_req_ready_i) begin  // the block's request taken: on to the next
          f_pend_q[SIdxW'(f_go ? '0 : f_sent_q)] <= f_idx;
          f_sent_q <= (f_go ? '0 : f_sent_q) + 1'b1;
          if (f_last) f_issued_q <= 1'b1;
          else if (f_bx == f_bx1) begin
            f_bx_q <= f_bx0;
            f_by_q <= f_by + 1'b1;
          end else f_bx_q <= f_bx + 1'b1;
        end
        if (f_active_q && mem_rsp_valid_i) begin
          if (f_rsp[EntryW-DepthW +: DepthW] < f_min_q) f_min_q <= f_rsp[EntryW-DepthW +: DepthW];
          if (f_rsp[EntryW-2*DepthW +: DepthW] > f_max_q) f_max_q <= f_rsp[EntryW-2*DepthW +: DepthW];
          f_got_q <= f_got_q + 1'b1;
          if (f_done) begin  // the last: valid until the tile is consumed
            f_active_q <= 1'b0;
            f_valid_q <= 1'b1;
          end
        end
      end
      if (q_consume_i) f_valid_q <= 1'b0;
      // The engine.
      if (e_read && mem_req_ready_i) e_wait_q <= 1'b1;
      if (e_apply) begin
        s_ent_q[SIdxW'(e_slot)] <= e_new;
        s_tag_q[SIdxW'(e_slot)] <= e_idx;
        if (!e_hit) s_n_q <= s_n_q + 1'b1;
        e_wait_q <= 1'b0;
        e_done_q <= e_done_q | e_lane;
      end
      if (e_wb && mem_req_ready_i) begin
        fresh_q[fresh_idx(s_tag_q[SIdxW'(s_wb_q)])] <= 1'b0;
        s_wb_q <= s_wb_q + 1'b1;
      end
      if (hd_pop) begin
        e_done_q <= '0;
        if (hd_end) {s_n_q, s_wb_q} <= '0;
        if (hd_clear) begin
          fresh_q <= '1;
          cz_q <= hd_cz;
        end
      end
    end
  end
endmodule

`default_nettype wire
