// SPDX-License-Identifier: Apache-2.0
// rast_rop: the ROP. Depth test and depth write, colour write and the clears, over a
// memory request/response port (docs/rtl.md "ROP"); the arithmetic of model/ref/rop.h
// (rop_write, depth_test) and the cycles of TimingParams (model/config/timing_params.h:
// rop_accesses, rop_fragment_cycles, rop_clear_cycles).
//
//   fragment beats -> access buffer -> group of up to PixelsPerCycle accesses
//     -> read port (depth) -> response: depth test -> write port (colour, depth)
//
// - Accesses (TimingParams::rop_accesses): a fragment whose mask is full (or any fragment
//   with one sample a pixel) is one access, a burst of S words (its pixel's samples);
//   any other fragment one access a covered sample, a burst of one word. Each sample is
//   still tested against its own stored depth (rop_write). A tile's accesses (the beats
//   up to in_last_i: one batch) leave the buffer PixelsPerCycle a cycle; a group never
//   holds two batches' accesses and only a batch's last group is short, so a batch of A
//   accesses issues ceil(A / PixelsPerCycle) groups, one a cycle while the memory keeps
//   up: rop_fragment_cycles.
// - Access buffer: a ring of fragments, not of accesses. A beat's lanes with an access are
//   packed (Lanes x Lanes) and written after the held ones; a group is cut from the P
//   oldest fragments, each lane k picking its fragment by the fragments' running access
//   counts and its sample as the n-th covered one (skip_q counts the oldest fragment's
//   accesses already issued). No structure muxes from Lanes MaxSamples accesses, so
//   elaboration and area grow with Lanes and P, not with MaxSamples.
// - Memory: a 32-bit word a sample. Sample s of pixel (x, y) is the word at
//   base + ((y W + x) S + s) 4 (W = fb_width_i, S = 2^samples_log2_i): colour at
//   color_base_i as bytes {r, g, b, a = 255} (a word {a, b, g, r}), depth at depth_base_i in
//   the low DepthW bits (ceil(DepthW / 8) bytes enabled on a write). A request carries
//   up to PixelsPerCycle lanes (read) or 2 PixelsPerCycle (write: lane k colour, lane
//   PixelsPerCycle + k depth of access k), each a byte address, a burst length in words
//   and one data word, written to each word of the burst under that word's byte enables
//   (a fragment's colour or depth to its samples; a clear's value). wr_fill_o: every word
//   of each lane's burst takes word 0's enables (a clear's burst is longer than
//   MaxSamples words). Read data returns in request order, a response
//   (rd_rvalid_i) per request, in a later cycle. The memory orders a read after every
//   write it took in the same cycle or earlier (write first), so a group's read may go
//   out in the cycle the previous group's write does.
// - One group in flight: a group's read goes out when no group waits for its response or
//   write, or when the waiting one's write is taken (or it writes nothing) in that cycle.
//   The depth test is combinational on the response; a write the port does not take is
//   held (w_q) until it is.
// - Markers: a marker beat is taken with the command on the command port (one command a
//   marker, fed in stream order) once every earlier access is done: cmd_op_i 0 passes
//   (1 cycle: rop_state_cycles), 1 and 2 clear colour or depth with cmd_value_i: after
//   the marker's cycle, one write a cycle of ClearPixelsPerCycle pixels (a fill burst of
//   ClearPixelsPerCycle S words), ceil(W H / ClearPixelsPerCycle) cycles
//   (rop_clear_cycles).
// - The depth function and depth write (raster.depth_func, raster.depth_write) are
//   static inputs, as the rest of the raster state in rast_top.
`default_nettype none

module rast_rop #(
  parameter int PixelW = 12,               // pixel x, y, unsigned
  parameter int DepthW = 24,               // raster.depth_bits, 1 .. 32
  parameter int MaxSamples = 4,            // largest raster.samples (a power of two)
  parameter int SampleLog2W = 3,           // samples_log2_i bits
  parameter int Lanes = 4,                 // fragment lanes a beat (interp.fragments_per_cycle)
  parameter int PixelsPerCycle = 4,        // accesses a cycle (rop.pixels_per_cycle)
  parameter int ClearPixelsPerCycle = 64,  // pixels a clear writes a cycle (rop.clear_pixels_per_cycle)
  parameter int AddrW = 32,                // byte address bits
  // Derived (leave at the default): a burst's length in words, up to a clear's.
  parameter int LenW = $clog2(ClearPixelsPerCycle * MaxSamples + 1)
) (
  input  wire logic                                   clk_i,          // core clock
  input  wire logic                                   rst_ni,         // asynchronous reset, active low
  input  wire logic [SampleLog2W-1:0]                 samples_log2_i, // log2 raster.samples (static)
  input  wire logic [PixelW-1:0]                      fb_width_i,     // framebuffer width, px (static)
  input  wire logic [PixelW-1:0]                      fb_height_i,    // framebuffer height, px (static)
  input  wire logic [AddrW-1:0]                       color_base_i,   // colour surface, byte address (static)
  input  wire logic [AddrW-1:0]                       depth_base_i,   // depth surface, byte address (static)
  input  wire logic [2:0]                             depth_func_i,   // raster.depth_func as ref DepthFunc (static)
  input  wire logic                                   depth_write_i,  // raster.depth_write (static)
  // Fragments (rast_top's fragment port).
  input  wire logic                                   in_valid_i,     // a fragment beat or marker
  output      logic                                   in_ready_o,     // taken
  input  wire logic                                   in_marker_i,    // a marker
  input  wire logic                                   in_last_i,      // a tile's (batch's) last beat
  input  wire logic [Lanes-1:0]                       in_lanes_i,     // lanes holding a fragment
  input  wire logic [Lanes*PixelW-1:0]                in_x_i,         // lane j x
  input  wire logic [Lanes*PixelW-1:0]                in_y_i,         // lane j y
  input  wire logic [Lanes*DepthW-1:0]                in_z_i,         // lane j depth
  input  wire logic [Lanes*24-1:0]                    in_rgb_i,       // lane j colour {b, g, r}
  input  wire logic [Lanes*MaxSamples-1:0]            in_mask_i,      // lane j sample mask
  // Commands, one a marker in stream order.
  input  wire logic                                   cmd_valid_i,    // a command
  output      logic                                   cmd_ready_o,    // taken (with its marker)
  input  wire logic [1:0]                             cmd_op_i,       // 0 pass, 1 clear colour, 2 clear depth, 3 pass
  input  wire logic [31:0]                            cmd_value_i,    // clear word: colour {a, b, g, r}, or depth
  // Memory reads: depth.
  output      logic                                   rd_valid_o,     // a read request
  input  wire logic                                   rd_ready_i,     // taken
  output      logic [PixelsPerCycle-1:0]              rd_lanes_o,     // lanes of the request
  output      logic [PixelsPerCycle*AddrW-1:0]        rd_addr_o,      // lane k byte address
  output      logic [PixelsPerCycle*LenW-1:0]         rd_len_o,       // lane k burst, words
  output      logic                                   rd_no_depth_o,  // the group's tile is tested with always: no depth read
  input  wire logic                                   rd_rvalid_i,    // the oldest read's data
  input  wire logic [PixelsPerCycle*MaxSamples*32-1:0] rd_rdata_i,    // lane k word i at [(k MaxSamples + i) 32 +: 32]
  // Memory writes: colour (lane k) and depth (lane PixelsPerCycle + k).
  output      logic                                   wr_valid_o,     // a write request
  input  wire logic                                   wr_ready_i,     // taken
  output      logic [2*PixelsPerCycle-1:0]            wr_lanes_o,     // lanes of the request
  output      logic [2*PixelsPerCycle*AddrW-1:0]      wr_addr_o,      // lane k byte address
  output      logic [2*PixelsPerCycle*LenW-1:0]       wr_len_o,       // lane k burst, words
  output      logic                                   wr_fill_o,      // each lane's word 0 fills its burst
  output      logic [2*PixelsPerCycle*MaxSamples*4-1:0]  wr_be_o,     // lane k word i byte enables
  output      logic [2*PixelsPerCycle*32-1:0]         wr_data_o,      // lane k data word
  output      logic                                   idle_o,         // nothing held, nothing in flight
  // Stage observation (rast_top's dbg_*_o): works this cycle, starts a batch (its first
  // group's read taken) or command (its marker taken), finishes a batch or clear (a pass
  // command starts and finishes in its marker's cycle), offers a request that is not taken.
  output      logic                                   dbg_has_o,
  output      logic                                   dbg_start_o,
  output      logic                                   dbg_done_o,
  output      logic                                   dbg_blocked_o,
  // Hi-Z hooks (rast_top with a table; docs/depth-culling.md "RTL"): the oldest batch not
  // ended (hiz_always_i) and the next one (hiz_always_next_i) are tested with `always`
  // (their tile was Hi-Z accepted): a batch's groups then read no depth (rd_no_depth_o),
  // taken at its first group's read; the depth writes it decides this cycle (one sample:
  // lane k's pixel and depth); a batch's end (its last group decided) or a marker taken;
  // a depth clear's marker taken (value cmd_value_i).
  input  wire logic                                   hiz_always_i,
  input  wire logic                                   hiz_always_next_i,
  output      logic [PixelsPerCycle-1:0]              hiz_wr_lanes_o,
  output      logic [PixelsPerCycle*PixelW-1:0]       hiz_wr_x_o,
  output      logic [PixelsPerCycle*PixelW-1:0]       hiz_wr_y_o,
  output      logic [PixelsPerCycle*DepthW-1:0]       hiz_wr_z_o,
  output      logic                                   hiz_end_o,
  output      logic                                   hiz_marker_o,
  output      logic                                   hiz_clear_o
);
  localparam int P = PixelsPerCycle;
  localparam int SBits = MaxSamples > 1 ? $clog2(MaxSamples) : 1;  // a sample index
  // The access buffer holds up to Cap accesses (a beat is taken while Lanes MaxSamples
  // more fit) as fragments, FCap entries: every fragment held is at least one access, so
  // at most Cap - Lanes MaxSamples + Lanes of them.
  localparam int Cap = 1 << $clog2(P + Lanes * MaxSamples);
  localparam int CapW = $clog2(Cap);
  localparam int FCap = 1 << $clog2(Cap - Lanes * MaxSamples + Lanes);
  localparam int FCapW = $clog2(FCap);
  localparam int LaneW = Lanes > 1 ? $clog2(Lanes) : 1;  // a beat's fragment index
  localparam int DepthBytes = (DepthW + 7) / 8;
  localparam logic [3:0] DepthBe = 4'((1 << DepthBytes) - 1);

  if (DepthW < 1 || DepthW > 32) begin : g_check_depth
    $error("rast_rop: DepthW (%0d) must be in 1..32 (a depth value is a 32-bit word)", DepthW);
  end
  if (MaxSamples < 1 || (MaxSamples & (MaxSamples - 1)) != 0) begin : g_check_samples
    $error("rast_rop: MaxSamples (%0d) must be a power of two", MaxSamples);
  end

  // One access: a pixel's samples (full: a burst of S words from sample 0) or one
  // sample, as bit fields of an AccW-bit word (Yosys 0.23 has no struct-typed variable in
  // a procedural block, and no array of structs).
  localparam int AccLast = 0;             // the batch's last access
  localparam int AccFull = 1;             // all S samples
  localparam int AccS0 = 2;               // first sample, SBits
  localparam int AccRgb = AccS0 + SBits;  // colour {b, g, r}, 24
  localparam int AccZ = AccRgb + 24;      // depth, DepthW
  localparam int AccY = AccZ + DepthW;    // pixel y, PixelW
  localparam int AccX = AccY + PixelW;    // pixel x, PixelW
  localparam int AccW = AccX + PixelW;
  // One fragment of the buffer: the access fields above AccS0 and its sample mask.
  localparam int FrLast = 0;                   // its last access ends the batch
  localparam int FrFull = 1;                   // one access, all S samples
  localparam int FrMask = 2;                   // covered samples (per-sample accesses), MaxSamples
  localparam int FrRgb = FrMask + MaxSamples;  // {x, y, z, rgb}, as from AccRgb up
  localparam int FrW = FrRgb + AccW - AccRgb;

  // The write request of a group (or held: w_q).
  typedef struct packed {
    logic [2*P-1:0]               lanes;
    logic [2*P*AddrW-1:0]         addr;
    logic [2*P*LenW-1:0]          len;
    logic [2*P*MaxSamples*4-1:0]  be;
    logic [2*P*32-1:0]            data;
  } wreq_t;

  // ---- State ----
  logic [FrW-1:0]  frag_q [FCap];   // the access buffer, a ring of fragments
  logic [FCapW-1:0] fhead_q;        // oldest fragment
  logic [FCapW:0]  fcount_q;        // fragments held
  logic [SBits-1:0] skip_q;         // accesses of the oldest fragment already issued
  logic [CapW:0]   count_q;         // accesses held
  logic            q_valid_q;       // a group's read taken, its response not yet in
  logic [P*AccW-1:0] q_acc_q;       // that group, access k at [k AccW +: AccW]
  logic [P-1:0]    q_lanes_q;
  logic            w_valid_q;       // a group's write not yet taken
  wreq_t           w_q;
  logic            w_last_q;        // it ends a batch
  logic [2:0]      depth_func_q;    // depth_func_i, registered (static)
  logic            depth_write_q;   // depth_write_i
  logic            q_last_q;        // the group in flight ends a batch
  logic            first_q;         // the next group starts a batch
  logic            batch_always_q;  // the batch of the last group read is tested with always
  logic            q_always_q;      // the group in flight is
  logic            clr_active_q;    // a clear in progress
  logic            clr_depth_q;     // of the depth surface
  logic [31:0]     clr_value_q;
  logic [AddrW-1:0] clr_addr_q;     // its next write's byte address
  logic [2*PixelW:0] clr_left_q;    // pixels left

  // ---- Geometry of the framebuffer ----
  logic [SampleLog2W-1:0] slog2;
  logic [MaxSamples:0]    s_count;  // S
  assign slog2 = samples_log2_i;
  assign s_count = (MaxSamples + 1)'(1) << slog2;

  // Byte offset of sample s of pixel (x, y) within a surface.
  function automatic logic [AddrW-1:0] word_offset(input logic [PixelW-1:0] x, input logic [PixelW-1:0] y,
                                                   input logic [SBits-1:0] s);
    logic [2*PixelW-1:0] pixel;  // y W + x < W H
    pixel = (2 * PixelW)'(y) * (2 * PixelW)'(fb_width_i) + (2 * PixelW)'(x);
    word_offset = ((AddrW'(pixel) << slog2) + AddrW'(s)) << 2;
  endfunction

  // Covered samples of a mask: a fragment's accesses when its mask is not full.
  function automatic logic [CapW:0] covered(input logic [MaxSamples-1:0] m);
    covered = '0;
    for (int i = 0; i < MaxSamples; i++) covered = covered + (CapW + 1)'(m[i]);
  endfunction

  // ---- The next group: up to P accesses from the head, never past a batch's end ----
  // Group lane k is access k from the head: of fragment f (of the P oldest) when
  // start_f <= k < start_f + n_f (n_f its accesses not yet issued); its sample the
  // (k - start_f + skip)-th covered one (skip for the oldest fragment only).
  logic [CapW:0] grp_n;      // accesses in it (0: none ready)
  logic [P*AccW-1:0] grp;   // access k at [k AccW +: AccW]
  logic [P-1:0]  grp_lanes;
  logic          grp_last;   // it ends a batch
  logic [FrW-1:0] head_fr [P];       // the P oldest fragments (one read of the ring each)
  logic [CapW:0] fr_start [P + 1];  // access index of the oldest fragments' first (P: past them)
  for (genvar f = 0; f < P; f++) begin : g_head
    assign head_fr[f] = frag_q[fhead_q + FCapW'(f)];
  end
  always_comb begin
    logic ended, hit;
    logic [CapW:0] upto, r, seen;
    logic [FrW-1:0] sel;
    logic [CapW:0] n;
    logic [SBits-1:0] s0;
    logic [AccW-1:0] a;
    fr_start[0] = '0;
    for (int f = 0; f < P; f++) begin
      n = head_fr[f][FrFull] ? (CapW + 1)'(1) : covered(head_fr[f][FrMask +: MaxSamples]);
      if (f == 0) n = n - (CapW + 1)'(skip_q);
      fr_start[f + 1] = (FCapW + 1)'(f) < fcount_q ? fr_start[f] + n : fr_start[f];
    end
    ended = 1'b0;
    upto = '0;
    for (int k = 0; k < P; k++) begin
      sel = '0;
      r = '0;
      hit = 1'b0;
      for (int f = 0; f < P; f++) begin
        if (fr_start[f] <= (CapW + 1)'(k) && (CapW + 1)'(k) < fr_start[f + 1]) begin
          sel = head_fr[f];
          r = (CapW + 1)'(k) - fr_start[f] + (f == 0 ? (CapW + 1)'(skip_q) : '0);
          hit = (CapW + 1)'(k) + 1'b1 == fr_start[f + 1];
        end
      end
      s0 = '0;
      seen = '0;
      for (int i = 0; i < MaxSamples; i++) begin
        if (sel[FrMask + i] && seen == r) s0 = SBits'(i);
        seen = seen + (CapW + 1)'(sel[FrMask + i]);
      end
      if (sel[FrFull]) s0 = '0;
      a = {sel[FrRgb +: AccW - AccRgb], s0, sel[FrFull], 1'b0};
      a[AccLast] = sel[FrLast] && hit;
      grp[k*AccW +: AccW] = a;
      if (!ended && (CapW + 1)'(k) < count_q) begin
        upto = (CapW + 1)'(k + 1);
        ended = a[AccLast];
      end
    end
    // A full group, or a short one that ends its batch.
    grp_n = (ended || count_q >= (CapW + 1)'(P)) ? upto : '0;
    grp_last = ended;
    for (int k = 0; k < P; k++) grp_lanes[k] = (CapW + 1)'(k) < grp_n;
  end

  // ---- The response: depth test, the group's write ----
  // Each word of the response against its access's depth: rast_depth_pass, the early
  // test's table too (one copy). A group of a batch tested with always passes every word.
  logic [2:0] resp_func;                  // ref DepthFunc of the group in flight
  logic [P*MaxSamples-1:0] resp_word_pass;  // lane k word i at [k MaxSamples + i]
  assign resp_func = q_always_q ? 3'd7 : depth_func_q;
  for (genvar k = 0; k < P; k++) begin : g_resp_lane
    for (genvar i = 0; i < MaxSamples; i++) begin : g_word
      /* verilator lint_off UNUSEDSIGNAL */  // the bits above DepthW: the stored depth is the low DepthW
      logic [31:0] word;
      /* verilator lint_on UNUSEDSIGNAL */
      assign word = rd_rdata_i[(k*MaxSamples + i)*32 +: 32];
      rast_depth_pass #(.DepthW(DepthW)) u_pass (
        .func_i(resp_func), .z_i(q_acc_q[k*AccW + AccZ +: DepthW]),
        .stored_i(word[DepthW-1:0]), .pass_o(resp_word_pass[k*MaxSamples + i]));
    end
  end
  wreq_t resp_w;
  logic  resp_any;
  always_comb begin
    logic [AddrW-1:0] off;
    logic [LenW-1:0]  len;
    /* verilator lint_off UNUSEDSIGNAL */
    logic [AccW-1:0]  a;  // its last flag is the group's (q_last_q)
    /* verilator lint_on UNUSEDSIGNAL */
    logic [MaxSamples-1:0]   pass;      // the access's words that pass the test
    logic [MaxSamples*4-1:0] cbe, zbe;  // their colour and depth byte enables
    resp_w = '0;
    for (int k = 0; k < P; k++) begin
      a = q_acc_q[k*AccW +: AccW];
      off = word_offset(a[AccX +: PixelW], a[AccY +: PixelW], a[AccS0 +: SBits]);
      len = a[AccFull] ? LenW'(s_count) : LenW'(1);
      resp_w.addr[k*AddrW +: AddrW] = color_base_i + off;
      resp_w.addr[(P + k)*AddrW +: AddrW] = depth_base_i + off;
      resp_w.len[k*LenW +: LenW] = len;
      resp_w.len[(P + k)*LenW +: LenW] = len;
      resp_w.data[k*32 +: 32] = {8'hff, a[AccRgb +: 24]};
      resp_w.data[(P + k)*32 +: 32] = 32'(a[AccZ +: DepthW]);
      // Per word into narrow variables, then one store a lane into the wide request
      // (Verilator stores into a wide vector a field at a time).
      for (int i = 0; i < MaxSamples; i++) begin
        pass[i] = q_lanes_q[k] && LenW'(i) < len && resp_word_pass[k*MaxSamples + i];
        cbe[i*4 +: 4] = pass[i] ? 4'hf : 4'h0;
        zbe[i*4 +: 4] = pass[i] && depth_write_q ? DepthBe : 4'h0;
      end
      resp_w.be[k*MaxSamples*4 +: MaxSamples*4] = cbe;
      resp_w.be[(P + k)*MaxSamples*4 +: MaxSamples*4] = zbe;
      resp_w.lanes[k] = |pass;
      resp_w.lanes[P + k] = |pass && depth_write_q;
    end
    resp_any = |resp_w.lanes;
  end

  // ---- The clear's write ----
  wreq_t clr_w;
  always_comb begin
    logic [LenW-1:0] n;  // pixels this write
    n = clr_left_q < (2 * PixelW + 1)'(ClearPixelsPerCycle) ? LenW'(clr_left_q) : LenW'(ClearPixelsPerCycle);
    clr_w = '0;
    clr_w.lanes[0] = 1'b1;
    clr_w.addr[0 +: AddrW] = clr_addr_q;
    clr_w.len[0 +: LenW] = n << slog2;
    clr_w.be[0 +: 4] = clr_depth_q ? DepthBe : 4'hf;
    clr_w.data[0 +: 32] = clr_value_q;
  end

  // ---- Handshakes ----
  logic resp_now;     // the waiting group's response is in
  logic resp_done;    // ... and its write is taken or it writes nothing
  logic w_done;       // the held write is taken
  logic free;         // no group in flight after this cycle
  logic rd_take, beat_take, marker_take;
  logic cmd_clear;    // the command is a clear (op 1 or 2; 0 and 3 pass)
  assign resp_now = q_valid_q && rd_rvalid_i;
  assign resp_done = resp_now && (!resp_any || wr_ready_i);
  assign w_done = w_valid_q && wr_ready_i;
  assign free = (!q_valid_q && !w_valid_q) || resp_done || w_done;

  assign rd_valid_o = grp_n != '0 && free && !clr_active_q;
  assign rd_lanes_o = grp_lanes;
  always_comb begin
    /* verilator lint_off UNUSEDSIGNAL */
    logic [AccW-1:0] g;  // the address and length need no colour, depth or batch end
    /* verilator lint_on UNUSEDSIGNAL */
    for (int k = 0; k < P; k++) begin
      g = grp[k*AccW +: AccW];
      rd_addr_o[k*AddrW +: AddrW] = depth_base_i + word_offset(g[AccX +: PixelW], g[AccY +: PixelW], g[AccS0 +: SBits]);
      rd_len_o[k*LenW +: LenW] = g[AccFull] ? LenW'(s_count) : LenW'(1);
    end
  end
  assign rd_take = rd_valid_o && rd_ready_i;
  // The group's batch is tested with `always`: a batch's first group is the oldest batch
  // not ended when no group is in flight (the previous batch ended at its last response),
  // else the next (the read goes out in the cycle the previous batch's last response
  // ends it); its later groups keep the batch's answer.
  logic grp_always;
  assign grp_always = first_q ? (q_valid_q ? hiz_always_next_i : hiz_always_i) : batch_always_q;
  assign rd_no_depth_o = grp_always;

  wreq_t wr;
  assign wr = clr_active_q ? clr_w : w_valid_q ? w_q : resp_w;
  assign wr_valid_o = clr_active_q || w_valid_q || (resp_now && resp_any);
  assign wr_lanes_o = wr.lanes;
  assign wr_addr_o = wr.addr;
  assign wr_len_o = wr.len;
  assign wr_be_o = wr.be;
  assign wr_data_o = wr.data;
  assign wr_fill_o = clr_active_q;

  // A beat when the buffer has room for a full one; a marker with its command once every
  // earlier access is done.
  logic quiet;
  assign quiet = count_q == '0 && free && !clr_active_q;
  assign in_ready_o = in_marker_i ? quiet && cmd_valid_i
                                  : !clr_active_q && count_q + (CapW + 1)'(Lanes * MaxSamples) <= (CapW + 1)'(Cap);
  assign cmd_ready_o = in_valid_i && in_marker_i && quiet;
  assign marker_take = in_valid_i && in_marker_i && quiet && cmd_valid_i;
  assign beat_take = in_valid_i && !in_marker_i && in_ready_o;
  assign cmd_clear = cmd_op_i == 2'd1 || cmd_op_i == 2'd2;

  // ---- The beat's fragments, in lane order ----
  // The lanes with at least one access, packed: slot i is the lane with i such lanes below
  // it; new_n their accesses (a full mask one, else one a covered sample).
  logic [FrW-1:0]  new_fr [1 << LaneW];
  logic [LaneW:0]  new_frn;  // fragments
  logic [CapW:0]   new_n;    // accesses
  logic [FrW-1:0]  beat_fr [Lanes];   // lane j's fragment
  logic [LaneW:0]  beat_idx [Lanes];  // its slot
  logic [Lanes-1:0] beat_has;         // it has an access
  always_comb begin
    logic [MaxSamples-1:0] full_mask, mask;
    full_mask = MaxSamples'(((MaxSamples + 1)'(1) << s_count) - 1'b1);
    new_frn = '0;
    new_n = '0;
    for (int j = 0; j < Lanes; j++) begin
      mask = slog2 == '0 ? MaxSamples'(1) : in_mask_i[j*MaxSamples +: MaxSamples] & full_mask;
      beat_has[j] = in_lanes_i[j] && mask != '0;
      beat_fr[j] = {in_x_i[j*PixelW +: PixelW], in_y_i[j*PixelW +: PixelW], in_z_i[j*DepthW +: DepthW], in_rgb_i[j*24 +: 24],
               mask, mask == full_mask, 1'b0};
      beat_idx[j] = new_frn;
      new_frn = new_frn + (LaneW + 1)'(beat_has[j]);
      if (beat_has[j]) new_n = new_n + (mask == full_mask ? (CapW + 1)'(1) : covered(mask));
    end
    for (int i = 0; i < (1 << LaneW); i++) begin
      new_fr[i] = '0;
      for (int j = 0; j < Lanes; j++) begin
        if (beat_has[j] && beat_idx[j] == (LaneW + 1)'(i)) begin
          new_fr[i] = beat_fr[j];
          new_fr[i][FrLast] = in_last_i && beat_idx[j] + 1'b1 == new_frn;
        end
      end
    end
  end

  // ---- Registers ----
  logic [CapW:0] drained;
  logic [FCapW:0] fr_done;     // the oldest fragments the group issues every access of
  logic [SBits-1:0] skip_next;
  assign drained = rd_take ? grp_n : '0;
  always_comb begin
    logic [SBits-1:0] part;  // of the first fragment left, accesses issued
    fr_done = '0;
    for (int f = 1; f <= P; f++) if (fr_start[f] <= drained && (FCapW + 1)'(f) <= fcount_q) fr_done = (FCapW + 1)'(f);
    part = '0;
    for (int f = 0; f < P; f++) if (fr_done == (FCapW + 1)'(f)) part = SBits'(drained - fr_start[f]);
    skip_next = fr_done == '0 ? skip_q + part : part;
  end
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      fhead_q <= '0;
      fcount_q <= '0;
      skip_q <= '0;
      count_q <= '0;
      q_valid_q <= 1'b0;
      w_valid_q <= 1'b0;
      clr_active_q <= 1'b0;
      first_q <= 1'b1;
    end else begin
      fhead_q <= fhead_q + fr_done[FCapW-1:0];
      fcount_q <= fcount_q - fr_done + (beat_take ? (FCapW + 1)'(new_frn) : '0);
      skip_q <= skip_next;
      if (rd_take) first_q <= grp_last;
      count_q <= count_q - drained + (beat_take ? new_n : '0);
      // The group in flight: read taken -> response -> write (held until taken).
      if (rd_take) q_valid_q <= 1'b1;
      else if (resp_now) q_valid_q <= 1'b0;
      if (resp_now && resp_any && !wr_ready_i) w_valid_q <= 1'b1;
      else if (w_done) w_valid_q <= 1'b0;
      if (marker_take) begin
        clr_active_q <= cmd_clear && fb_width_i != '0 && fb_height_i != '0;
      end else if (clr_active_q && wr_ready_i && clr_left_q <= (2 * PixelW + 1)'(ClearPixelsPerCycle)) begin
        clr_active_q <= 1'b0;
      end
    end
  end
  always_ff @(posedge clk_i) begin
    depth_func_q <= depth_func_i;
    depth_write_q <= depth_write_i;
    if (rd_take) begin
      q_acc_q <= grp;
      q_lanes_q <= grp_lanes;
      q_always_q <= grp_always;
      batch_always_q <= grp_always;
    end
    if (resp_now && resp_any && !wr_ready_i) begin
      w_q <= resp_w;
      w_last_q <= q_last_q;
    end
    if (rd_take) q_last_q <= grp_last;
    if (marker_take) begin
      clr_depth_q <= cmd_op_i == 2'd2;
      clr_value_q <= cmd_value_i;
      clr_addr_q <= cmd_op_i == 2'd2 ? depth_base_i : color_base_i;
      clr_left_q <= (2 * PixelW + 1)'(fb_width_i) * (2 * PixelW + 1)'(fb_height_i);
    end else if (clr_active_q && wr_ready_i) begin
      clr_addr_q <= clr_addr_q + ((AddrW'(ClearPixelsPerCycle) << slog2) << 2);
      clr_left_q <= clr_left_q - (2 * PixelW + 1)'(ClearPixelsPerCycle);
    end
  end

  // The beat's fragments into the ring after the held ones: entry e takes slot
  // (e - tail) mod FCap when that is one of the beat's.
  logic [FCapW-1:0] tail;
  assign tail = fhead_q + fcount_q[FCapW-1:0];
  for (genvar e = 0; e < FCap; e++) begin : g_ring
    logic [FCapW-1:0] i;
    assign i = FCapW'(e) - tail;
    always_ff @(posedge clk_i) begin
      if (beat_take && (FCapW + 1)'(i) < (FCapW + 1)'(new_frn)) frag_q[e] <= new_fr[LaneW'(i)];
    end
  end

  // ---- Hi-Z hooks ----
  for (genvar k = 0; k < P; k++) begin : g_hiz
    assign hiz_wr_lanes_o[k] = resp_now && resp_w.lanes[P + k];
    assign hiz_wr_x_o[k*PixelW +: PixelW] = q_acc_q[k*AccW + AccX +: PixelW];
    assign hiz_wr_y_o[k*PixelW +: PixelW] = q_acc_q[k*AccW + AccY +: PixelW];
    assign hiz_wr_z_o[k*DepthW +: DepthW] = q_acc_q[k*AccW + AccZ +: DepthW];
  end
  assign hiz_end_o = resp_now && q_last_q;
  assign hiz_marker_o = marker_take;
  assign hiz_clear_o = marker_take && cmd_op_i == 2'd2;

  // ---- Observation ----
  assign idle_o = count_q == '0 && !q_valid_q && !w_valid_q && !clr_active_q;
  // Works this cycle: issues a group's read, a clear's write or takes a marker, waits for
  // its read's response (a memory slower than a cycle: a line fill), or holds a write the
  // memory refuses (a batch's last write, taken, is not a cycle of its own: a batch of A
  // accesses works rop_fragment_cycles(A) cycles with a one-cycle memory, the SystemC
  // model's; with a slower one, to its last group's response: memory_group_response).
  assign dbg_has_o = rd_valid_o || clr_active_q || marker_take || w_valid_q || (wr_valid_o && !wr_ready_i) ||
                     (q_valid_q && !rd_rvalid_i);
  assign dbg_start_o = (rd_take && first_q) || marker_take;
  assign dbg_done_o = (resp_done && q_last_q) || (w_done && w_last_q) ||
                      (clr_active_q && wr_ready_i && clr_left_q <= (2 * PixelW + 1)'(ClearPixelsPerCycle));
  assign dbg_blocked_o = (rd_valid_o && !rd_ready_i) || (wr_valid_o && !wr_ready_i);
endmodule

`default_nettype wire
