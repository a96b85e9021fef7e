// SPDX-License-Identifier: Apache-2.0
// rast_texture_cache: the texture unit's texel fetch (docs/texture.md, "RTL: the texture
// cache"): a read-only, set-associative, true-LRU cache of texel lines, the policy of
// model/ref/memory/cache.h (SetAssocCache) decision for decision, and the texel decode of
// model/ref/texture/texture.h (decode_texel) to RGBA8.
//
// - A request is up to 4 texels' byte addresses (AddrW bits each, texel k at
//   [k AddrW +: AddrW]), req_count_i of them (1 nearest, 4 bilinear; 0 looks nothing up
//   and answers texels 0, 5..7 are taken as 4), and the
//   format (0 rgba8888, 1 rgb565, 2 l8; 3 reserved, decoded as 0). Its response is the
//   texels decoded to RGBA8 (texel k at [32 k +: 32], R at [7:0]; texels k >= count 0),
//   one a request, in request order. Addresses are aligned to their texel's bytes (as the
//   reference places textures), so a texel never straddles a line.
// - Lookups in texel order, Ports a cycle: line = addr / LineBytes, set = line mod Sets,
//   tag = line / Sets. A cycle looks up texels k .. k + Ports - 1 and takes the hits up to
//   the first miss; a miss is looked up as the first of its cycle: it allocates the first
//   invalid way of its set, else the least recently used (rank Ways - 1), makes it the
//   most recent, and fetches the line; the cycle after the line's last beat looks the
//   texel up again (a hit, not counted: its way is the most recent already, so the
//   recency does not change) with the texels after it. Every counted access makes its way
//   the most recent: ranks as rast_rop_cache's (0 most recent; the ways more recent than
//   the touched one move down one), applied in texel order within a cycle.
// - Memory side: a fill is a request (mem_req_addr_o, the line's byte address; a burst of
//   LineBytes bytes) and LineBytes / BeatBytes beats on mem_rsp_*, beat b the line's bytes
//   [b BeatBytes, (b + 1) BeatBytes) (byte i at [8 i +: 8]), any latency. One miss in flight
//   (blocking, as the timed model's texture port).
// - Stats: evt_hits_o (texels that hit this cycle) and evt_miss_o (a miss this cycle): their
//   sums are texture_cache_hits and texture_cache_misses; the fills are the misses.
// - Storage: tags, valid bits and ranks in flip-flops, a row a set (Sets-entry arrays of
//   rows: a port reads its set's row through a Sets-way select, a write enables one row);
//   the data in Ports copies of rast_rop_cache_data (single-port SRAM, registered read),
//   copy p reading the texel looked up at position p of a cycle, every fill written to all
//   copies.
//
// Cycles (docs/texture.md): a request whose texels all hit takes ceil(count / Ports)
// lookup cycles, back to back (the next request is taken in the cycle of the last
// lookup); a response shows 2 cycles after its last lookup (data read, decode). A miss
// adds its lookup, the fill request (1 cycle when mem_req_ready_i is high), the beats
// (LineBytes / BeatBytes cycles from the cycle after the request, memory permitting), and
// ends the cycle's group: the texel's look-up again starts the next group.
`default_nettype none

module rast_texture_cache #(
  parameter int AddrW = 42,         // texel byte address bits (TextureRtlParams::addr_w)
  parameter int CacheBytes = 16384, // texture.cache_bytes: Sets x Ways x LineBytes
  parameter int Ways = 4,           // texture.ways
  parameter int LineBytes = 64,     // texture.line_bytes, a power of two >= 4
  parameter int Ports = 4,          // texel lookups a cycle, 1..4
  parameter int BeatBytes = 16      // bytes a fill beat, a power of two <= LineBytes
) (
  input  wire logic                   clk_i,            // core clock
  input  wire logic                   rst_ni,           // asynchronous reset, active low
  input  wire logic                   req_valid_i,
  output      logic                   req_ready_o,
  input  wire logic [4*AddrW-1:0]     req_addr_i,       // texel k's byte address at [k AddrW +: AddrW]
  input  wire logic [2:0]             req_count_i,      // texels, 1..4 (0: none; 5..7: 4)
  input  wire logic [1:0]             req_format_i,     // 0 rgba8888, 1 rgb565, 2 l8
  output      logic                   rsp_valid_o,
  input  wire logic                   rsp_ready_i,
  output      logic [127:0]           rsp_texels_o,     // texel k's RGBA8 at [32 k +: 32], R at [7:0]
  output      logic                   mem_req_valid_o,  // a line fill
  input  wire logic                   mem_req_ready_i,
  output      logic [AddrW-1:0]       mem_req_addr_o,   // the line's byte address (LineBytes bytes)
  input  wire logic                   mem_rsp_valid_i,  // a beat of the line
  output      logic                   mem_rsp_ready_o,
  input  wire logic [8*BeatBytes-1:0] mem_rsp_data_i,
  output      logic [2:0]             evt_hits_o,       // counted hits this cycle, 0..Ports
  output      logic                   evt_miss_o        // a miss this cycle
);
  localparam int Sets = CacheBytes / (Ways * LineBytes);
  localparam int OffW = $clog2(LineBytes);
  localparam int SetW = $clog2(Sets);
  localparam int TagW = AddrW - OffW - SetW;
  localparam int SetIdxW = SetW > 0 ? SetW : 1;
  localparam int WayW = Ways > 1 ? $clog2(Ways) : 1;
  localparam int Entries = Sets * Ways;
  localparam int EntW = Entries > 1 ? $clog2(Entries) : 1;
  localparam int Beats = LineBytes / BeatBytes;
  localparam int BeatW = Beats > 1 ? $clog2(Beats) : 1;
  localparam int RowRankW = Ways * WayW;
  localparam int RowTagW = Ways * TagW;

  if (Sets < 1 || (Sets & (Sets - 1)) != 0 || Sets * Ways * LineBytes != CacheBytes) begin : g_check_sets
    $error("rast_texture_cache: CacheBytes (%0d) must be Ways (%0d) x LineBytes (%0d) x a power of two", CacheBytes,
           Ways, LineBytes);
  end
  if (LineBytes < 4 || (LineBytes & (LineBytes - 1)) != 0 || BeatBytes < 1 || (BeatBytes & (BeatBytes - 1)) != 0 ||
      BeatBytes > LineBytes) begin : g_check_line
    $error("rast_texture_cache: LineBytes (%0d) must be a power of two >= 4, BeatBytes (%0d) one <= LineBytes",
           LineBytes, BeatBytes);
  end
  if (Ports < 1 || Ports > 4) begin : g_check_ports
    $error("rast_texture_cache: Ports (%0d) must be in 1..4", Ports);
  end
  if (TagW < 1) begin : g_check_tag
    $error("rast_texture_cache: AddrW (%0d) must exceed the line offset and set bits (%0d)", AddrW, OffW + SetW);
  end

  typedef enum logic [1:0] { SLookup, SFillReq, SFill } state_e;

  // ---- State ----
  state_e                  state_q;
  // A row a set, way w at [w TagW +: TagW], [w WayW +: WayW], [w]. Rows, not one flat vector
  // of Entries: a part-select at a variable offset of a 7,680-bit vector (the default's tags)
  // made Yosys build barrel shifters across all of it for each of the 16 tag reads, and its
  // synthesis did not finish in 45 minutes (docs/texture.md, "Area").
  logic [RowTagW-1:0]      tag_q [Sets];
  logic [RowRankW-1:0]     rank_q [Sets];   // recency: 0 most recent
  logic [Ways-1:0]         valid_q [Sets];
  // The request being looked up.
  logic                    cur_valid_q;
  logic [4*AddrW-1:0]      cur_addr_q;
  logic [2:0]              cur_count_q, k_q;  // texels; the next to look up
  logic [1:0]              cur_format_q;
  logic                    replay_q;   // texel k follows its fill: its hit is not counted
  logic [EntW-1:0]         fill_entry_q;
  logic [BeatW-1:0]        beat_q;
  // The data stage: the texels read in the previous lookup cycle.
  logic                    d_valid_q, d_last_q;
  logic [Ports-1:0]        d_take_q;
  logic [3*Ports-1:0]      d_idx_q;    // texel index of position p at [3 p +: 3]
  logic [Ports*OffW-1:0]   d_off_q;    // its byte in the line
  logic [1:0]              d_format_q;
  logic [127:0]            asm_q;      // the request's texels decoded so far
  logic                    rsp_valid_q;
  logic [127:0]            rsp_q;

  function automatic logic [EntW-1:0] entry(input logic [SetIdxW-1:0] s, input logic [WayW-1:0] w);
    entry = EntW'(s) * EntW'(Ways) + EntW'(w);
  endfunction
  localparam int LineW = AddrW - OffW;  // a line number
  function automatic logic [SetIdxW-1:0] set_of(input logic [LineW-1:0] l);
    // verilator lint_off UNUSEDSIGNAL
    logic [LineW-1:0] line;  // the set is its low bits (none with one set)
    // verilator lint_on UNUSEDSIGNAL
    line = l;
    set_of = SetW > 0 ? line[SetIdxW-1:0] : '0;
  endfunction
  // A row of ranks after `w` is touched: w most recent, the ways more recent than it down one.
  function automatic logic [RowRankW-1:0] touch(input logic [RowRankW-1:0] row, input logic [WayW-1:0] w);
    for (int i = 0; i < Ways; i++) begin
      touch[i*WayW +: WayW] = row[i*WayW +: WayW];
      if (row[i*WayW +: WayW] < row[w*WayW +: WayW]) touch[i*WayW +: WayW] = row[i*WayW +: WayW] + 1'b1;
      if (WayW'(i) == w) touch[i*WayW +: WayW] = '0;
    end
  endfunction

  // The D stage holds the request's last group and the response register is full: hold.
  logic stall;
  assign stall = d_valid_q && d_last_q && rsp_valid_q && !rsp_ready_i;
  logic lookup;  // a lookup cycle
  assign lookup = state_q == SLookup && cur_valid_q && !stall;

  // ---- Lookup of positions p = 0 .. Ports-1 (texel k + p) ----
  logic [Ports-1:0]         active, hit, take;
  logic [Ports*WayW-1:0]    way;       // the hit way (position 0: the victim on a miss)
  logic [Ports*SetIdxW-1:0] set;
  logic [Ports*RowRankW-1:0] row_after;  // position p's set's ranks after its touch
  logic [RowTagW-1:0]       tags0;     // position 0's set's row of tags and valid bits
  logic [Ways-1:0]          valid0;
  logic [2:0]               n_take;
  always_comb begin
    logic prefix;
    logic found;
    logic [RowRankW-1:0] row_before;
    logic [RowTagW-1:0] row_tag;
    logic [Ways-1:0] row_valid;
    prefix = 1'b1;
    found = 1'b0;
    n_take = '0;
    row_after = '0;
    tags0 = '0;
    valid0 = '0;
    for (int p = 0; p < Ports; p++) begin
      logic [LineW-1:0] l;
      logic [SetIdxW-1:0] s;
      l = cur_addr_q[(32'(k_q) + p) % 4 * AddrW + OffW +: LineW];
      s = set_of(l);
      set[p*SetIdxW +: SetIdxW] = s;
      row_tag = tag_q[s];
      row_valid = valid_q[s];
      if (p == 0) begin
        tags0 = row_tag;
        valid0 = row_valid;
      end
      active[p] = 32'(k_q) + p < 32'(cur_count_q);
      hit[p] = 1'b0;
      way[p*WayW +: WayW] = '0;
      for (int w = 0; w < Ways; w++)
        if (row_valid[w] && row_tag[w*TagW +: TagW] == l[LineW-1 -: TagW]) begin
          hit[p] = 1'b1;
          way[p*WayW +: WayW] = WayW'(w);
        end
      prefix = prefix && active[p] && hit[p];
      take[p] = prefix;
      if (prefix) n_take = n_take + 1'b1;
      // The set's ranks before this touch: the last earlier position in the same set, else the array's.
      row_before = rank_q[s];
      for (int q = 0; q < p; q++)
        if (take[q] && set[q*SetIdxW +: SetIdxW] == s) row_before = row_after[q*RowRankW +: RowRankW];
      if (p == 0 && !hit[0]) begin  // the victim: the first invalid way, else rank Ways - 1
        for (int w = 0; w < Ways; w++)
          if (!found && !row_valid[w]) begin
            found = 1'b1;
            way[WayW-1:0] = WayW'(w);
          end
        if (!found)
          for (int w = 0; w < Ways; w++)
            if (row_before[w*WayW +: WayW] == WayW'(Ways - 1)) way[WayW-1:0] = WayW'(w);
      end
      row_after[p*RowRankW +: RowRankW] = touch(row_before, way[p*WayW +: WayW]);
    end
  end
  logic miss, done;  // this lookup's first texel misses; the request's last texel is taken
  assign miss = lookup && active[0] && !hit[0];
  assign done = lookup && !miss && 32'(k_q) + 32'(n_take) >= 32'(cur_count_q);

  assign req_ready_o = !cur_valid_q || done;
  assign evt_miss_o = miss;
  assign evt_hits_o = lookup ? n_take - 3'(replay_q) : '0;
  assign mem_req_valid_o = state_q == SFillReq;
  assign mem_req_addr_o = {cur_addr_q[32'(k_q) * AddrW + OffW +: LineW], OffW'(0)};
  assign mem_rsp_ready_o = state_q == SFill;
  assign rsp_valid_o = rsp_valid_q;
  assign rsp_texels_o = rsp_q;

  // ---- The data copies ----
  logic [Ports*8*LineBytes-1:0] rdata;
  logic                         fill_we;
  logic [LineBytes-1:0]         fill_mask;
  assign fill_we = state_q == SFill && mem_rsp_valid_i;
  always_comb begin
    fill_mask = '0;
    fill_mask[32'(beat_q) * BeatBytes +: BeatBytes] = '1;
  end
  for (genvar p = 0; p < Ports; p++) begin : g_copy
    rast_rop_cache_data #(.Entries(Entries), .LineBytes(LineBytes)) u_data (
      .clk_i, .en_i(fill_we || (lookup && take[p])), .we_i(fill_we),
      .addr_i(fill_we ? fill_entry_q : entry(set[p*SetIdxW +: SetIdxW], way[p*WayW +: WayW])),
      .wmask_i(fill_mask), .wdata_i({Beats{mem_rsp_data_i}}), .rdata_o(rdata[p*8*LineBytes +: 8*LineBytes]));
  end

  // ---- Decode (decode_texel): the texel at byte `off` of `line` in format `f` ----
  function automatic logic [31:0] decode(input logic [8*LineBytes-1:0] line, input logic [OffW-1:0] off,
                                         input logic [1:0] f);
    logic [31:0] v;
    v = 32'(line >> (32'(off) * 8));
    case (f)
      2'd0: decode = v;
      2'd1: decode = {8'hff, v[4:0], v[4:2], v[10:5], v[10:9], v[15:11], v[15:13]};
      2'd2: decode = {8'hff, v[7:0], v[7:0], v[7:0]};
      default: decode = '0;
    endcase
  endfunction
  logic [127:0] asm_n;  // asm_q with the D stage's texels
  always_comb begin
    asm_n = asm_q;
    for (int p = 0; p < Ports; p++)
      if (d_take_q[p])
        asm_n[32'(d_idx_q[3*p +: 3]) * 32 +: 32] =
            decode(rdata[p*8*LineBytes +: 8*LineBytes], d_off_q[p*OffW +: OffW], d_format_q);
  end

  // ---- Tags, valid bits, ranks ----
  // A miss's set row: the victim way's tag replaced and made valid.
  logic [RowTagW-1:0] fill_tags;
  logic [Ways-1:0]    fill_valid;
  always_comb begin
    fill_tags = tags0;
    fill_tags[way[WayW-1:0]*TagW +: TagW] = cur_addr_q[32'(k_q) * AddrW + AddrW - TagW +: TagW];
    fill_valid = valid0;
    fill_valid[way[WayW-1:0]] = 1'b1;
  end
  // The ranks at reset: way w has rank w in every set.
  function automatic logic [RowRankW-1:0] ranks_reset();
    for (int w = 0; w < Ways; w++) ranks_reset[w*WayW +: WayW] = WayW'(w);
  endfunction
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      for (int s = 0; s < Sets; s++) begin
        valid_q[s] <= '0;
        tag_q[s] <= '0;
        rank_q[s] <= ranks_reset();
      end
    end else if (miss) begin
      valid_q[set[SetIdxW-1:0]] <= fill_valid;
      tag_q[set[SetIdxW-1:0]] <= fill_tags;
      rank_q[set[SetIdxW-1:0]] <= row_after[RowRankW-1:0];
    end else if (lookup) begin
      for (int p = 0; p < Ports; p++)  // in order: a later touch of the same set includes the earlier ones
        if (take[p]) rank_q[set[p*SetIdxW +: SetIdxW]] <= row_after[p*RowRankW +: RowRankW];
    end
  end

  // ---- The request, the fill, the data stage and the response ----
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      state_q <= SLookup;
      cur_valid_q <= 1'b0;
      cur_addr_q <= '0;
      cur_count_q <= '0;
      cur_format_q <= '0;
      k_q <= '0;
      replay_q <= 1'b0;
      fill_entry_q <= '0;
      beat_q <= '0;
      d_valid_q <= 1'b0;
      d_last_q <= 1'b0;
      d_take_q <= '0;
      d_idx_q <= '0;
      d_off_q <= '0;
      d_format_q <= '0;
      asm_q <= '0;
      rsp_valid_q <= 1'b0;
      rsp_q <= '0;
    end else begin
      if (rsp_ready_i) rsp_valid_q <= 1'b0;
      if (!stall) begin  // the data stage takes what this cycle looked up (nothing outside lookups)
        if (d_valid_q) begin
          asm_q <= d_last_q ? '0 : asm_n;
          if (d_last_q) begin
            rsp_q <= asm_n;
            rsp_valid_q <= 1'b1;
          end
        end
        d_valid_q <= lookup && !miss;
        d_last_q <= done;
        d_take_q <= lookup ? take : '0;
        d_format_q <= cur_format_q;
        for (int p = 0; p < Ports; p++) begin
          d_idx_q[3*p +: 3] <= 3'(32'(k_q) + p);
          d_off_q[p*OffW +: OffW] <= cur_addr_q[(32'(k_q) + p) % 4 * AddrW +: OffW];
        end
      end
      case (state_q)
        SLookup: begin
          if (miss) begin
            fill_entry_q <= entry(set[SetIdxW-1:0], way[WayW-1:0]);
            state_q <= SFillReq;
          end else if (lookup) begin
            k_q <= k_q + n_take;
            replay_q <= 1'b0;
          end
          if (req_valid_i && req_ready_o) begin
            cur_valid_q <= 1'b1;
            cur_addr_q <= req_addr_i;
            cur_count_q <= req_count_i > 3'd4 ? 3'd4 : req_count_i;
            cur_format_q <= req_format_i;
            k_q <= '0;
          end else if (done) cur_valid_q <= 1'b0;
        end
        SFillReq: if (mem_req_ready_i) begin
          beat_q <= '0;
          state_q <= SFill;
        end
        SFill: if (mem_rsp_valid_i) begin
          beat_q <= beat_q + 1'b1;
          if (beat_q == BeatW'(Beats - 1)) begin
            replay_q <= 1'b1;
            state_q <= SLookup;
          end
        end
        default: state_q <= SLookup;
      endcase
    end
  end
endmodule

`default_nettype wire
