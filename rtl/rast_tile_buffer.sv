// SPDX-License-Identifier: Apache-2.0
// rast_tile_buffer: the on-chip tile buffer of binned mode (pipeline.mode = binned;
// docs/binning.md "Timed model", docs/rtl.md "Tile buffer"). The ROP reads and writes it
// instead of the framebuffer in memory while a bin renders; a bin's begin marker loads it
// from memory (or starts it from the frame's initial value), its end marker stores it.
//
//   ROP memory port (bin-local addresses) -> colour and depth arrays (Slots samples each)
//   bin begin: loads, reads through the memory port tl_* (waited for), PortBytes a cycle
//   bin end:   stores, posted writes through tl_*, PortBytes a cycle
//   bin clear: a flash clear, ClearPixelsPerCycle pixels a cycle of time
//
// - Storage: Slots = bin.tile_buffer_bytes / (4 + depth bytes) samples (TileBufferSamples,
//   model/rtlsim/rtl_params.cpp): a 32-bit colour word {a, b, g, r} and a DepthW-bit depth
//   a sample, each with a valid bit. Sample s of bin pixel (x', y') (x' = x - bin x0) is
//   slot (y' w + x') S + s, w the bin's width clipped to the screen: the ROP addresses it
//   with fb_width_i = w, colour base 0 and depth base Slots 4 (rast_top), so its address
//   arithmetic is the immediate mode's. The arrays and their valid bits are
//   rast_tile_buffer_data (an SRAM macro: a blackbox to `rastsim area`, counted as
//   storage rows; this module's ports and logic around it). A slot not valid reads as its surface's fill
//   value: the frame's initial value (colour opaque black, depth the far value
//   2^DepthW - 1: ref render_scene's framebuffer) after a begin marker that does not load
//   the surface (the reference's tile buffer is the framebuffer, untouched before a
//   bin's first pass), or a clear's value.
// - ROP port: a read taken in cycle c answers in c + 1 from the arrays (which hold every
//   write taken up to c: the ROP's one-cycle memory, rop_fragment_cycles); writes apply
//   each lane's words under their byte enables. rd_ready_o and wr_ready_o are low while
//   a load, store or clear runs (busy_o), and the ROP's next command waits.
// - Commands (cmd_take_i: the ROP takes a marker with a command, rast_top's handshake;
//   every one is a pass at the ROP): op 4 begins a bin (cmd_bin_i its rectangle {y1, x1,
//   y0, x0}, half-open px; cmd_value_i bit 0 load colour, bit 1 load depth), op 5 ends it
//   (bit 0 store colour, bit 1 store depth), op 1 / 2 clears the bin's colour / depth to
//   cmd_value_i: valid bits cleared, the value the fill value, busy
//   ceil(A / ClearPixelsPerCycle) cycles from the marker's (the timed model's
//   rop_clear_cycles of the bin's A pixels).
// - Loads and stores walk the bin's rows of each surface in turn, a beat of up to
//   PortBytes a cycle from the marker's cycle (PortBytes / 4 colour words, PortBytes /
//   DepthBytes depth words, DepthBytes = 2 for DepthW <= 16, else 4, as the reference
//   counts a sample), never two rows in one beat: a row of w S samples is
//   ceil(w S bytes / PortBytes) beats, a bin ceil(L / PortBytes) when a row is a multiple
//   of PortBytes (the SystemC model's ceil(L / R), R = rop.resolve_bytes_per_cycle). Beat
//   addresses are the memory's layout (docs/rtl.md "ROP": sample s of pixel (x, y) at base
//   + ((y W + x) S + s) 4, W = fb_width_i). A load's responses come back in order
//   (tl_rvalid_i, tl_rdata_i) and the ROP waits until the last (it may read in that
//   cycle); a store beat's words follow its request by a cycle on tl_wdata_o (read from
//   the arrays after the ROP's last write, which may be taken in the end marker's cycle)
//   and the ROP waits until the last request is taken.
// - The per-bin resolve (end marker value bit 2: the frame's last pass with S =
//   2^samples_log2_i > 1, docs/binning.md "Timed model"): the colour surface is stored
//   resolved, one word a pixel at the one-sample layout (pixel (x, y) at base + (y W + x) 4),
//   each channel of a pixel's S samples averaged as the reference's Framebuffer::resolve
//   ((sum + S / 2) / S, 8 bits). A beat of k pixels first reads its k S samples,
//   ColorWords a cycle (ceil(k S / ColorWords) cycles from the marker's or the last beat's
//   next), then is issued: a row of ColorWords-multiple pixels costs its samples' bytes and
//   its resolved bytes at PortBytes a cycle, the SystemC ROP's resolve_cycles(A, S) =
//   ceil((A S 4 + A 4) / R). Depth, when stored too, follows every sample as before.
`default_nettype none

module rast_tile_buffer #(
  parameter int PixelW = 12,        // pixel x, y, unsigned
  parameter int DepthW = 24,        // raster.depth_bits
  parameter int MaxSamples = 4,     // largest raster.samples
  parameter int SampleLog2W = 3,    // samples_log2_i bits
  parameter int P = 4,              // the ROP's accesses a cycle (rop.pixels_per_cycle)
  parameter int LenW = 9,           // the ROP's burst length bits
  parameter int Slots = 4096,       // samples held (TileBufferSamples)
  parameter int PortBytes = 64,     // bytes a load or store beat (rop.resolve_bytes_per_cycle)
  parameter int ClearPixelsPerCycle = 64,  // a clear's pixels a cycle (rop.clear_pixels_per_cycle)
  parameter int AddrW = 32,         // byte address bits
  // Derived (leave at the default).
  parameter int DepthBytes = DepthW <= 16 ? 2 : 4,  // a depth sample's bytes in memory
  parameter int PortWords = PortBytes / DepthBytes  // words of the widest beat (depth)
) (
  input  wire logic                              clk_i,
  input  wire logic                              rst_ni,
  input  wire logic [SampleLog2W-1:0]            samples_log2_i,  // log2 raster.samples (static)
  input  wire logic [PixelW-1:0]                 fb_width_i,      // the screen's width, px (static)
  input  wire logic [AddrW-1:0]                  color_base_i,    // colour surface in memory (static)
  input  wire logic [AddrW-1:0]                  depth_base_i,    // depth surface in memory (static)
  // The ROP takes a marker with a bin command.
  input  wire logic                              cmd_take_i,
  input  wire logic [2:0]                        cmd_op_i,        // 4 begin, 5 end (others: nothing here)
  input  wire logic [31:0]                       cmd_value_i,     // bin: bit 0 colour, bit 1 depth loaded / stored, bit 2 (end) colour resolved; clear: its word
  input  wire logic [4*PixelW-1:0]               cmd_bin_i,       // {y1, x1, y0, x0}, half-open px
  output      logic                              busy_o,          // a load or store runs: the ROP waits
  output      logic [PixelW-1:0]                 bin_x0_o,        // the bin's origin, px
  output      logic [PixelW-1:0]                 bin_y0_o,
  output      logic [PixelW-1:0]                 bin_w_o,         // its size, px (clipped to the screen)
  output      logic [PixelW-1:0]                 bin_h_o,
  // The ROP's memory port (rast_rop's rd_*, wr_*), bin-local byte addresses.
  input  wire logic                              rd_valid_i,
  output      logic                              rd_ready_o,
  input  wire logic [P-1:0]                      rd_lanes_i,
  input  wire logic [P*AddrW-1:0]                rd_addr_i,
  input  wire logic [P*LenW-1:0]                 rd_len_i,
  output      logic                              rd_rvalid_o,
  output      logic [P*MaxSamples*32-1:0]        rd_rdata_o,
  input  wire logic                              wr_valid_i,
  output      logic                              wr_ready_o,
  input  wire logic [2*P-1:0]                    wr_lanes_i,
  input  wire logic [2*P*AddrW-1:0]              wr_addr_i,
  input  wire logic [2*P*LenW-1:0]               wr_len_i,
  input  wire logic [2*P*MaxSamples*4-1:0]       wr_be_i,
  input  wire logic [2*P*32-1:0]                 wr_data_i,
  // The memory port of loads and stores: a beat of tl_count_o words from byte address
  // tl_addr_o (consecutive words; a depth word's low DepthW bits), written (tl_write_o,
  // data tl_wdata_o word i at [32 i +: 32]) or read (its data later on tl_rdata_i, in order).
  output      logic                              tl_valid_o,
  input  wire logic                              tl_ready_i,
  output      logic                              tl_write_o,
  output      logic [AddrW-1:0]                  tl_addr_o,
  output      logic [$clog2(PortWords+1)-1:0]    tl_count_o,
  output      logic [PortWords*32-1:0]           tl_wdata_o,
  input  wire logic                              tl_rvalid_i,
  input  wire logic [PortWords*32-1:0]           tl_rdata_i,
  output      logic                              idle_o
);
  localparam int SlotW = $clog2(Slots + 1);                 // a slot index, 0 .. Slots
  localparam int CntW = $clog2(PortWords + 1);              // words of a beat
  localparam int RowW = PixelW + SampleLog2W + 4;           // words of a bin row, w S (up to 2^SampleLog2W - 1 shifts)
  localparam int ColorWords = PortBytes / 4;                // colour words a beat
  localparam int DepthWords = PortBytes / DepthBytes;       // depth words a beat
  localparam logic [31:0] InitColor = 32'hff000000;         // {a = 255, b, g, r = 0}: opaque black
  localparam logic [DepthW-1:0] InitDepth = {DepthW{1'b1}}; // the far value

  if (PortBytes < 4 || PortBytes % 4 != 0) begin : g_check_port
    $error("rast_tile_buffer: PortBytes (%0d) must be a positive multiple of 4", PortBytes);
  end
  if (PortWords != PortBytes / DepthBytes) begin : g_check_words
    $error("rast_tile_buffer: PortWords (%0d) must be PortBytes / DepthBytes (%0d)", PortWords, PortBytes / DepthBytes);
  end
  if (Slots < 2) begin : g_check_slots
    $error("rast_tile_buffer: Slots (%0d) must be at least 2", Slots);
  end
  localparam int IdxW = $clog2(Slots);  // an array index

  // ---- Storage: the arrays (rast_tile_buffer_data, an SRAM macro to `rastsim area`) ----
  // Read ports: the ROP's, a lane's samples (P MaxSamples), then a store beat's words
  // (PortWords), then a resolved store word's samples (PortWords MaxSamples). Write ports:
  // the ROP's, a lane's samples (2 P MaxSamples), then a load beat's words (PortWords).
  localparam int RopReads = P * MaxSamples;
  localparam int ResolveReads0 = RopReads + PortWords;  // a resolved store word's samples
  localparam int Reads = ResolveReads0 + PortWords * MaxSamples;
  localparam int RopWrites = 2 * P * MaxSamples;
  localparam int Writes = RopWrites + PortWords;
  logic [31:0]       col_fill_q;        // what a slot not valid holds: the initial value or a clear's
  logic [DepthW-1:0] dep_fill_q;
  logic              clear_col, clear_dep;  // a clear of the valid bits this cycle
  logic [Reads-1:0]       rd_dep, rd_in, rd_valid;  // a read port: depth; its slot < Slots; valid there
  logic [Reads*IdxW-1:0]  rd_slot;
  logic [Reads*32-1:0]    rd_word;
  logic [Writes-1:0]      wp_en, wp_dep;
  logic [Writes*IdxW-1:0] wp_slot;
  logic [Writes*4-1:0]    wp_be;
  logic [Writes*32-1:0]   wp_data;
  rast_tile_buffer_data #(.Slots(Slots), .DepthW(DepthW), .Reads(Reads), .Writes(Writes)) u_data (
    .clk_i, .col_fill_i(col_fill_q), .dep_fill_i(dep_fill_q), .clear_col_i(clear_col), .clear_dep_i(clear_dep),
    .rd_dep_i(rd_dep), .rd_slot_i(rd_slot), .rd_word_o(rd_word), .rd_valid_o(rd_valid), .wr_en_i(wp_en),
    .wr_dep_i(wp_dep), .wr_slot_i(wp_slot), .wr_be_i(wp_be), .wr_data_i(wp_data));
  // Read port r addressed at slot s of a surface (its word below: the fill value unless valid).
  function automatic logic [31:0] port_word(input int r);
    port_word = rd_in[r] && rd_valid[r] ? rd_word[r*32 +: 32] : rd_dep[r] ? 32'(dep_fill_q) : col_fill_q;
  endfunction
  // Store word i's resolved colour: each channel of its pixel's 2^l2 samples averaged,
  // (sum + 2^l2 / 2) >> l2 (ref Framebuffer::resolve; 8 + SampleLog2W bits a sum).
  localparam int SumW = 9 + $clog2(MaxSamples);
  function automatic logic [31:0] resolved_word(input int i, input logic [SampleLog2W-1:0] l2);
    logic [SumW-1:0] sum;
    logic [31:0] w;
    for (int c = 0; c < 4; c++) begin
      sum = SumW'((1 << l2) >> 1);
      for (int k = 0; k < MaxSamples; k++) begin
        w = port_word(ResolveReads0 + i * MaxSamples + k);  // store word i's sample k
        if (k < (1 << l2)) sum = sum + SumW'(w[c*8 +: 8]);
      end
      resolved_word[c*8 +: 8] = 8'(sum >> l2);
    end
  endfunction

  // ---- The bin and its load or store ----
  logic [PixelW-1:0] x0_q, y0_q, w_q, h_q;
  logic              depth_too_q;  // the load or store goes on to depth after colour
  logic              load_q;    // a load runs (else a store, when busy)
  logic              busy_q;    // a load or store runs
  logic              clr_busy_q;  // a clear's cycles after its marker's
  logic [2*PixelW:0] clr_left_q;  // its pixels left after this cycle's
  // The command taken this cycle.
  logic begin_take, end_take, clear_take, xfer_take;
  logic [1:0] cmd_flags;
  logic [PixelW-1:0] cx0, cy0, cx1, cy1;
  assign {cy1, cx1, cy0, cx0} = cmd_bin_i;
  assign begin_take = cmd_take_i && cmd_op_i == 3'd4;
  assign end_take = cmd_take_i && cmd_op_i == 3'd5;
  assign clear_take = cmd_take_i && (cmd_op_i == 3'd1 || cmd_op_i == 3'd2);
  assign xfer_take = begin_take || end_take;
  assign cmd_flags = cmd_value_i[1:0];
  // The bin as of this cycle: a begin's rectangle from its marker's cycle on.
  logic [PixelW-1:0] bx0, by0, bw, bh;
  logic depth_too;
  assign {bx0, by0} = begin_take ? {cx0, cy0} : {x0_q, y0_q};
  assign {bw, bh} = begin_take ? {cx1 - cx0, cy1 - cy0} : {w_q, h_q};
  assign depth_too = xfer_take ? cmd_flags[1] : depth_too_q;
  logic [RowW-1:0]   row_words, row_words_q;  // w S: of this cycle's bin, of the registered one
  assign row_words = RowW'(bw) << samples_log2_i;
  assign row_words_q = RowW'(w_q) << samples_log2_i;
  // The store resolves colour (end marker bit 2, S > 1): its colour rows are w words.
  logic rsv_q, rsv;
  assign rsv = xfer_take ? end_take && cmd_value_i[2] && samples_log2_i != '0 : rsv_q;
  logic [RowW-1:0] crow_words;  // this cycle's colour row: w resolved, else w S
  assign crow_words = rsv ? RowW'(bw) : row_words;
  // A walk over the surfaces' rows, a beat at a time: {done, surface (1: depth), row,
  // word in the row, slot}. The beats issued and (loads) the responses each walk it.
  localparam int WalkW = 2 + PixelW + RowW + SlotW;
  // Beats walk rows of `rw` words (colour: `crw`), `h` rows, colour then (`dtoo`) depth; a
  // resolved colour word (`rs`) is 2^`l2` slots.
  function automatic logic [CntW-1:0] beat_words(input logic [WalkW-1:0] wk, input logic [RowW-1:0] rw,
                                                 input logic [RowW-1:0] crw);
    logic [RowW-1:0] left, most;
    left = (wk[WalkW-2] ? rw : crw) - wk[SlotW +: RowW];
    most = wk[WalkW-2] ? RowW'(DepthWords) : RowW'(ColorWords);
    beat_words = CntW'(left < most ? left : most);
  endfunction
  function automatic logic [WalkW-1:0] walk_start(input logic [1:0] flags);
    walk_start = {!flags[0] && !flags[1], !flags[0], {(WalkW - 2){1'b0}}};
  endfunction
  function automatic logic [WalkW-1:0] walk_next(input logic [WalkW-1:0] wk, input logic [RowW-1:0] rw,
                                               input logic [RowW-1:0] crw, input logic [PixelW-1:0] h,
                                               input logic dtoo, input logic rs, input logic [SampleLog2W-1:0] l2);
    logic done, depth;
    logic [PixelW-1:0] row;
    logic [RowW-1:0] off;
    logic [SlotW-1:0] slot;
    done = 1'b0;
    depth = wk[WalkW-2];
    row = wk[SlotW + RowW +: PixelW];
    off = wk[SlotW +: RowW] + RowW'(beat_words(wk, rw, crw));
    slot = wk[0 +: SlotW] + (SlotW'(beat_words(wk, rw, crw)) << (rs && !depth ? l2 : '0));
    if (off == (depth ? rw : crw)) begin
      off = '0;
      row = row + 1'b1;
      if (row == h) begin
        row = '0;
        slot = '0;
        if (!depth && dtoo) depth = 1'b1;
        else done = 1'b1;
      end
    end
    walk_next = {done, depth, row, off, slot};
  endfunction
  logic [WalkW-1:0] iss_q, rsp_q;  // the next beat to issue; the next response (loads)
  logic [WalkW-1:0] iss_cur;       // the beat offered: a load's or store's first from its marker's cycle
  assign iss_cur = xfer_take ? walk_start(cmd_flags) : iss_q;
  logic            rs_beat;          // the offered beat is resolved colour
  logic [RowW-1:0] rdw_q, rdw_cur;   // its samples' words read so far

  // The offered beat: its memory address.
  logic [AddrW-1:0] beat_addr;
  always_comb begin
    logic [2*PixelW-1:0] pixel;
    pixel = ((2 * PixelW)'(by0) + (2 * PixelW)'(iss_cur[SlotW + RowW +: PixelW])) * (2 * PixelW)'(fb_width_i) +
            (2 * PixelW)'(bx0);
    beat_addr = (iss_cur[WalkW-2] ? depth_base_i : color_base_i) +
                (((AddrW'(pixel) << (rs_beat ? '0 : samples_log2_i)) + AddrW'(iss_cur[SlotW +: RowW])) << 2);
  end
  // A resolved beat waits for its samples' reads: rdw words read so far, ColorWords a cycle.
  assign rs_beat = rsv && !iss_cur[WalkW-2];
  assign rdw_cur = xfer_take ? '0 : rdw_q;
  logic            rs_wait;       // its samples not all read yet
  assign rs_wait = rs_beat && rdw_cur < (RowW'(tl_count_o) << samples_log2_i);
  assign tl_valid_o = (xfer_take || busy_q) && !iss_cur[WalkW-1] && !rs_wait;
  assign tl_write_o = xfer_take ? end_take : !load_q;
  assign tl_addr_o = beat_addr;
  assign tl_count_o = beat_words(iss_cur, row_words, crow_words);
  // A store beat's words follow its request by a cycle (read from the arrays then, after
  // every write the ROP made before its end marker).
  logic             wd_valid_q, wd_depth_q, wd_rsv_q;
  logic [SlotW-1:0] wd_slot_q;
  logic [CntW-1:0]  wd_count_q;
  for (genvar i = 0; i < PortWords; i++) begin : g_store_word
    logic [SlotW-1:0] s;
    assign s = wd_slot_q + SlotW'(i);
    assign rd_dep[RopReads + i] = wd_depth_q;
    assign rd_in[RopReads + i] = s < SlotW'(Slots);
    assign rd_slot[(RopReads + i)*IdxW +: IdxW] = IdxW'(s);
    // A resolved word's samples: its pixel's MaxSamples slots from wd_slot_q + i S.
    for (genvar k = 0; k < MaxSamples; k++) begin : g_sample
      localparam int R = ResolveReads0 + i * MaxSamples + k;  // the read port
      logic [SlotW-1:0] rs;
      assign rs = wd_slot_q + (SlotW'(i) << samples_log2_i) + SlotW'(k);
      assign rd_dep[R] = 1'b0;
      assign rd_in[R] = rs < SlotW'(Slots);
      assign rd_slot[R*IdxW +: IdxW] = IdxW'(rs);
    end
    assign tl_wdata_o[i*32 +: 32] = !wd_valid_q || CntW'(i) >= wd_count_q ? 32'h0 :
                                    wd_rsv_q && !wd_depth_q ? resolved_word(i, samples_log2_i) :
                                    port_word(RopReads + i);
  end
  logic iss_take, rsp_take;
  assign iss_take = tl_valid_o && tl_ready_i;
  assign rsp_take = busy_q && load_q && tl_rvalid_i && !rsp_q[WalkW-1];
  // Busy until a load's last response is in, or a store's last beat is taken.
  logic busy_next;
  logic [WalkW-1:0] iss_next, rsp_next;
  assign iss_next = walk_next(iss_cur, row_words, crow_words, bh, depth_too, rsv, samples_log2_i);
  assign rsp_next = walk_next(rsp_q, row_words_q, row_words_q, h_q, depth_too_q, 1'b0, samples_log2_i);  // a response: after its begin's cycle
  always_comb begin
    busy_next = busy_q;
    if (xfer_take) busy_next = cmd_flags != 2'b00 && !(end_take && iss_take && iss_next[WalkW-1]);
    else if (busy_q && load_q && rsp_take && rsp_next[WalkW-1]) busy_next = 1'b0;
    else if (busy_q && !load_q && iss_take && iss_next[WalkW-1]) busy_next = 1'b0;
  end
  // A load's last response frees the ROP in its own cycle (it reads the arrays a cycle
  // later); a store's last beat the cycle after.
  assign busy_o = (busy_q && !(load_q && rsp_take && rsp_next[WalkW-1])) || clr_busy_q;
  assign idle_o = !busy_q && !clr_busy_q && !wd_valid_q;
  assign {bin_x0_o, bin_y0_o, bin_w_o, bin_h_o} = {x0_q, y0_q, w_q, h_q};

  // A clear: its marker's cycle and ceil(A / ClearPixelsPerCycle) - 1 more (rop_clear_cycles).
  logic [2*PixelW:0] clr_area;
  assign clr_area = (2 * PixelW + 1)'(w_q) * (2 * PixelW + 1)'(h_q);
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      busy_q <= 1'b0;
      load_q <= 1'b0;
      clr_busy_q <= 1'b0;
      wd_valid_q <= 1'b0;
      iss_q <= {1'b1, {(WalkW - 1){1'b0}}};
      rsp_q <= {1'b1, {(WalkW - 1){1'b0}}};
      rsv_q <= 1'b0;
      rdw_q <= '0;
    end else begin
      if (xfer_take) rsv_q <= rsv;
      if (iss_take) rdw_q <= '0;
      else if (rs_wait && (xfer_take || busy_q) && !iss_cur[WalkW-1]) rdw_q <= rdw_cur + RowW'(ColorWords);
      busy_q <= busy_next;
      if (xfer_take) load_q <= begin_take;
      if (iss_take) iss_q <= iss_next;
      else if (xfer_take) iss_q <= iss_cur;
      if (begin_take) rsp_q <= walk_start(cmd_flags);
      else if (rsp_take) rsp_q <= rsp_next;
      wd_valid_q <= iss_take && tl_write_o;
      if (clear_take) begin
        clr_busy_q <= clr_area > (2 * PixelW + 1)'(ClearPixelsPerCycle);
        clr_left_q <= clr_area - (2 * PixelW + 1)'(ClearPixelsPerCycle);
      end else if (clr_busy_q) begin
        clr_busy_q <= clr_left_q > (2 * PixelW + 1)'(ClearPixelsPerCycle);
        clr_left_q <= clr_left_q - (2 * PixelW + 1)'(ClearPixelsPerCycle);
      end
    end
  end
  always_ff @(posedge clk_i) begin
    if (begin_take) begin
      x0_q <= cx0;
      y0_q <= cy0;
      w_q <= cx1 - cx0;
      h_q <= cy1 - cy0;
    end
    if (xfer_take) depth_too_q <= cmd_flags[1];
    wd_slot_q <= iss_cur[0 +: SlotW];
    wd_count_q <= tl_count_o;
    wd_depth_q <= iss_cur[WalkW-2];
    wd_rsv_q <= rs_beat;
  end

  // ---- The ROP's port: reads answered the next cycle, writes applied ----
  localparam int DepthSlot = Slots * 4;  // the ROP's depth base (rast_top)
  logic              rq_valid_q;
  logic [P-1:0]      rq_lanes_q;
  logic [P*AddrW-1:0] rq_addr_q;
  logic [P*LenW-1:0] rq_len_q;
  assign rd_ready_o = !busy_o;
  assign wr_ready_o = !busy_o;
  assign rd_rvalid_o = rq_valid_q;
  // A bin-local byte address as {depth, slot}.
  function automatic logic [SlotW:0] local_slot(input logic [AddrW-1:0] a);
    local_slot = a >= AddrW'(DepthSlot) ? {1'b1, SlotW'((a - AddrW'(DepthSlot)) >> 2)} : {1'b0, SlotW'(a >> 2)};
  endfunction
  for (genvar k = 0; k < P; k++) begin : g_rop_read
    logic [SlotW:0] ls;
    assign ls = local_slot(rq_addr_q[k*AddrW +: AddrW]);
    for (genvar i = 0; i < MaxSamples; i++) begin : g_word
      logic [SlotW-1:0] s;
      assign s = ls[SlotW-1:0] + SlotW'(i);
      assign rd_dep[k*MaxSamples + i] = ls[SlotW];
      assign rd_in[k*MaxSamples + i] = s < SlotW'(Slots);
      assign rd_slot[(k*MaxSamples + i)*IdxW +: IdxW] = IdxW'(s);
      assign rd_rdata_o[(k*MaxSamples + i)*32 +: 32] =
          rq_lanes_q[k] && LenW'(i) < rq_len_q[k*LenW +: LenW] ? port_word(k*MaxSamples + i) : 32'h0;
    end
  end
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) rq_valid_q <= 1'b0;
    else rq_valid_q <= rd_valid_i && rd_ready_o;
  end
  always_ff @(posedge clk_i) begin
    if (rd_valid_i && rd_ready_o) begin
      rq_lanes_q <= rd_lanes_i;
      rq_addr_q <= rd_addr_i;
      rq_len_q <= rd_len_i;
    end
  end

  // Word writes: the ROP's (a group's lanes, or a clear's fill burst), a load's response,
  // each a write port of the arrays (the bytes not enabled of a word not valid: the fill
  // value). A clear (op 1 colour, 2 depth: its word on cmd_value_i) clears the surface's
  // valid bits and makes its value the fill value: a flash clear, timed as
  // ClearPixelsPerCycle pixels a cycle. A clear taken with a load's last response wins.
  logic rop_wr;
  assign rop_wr = wr_valid_i && wr_ready_o;
  assign clear_col = (begin_take && !cmd_flags[0]) || (clear_take && cmd_op_i == 3'd1);
  assign clear_dep = (begin_take && !cmd_flags[1]) || (clear_take && cmd_op_i == 3'd2);
  always_ff @(posedge clk_i) begin
    if (begin_take && !cmd_flags[0]) col_fill_q <= InitColor;
    if (begin_take && !cmd_flags[1]) dep_fill_q <= InitDepth;
    if (clear_take && cmd_op_i == 3'd1) col_fill_q <= cmd_value_i;
    if (clear_take && cmd_op_i == 3'd2) dep_fill_q <= DepthW'(cmd_value_i);
  end
  for (genvar k = 0; k < 2 * P; k++) begin : g_rop_lane
    logic [SlotW:0] ls;
    assign ls = local_slot(wr_addr_i[k*AddrW +: AddrW]);
    for (genvar i = 0; i < MaxSamples; i++) begin : g_word
      localparam int W = k * MaxSamples + i;  // the write port
      logic [SlotW-1:0] s;
      logic [3:0] be;
      assign s = ls[SlotW-1:0] + SlotW'(i);
      assign be = wr_be_i[W*4 +: 4];
      assign wp_en[W] = rop_wr && wr_lanes_i[k] && LenW'(i) < wr_len_i[k*LenW +: LenW] && be != 4'h0 &&
                        s < SlotW'(Slots);
      assign wp_dep[W] = ls[SlotW];
      assign wp_slot[W*IdxW +: IdxW] = IdxW'(s);
      assign wp_be[W*4 +: 4] = be;
      assign wp_data[W*32 +: 32] = wr_data_i[k*32 +: 32];
    end
  end
  for (genvar i = 0; i < PortWords; i++) begin : g_load_word
    localparam int W = RopWrites + i;  // the write port
    logic [SlotW-1:0] s;
    assign s = rsp_q[0 +: SlotW] + SlotW'(i);
    assign wp_en[W] = rsp_take && CntW'(i) < beat_words(rsp_q, row_words_q, row_words_q) && s < SlotW'(Slots);
    assign wp_dep[W] = rsp_q[WalkW-2];
    assign wp_slot[W*IdxW +: IdxW] = IdxW'(s);
    assign wp_be[W*4 +: 4] = 4'hf;
    assign wp_data[W*32 +: 32] = tl_rdata_i[i*32 +: 32];
  end
endmodule

`default_nettype wire
