// SPDX-License-Identifier: Apache-2.0
// rast_rop_cache: the ROP's cache of one surface (colour or depth), set-associative,
// write-back, write-allocate, true LRU: the policy of model/ref/memory/cache.h
// (SetAssocCache), decision for decision (docs/rtl.md "ROP cache", docs/memory.md "Caches").
//
// - Addresses are byte offsets in the surface (AddrW bits; the surface's base is added
//   past the cache). line = addr / LineBytes, set = line mod Sets (the low line bits),
//   tag = line / Sets. Sets = CacheBytes / (Ways LineBytes), a power of two.
// - A miss takes the first invalid way of its set (lowest way index), else the least
//   recently used one; every access, hit or miss, makes its way the most recently used.
//   Recency is a rank a way (0 = most recent, Ways - 1 = least), a permutation of the
//   set's ways: a touched way goes to 0 and the ways more recent than it move down one.
// - Write-allocate: a write miss fills its line too, and the written bytes are merged into
//   the fill. A write marks its line dirty. A miss whose victim is dirty writes the victim
//   back (whole line) before it requests the fill.
// - Flush (req_op_i 2): every dirty line written back, set by set, ways in order, then
//   every line clean. Invalidate (3): every line invalid, dirty data dropped (a clear
//   overwrites the surface).
// - One request at a time (valid/ready), one response for each (valid/ready, in order):
//   a read's word, whether it hit, and a miss's victim (valid, dirty, its line address).
// - Memory side: a fill is a request (line address) and a response (the line, one beat);
//   a write-back is one beat of address and line. Each valid/ready.
// - Storage: tags, valid, dirty and ranks in flip-flops; the data in rast_rop_cache_data,
//   a single-port SRAM (one access a cycle: a hit's read or write, a victim's read, a
//   fill's write).
//
// Cycles with a memory that takes and answers at once: read hit 4 (request, lookup, data,
// response), write hit 3, miss 5 (request, lookup, fill request, fill, response), one more
// with a dirty victim (its write-back); flush 3 + Sets Ways + one a dirty line;
// invalidate 3.
`default_nettype none

module rast_rop_cache #(
  parameter int AddrW = 16,        // byte offset bits in the surface
  parameter int CacheBytes = 256,  // capacity (rop.*_cache_bytes): Sets x Ways x LineBytes
  parameter int Ways = 2,          // rop.*_cache_ways, >= 1
  parameter int LineBytes = 16,    // rop.*_cache_line_bytes, a power of two >= WordBytes
  parameter int WordBytes = 4      // bytes of a core-side word (a sample: colour 4, depth 2 or 4)
) (
  input  wire logic                   clk_i,              // core clock
  input  wire logic                   rst_ni,             // asynchronous reset, active low
  // Core side: requests.
  input  wire logic                   req_valid_i,
  output      logic                   req_ready_o,
  input  wire logic [1:0]             req_op_i,           // 0 read, 1 write, 2 flush, 3 invalidate
  input  wire logic [AddrW-1:0]       req_addr_i,         // byte offset (its word: the low bits ignored)
  input  wire logic [WordBytes-1:0]   req_be_i,           // a write's byte enables within the word
  input  wire logic [8*WordBytes-1:0] req_wdata_i,        // a write's word
  // Core side: responses, one a request, in order.
  output      logic                   rsp_valid_o,
  input  wire logic                   rsp_ready_i,
  output      logic [8*WordBytes-1:0] rsp_rdata_o,        // a read's word
  output      logic                   rsp_hit_o,          // a read or write hit
  output      logic                   rsp_evict_o,        // a miss replaced a valid line
  output      logic                   rsp_evict_dirty_o,  // ... a dirty one (written back)
  output      logic [AddrW-1:0]       rsp_victim_addr_o,  // ... its byte address
  // Memory side: line fills.
  output      logic                   fill_req_valid_o,
  input  wire logic                   fill_req_ready_i,
  output      logic [AddrW-1:0]       fill_req_addr_o,    // the line's byte address
  input  wire logic                   fill_rsp_valid_i,
  output      logic                   fill_rsp_ready_o,
  input  wire logic [8*LineBytes-1:0] fill_rsp_data_i,    // the line, byte i at [8 i +: 8]
  // Memory side: write-backs.
  output      logic                   wb_valid_o,
  input  wire logic                   wb_ready_i,
  output      logic [AddrW-1:0]       wb_addr_o,          // the line's byte address
  output      logic [8*LineBytes-1:0] wb_data_o,
  output      logic                   idle_o              // no request in progress
);
  localparam int Sets = CacheBytes / (Ways * LineBytes);
  localparam int OffW = $clog2(LineBytes);                 // byte in a line
  localparam int SetW = $clog2(Sets);                      // set index (0: one set)
  localparam int TagW = AddrW - OffW - SetW;
  localparam int SetIdxW = SetW > 0 ? SetW : 1;
  localparam int WayW = Ways > 1 ? $clog2(Ways) : 1;
  localparam int Entries = Sets * Ways;                    // lines, set-major
  localparam int EntW = Entries > 1 ? $clog2(Entries) : 1;
  localparam int WordOffW = $clog2(WordBytes);             // byte in a word
  localparam int Words = LineBytes / WordBytes;            // words a line
  localparam int WordIdxW = Words > 1 ? $clog2(Words) : 1;

  if (Sets < 1 || (Sets & (Sets - 1)) != 0 || Sets * Ways * LineBytes != CacheBytes) begin : g_check_sets
    $error("rast_rop_cache: CacheBytes (%0d) must be Ways (%0d) x LineBytes (%0d) x a power of two", CacheBytes,
           Ways, LineBytes);
  end
  if (WordBytes < 1 || (WordBytes & (WordBytes - 1)) != 0 || (LineBytes & (LineBytes - 1)) != 0 ||
      LineBytes < WordBytes) begin : g_check_line
    $error("rast_rop_cache: LineBytes (%0d) and WordBytes (%0d) must be powers of two, LineBytes >= WordBytes",
           LineBytes, WordBytes);
  end
  if (TagW < 1) begin : g_check_tag
    $error("rast_rop_cache: AddrW (%0d) must exceed the line offset and set bits (%0d)", AddrW, OffW + SetW);
  end

  typedef enum logic [3:0] {
    SIdle, SLookup, SReadData, SWriteBack, SFillReq, SFillWait, SFlush, SFlushWb, SResp
  } state_e;

  // ---- State (flip-flops) ----
  state_e               state_q;
  // Entry e (= set Ways + way) at [e TagW +: TagW] and [e WayW +: WayW].
  logic [Entries*TagW-1:0] tag_q;
  logic [Entries*WayW-1:0] rank_q;          // recency: 0 most recent
  logic [Entries-1:0]   valid_q, dirty_q;
  logic [1:0]           op_q;              // the request in progress
  logic [AddrW-1:0]     addr_q;
  logic [WordBytes-1:0] be_q;
  logic [8*WordBytes-1:0] wdata_q;
  logic [WayW-1:0]      way_q;             // the hit or victim way
  logic                 hit_q, evict_q, evict_dirty_q;
  logic [AddrW-1:0]     victim_addr_q;     // also a flushed line's address
  logic [8*WordBytes-1:0] rdata_q;
  logic [SetIdxW-1:0]   scan_set_q;        // flush: the line looked at
  logic [WayW-1:0]      scan_way_q;

  // ---- The request's fields ----
  logic [SetIdxW-1:0]  set;
  logic [TagW-1:0]     tag;
  logic [WordIdxW-1:0] word;
  assign tag = addr_q[AddrW-1 -: TagW];
  if (SetW > 0) begin : g_set
    assign set = addr_q[OffW +: SetW];
  end else begin : g_one_set
    assign set = '0;
  end
  if (WordOffW > 0) begin : g_unused_addr
    logic unused_byte_in_word;  // a request is a word: its byte offset is not looked at
    assign unused_byte_in_word = ^addr_q[WordOffW-1:0];
  end
  if (Words > 1) begin : g_word
    assign word = addr_q[WordOffW +: WordIdxW];
  end else begin : g_one_word
    assign word = '0;
  end

  function automatic logic [EntW-1:0] entry(input logic [SetIdxW-1:0] s, input logic [WayW-1:0] w);
    entry = EntW'(s) * EntW'(Ways) + EntW'(w);
  endfunction

  // The line's byte address from its tag and set.
  function automatic logic [AddrW-1:0] line_addr(input logic [TagW-1:0] t, input logic [SetIdxW-1:0] s);
    logic [AddrW-1:0] a;
    a = AddrW'(t) << (OffW + SetW);
    if (SetW > 0) a = a | (AddrW'(s) << OffW);
    line_addr = a;
  endfunction

  // ---- The request's set: its ways' tags, valid and dirty bits and ranks (one row) ----
  localparam int RowTagW = Ways * TagW, RowRankW = Ways * WayW;
  logic [RowTagW-1:0]  row_tag;   // way w at [w TagW +: TagW]
  logic [RowRankW-1:0] row_rank;  // way w at [w WayW +: WayW]
  logic [Ways-1:0]     row_valid, row_dirty;
  assign row_tag = tag_q[set * RowTagW +: RowTagW];
  assign row_rank = rank_q[set * RowRankW +: RowRankW];
  assign row_valid = valid_q[set * Ways +: Ways];
  assign row_dirty = dirty_q[set * Ways +: Ways];

  // ---- Lookup: the hit way, else the victim (first invalid way, else rank Ways - 1) ----
  logic            hit;
  logic [WayW-1:0] hit_way, victim_way;
  always_comb begin
    logic found_invalid;
    hit = 1'b0;
    hit_way = '0;
    victim_way = '0;
    found_invalid = 1'b0;
    for (int w = 0; w < Ways; w++) begin
      if (row_valid[w] && row_tag[w*TagW +: TagW] == tag) begin
        hit = 1'b1;
        hit_way = WayW'(w);
      end
    end
    for (int w = 0; w < Ways; w++)
      if (!found_invalid && !row_valid[w]) begin
        found_invalid = 1'b1;
        victim_way = WayW'(w);
      end
    if (!found_invalid)
      for (int w = 0; w < Ways; w++)
        if (row_rank[w*WayW +: WayW] == WayW'(Ways - 1)) victim_way = WayW'(w);
  end
  logic [WayW-1:0] touch_way;  // the way the lookup makes most recent
  assign touch_way = hit ? hit_way : victim_way;

  // The row after the lookup: touch_way most recent (the ways more recent than it one
  // down), a write's line dirty, a miss's line allocated in the victim's way.
  logic [RowTagW-1:0]  row_tag_n;
  logic [RowRankW-1:0] row_rank_n;
  logic [Ways-1:0]     row_valid_n, row_dirty_n;
  always_comb begin
    row_tag_n = row_tag;
    row_valid_n = row_valid;
    row_dirty_n = row_dirty;
    for (int w = 0; w < Ways; w++) begin
      row_rank_n[w*WayW +: WayW] = row_rank[w*WayW +: WayW];
      if (row_rank[w*WayW +: WayW] < row_rank[touch_way*WayW +: WayW])
        row_rank_n[w*WayW +: WayW] = row_rank[w*WayW +: WayW] + 1'b1;
      if (WayW'(w) == touch_way) begin
        row_rank_n[w*WayW +: WayW] = '0;
        if (op_q[0]) row_dirty_n[w] = 1'b1;
        if (!hit) begin
          row_tag_n[w*TagW +: TagW] = tag;
          row_valid_n[w] = 1'b1;
          row_dirty_n[w] = op_q[0];
        end
      end
    end
  end

  // ---- The written word placed in a line: its byte mask and data ----
  logic [LineBytes-1:0]   word_mask;
  logic [8*LineBytes-1:0] word_line, fill_merged;
  always_comb begin
    word_mask = '0;
    for (int k = 0; k < Words; k++)
      if (WordIdxW'(k) == word) word_mask[k*WordBytes +: WordBytes] = be_q;
    word_line = {Words{wdata_q}};
    fill_merged = fill_rsp_data_i;
    if (op_q == 2'd1)
      for (int b = 0; b < LineBytes; b++)
        if (word_mask[b]) fill_merged[8*b +: 8] = wdata_q[8*(b % WordBytes) +: 8];
  end

  // The word `word` of a line.
  function automatic logic [8*WordBytes-1:0] word_of(input logic [8*LineBytes-1:0] line, input logic [WordIdxW-1:0] k);
    word_of = '0;
    for (int i = 0; i < Words; i++)
      if (WordIdxW'(i) == k) word_of = line[8*WordBytes*i +: 8*WordBytes];
  endfunction

  // ---- The data array ----
  logic                   ram_en, ram_we;
  logic [EntW-1:0]        ram_addr;
  logic [LineBytes-1:0]   ram_wmask;
  logic [8*LineBytes-1:0] ram_wdata, ram_rdata;
  rast_rop_cache_data #(.Entries(Entries), .LineBytes(LineBytes)) u_data (
    .clk_i, .en_i(ram_en), .we_i(ram_we), .addr_i(ram_addr), .wmask_i(ram_wmask), .wdata_i(ram_wdata),
    .rdata_o(ram_rdata));

  logic flush_last;  // the scan is at the last line
  assign flush_last = (scan_set_q == SetIdxW'(Sets - 1)) && (scan_way_q == WayW'(Ways - 1));

  always_comb begin
    ram_en = 1'b0;
    ram_we = 1'b0;
    ram_addr = entry(set, way_q);
    ram_wmask = '1;
    ram_wdata = fill_merged;
    case (state_q)
      SLookup: if (op_q[1] == 1'b0) begin
        ram_addr = entry(set, touch_way);
        if (hit) begin  // a read's line, or the written word
          ram_en = 1'b1;
          ram_we = op_q[0];
          ram_wmask = word_mask;
          ram_wdata = word_line;
        end else if (row_valid[victim_way] && row_dirty[victim_way]) begin
          ram_en = 1'b1;  // the victim's line, for its write-back
        end
      end
      SFlush: begin
        ram_addr = entry(scan_set_q, scan_way_q);
        ram_en = valid_q[ram_addr] && dirty_q[ram_addr];
      end
      SFillWait: begin
        ram_en = fill_rsp_valid_i;
        ram_we = 1'b1;
      end
      default: ;
    endcase
  end

  assign req_ready_o = state_q == SIdle;
  assign idle_o = state_q == SIdle;
  assign rsp_valid_o = state_q == SResp;
  assign rsp_rdata_o = rdata_q;
  assign rsp_hit_o = hit_q;
  assign rsp_evict_o = evict_q;
  assign rsp_evict_dirty_o = evict_dirty_q;
  assign rsp_victim_addr_o = victim_addr_q;
  assign fill_req_valid_o = state_q == SFillReq;
  assign fill_req_addr_o = line_addr(tag, set);
  assign fill_rsp_ready_o = state_q == SFillWait;
  assign wb_valid_o = state_q == SWriteBack || state_q == SFlushWb;
  assign wb_addr_o = victim_addr_q;
  assign wb_data_o = ram_rdata;

  // ---- Tags, valid, dirty, ranks ----
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      valid_q <= '0;
      dirty_q <= '0;
      tag_q <= '0;
      for (int e = 0; e < Entries; e++) rank_q[e*WayW +: WayW] <= WayW'(e % Ways);
    end else if (state_q == SLookup && op_q == 2'd3) begin
      valid_q <= '0;
      dirty_q <= '0;
    end else if (state_q == SLookup && op_q[1] == 1'b0) begin
      tag_q[set * RowTagW +: RowTagW] <= row_tag_n;
      rank_q[set * RowRankW +: RowRankW] <= row_rank_n;
      valid_q[set * Ways +: Ways] <= row_valid_n;
      dirty_q[set * Ways +: Ways] <= row_dirty_n;
    end else if (state_q == SFlush && ram_en) begin
      dirty_q[ram_addr] <= 1'b0;
    end
  end

  // ---- The request, its response and the sequence ----
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      state_q <= SIdle;
      op_q <= '0;
      addr_q <= '0;
      be_q <= '0;
      wdata_q <= '0;
      way_q <= '0;
      hit_q <= 1'b0;
      evict_q <= 1'b0;
      evict_dirty_q <= 1'b0;
      victim_addr_q <= '0;
      rdata_q <= '0;
      scan_set_q <= '0;
      scan_way_q <= '0;
    end else begin
      case (state_q)
        SIdle: if (req_valid_i) begin
          op_q <= req_op_i;
          addr_q <= req_addr_i;
          be_q <= req_be_i;
          wdata_q <= req_wdata_i;
          state_q <= SLookup;
        end
        SLookup: begin
          hit_q <= hit;
          evict_q <= 1'b0;
          evict_dirty_q <= 1'b0;
          way_q <= touch_way;
          scan_set_q <= '0;
          scan_way_q <= '0;
          if (op_q == 2'd2) state_q <= SFlush;
          else if (op_q == 2'd3) begin
            hit_q <= 1'b0;
            state_q <= SResp;
          end else if (hit) state_q <= op_q[0] ? SResp : SReadData;
          else begin
            evict_q <= row_valid[victim_way];
            evict_dirty_q <= row_valid[victim_way] && row_dirty[victim_way];
            victim_addr_q <= line_addr(row_tag[victim_way*TagW +: TagW], set);
            state_q <= row_valid[victim_way] && row_dirty[victim_way] ? SWriteBack : SFillReq;
          end
        end
        SReadData: begin
          rdata_q <= word_of(ram_rdata, word);
          state_q <= SResp;
        end
        SWriteBack: if (wb_ready_i) state_q <= SFillReq;
        SFillReq: if (fill_req_ready_i) state_q <= SFillWait;
        SFillWait: if (fill_rsp_valid_i) begin
          rdata_q <= word_of(fill_merged, word);
          state_q <= SResp;
        end
        SFlush: begin
          victim_addr_q <= line_addr(tag_q[ram_addr*TagW +: TagW], scan_set_q);
          if (ram_en) state_q <= SFlushWb;  // the line's data on ram_rdata from the next cycle
          else if (flush_last) state_q <= SResp;
          else begin
            scan_way_q <= scan_way_q == WayW'(Ways - 1) ? '0 : scan_way_q + 1'b1;
            if (scan_way_q == WayW'(Ways - 1)) scan_set_q <= scan_set_q + 1'b1;
          end
        end
        SFlushWb: if (wb_ready_i) begin
          if (flush_last) state_q <= SResp;
          else begin
            scan_way_q <= scan_way_q == WayW'(Ways - 1) ? '0 : scan_way_q + 1'b1;
            if (scan_way_q == WayW'(Ways - 1)) scan_set_q <= scan_set_q + 1'b1;
            state_q <= SFlush;
          end
        end
        SResp: if (rsp_ready_i) state_q <= SIdle;
        default: state_q <= SIdle;
      endcase
    end
  end
endmodule

`default_nettype wire
