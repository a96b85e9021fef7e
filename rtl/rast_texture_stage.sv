// SPDX-License-Identifier: Apache-2.0
// rast_texture_stage: the texture unit in rast_top, between the interpolator and the
// fragment FIFO's beat packer (docs/texture.md "RTL"; ref: model/ref/texture/texture_unit.cpp
// TextureUnit::shade; model: model/sc/texture.cpp).
//
// - In: the interpolator's beats (Lanes fragments), with the texture state of the tile
//   they belong to (in_tex_*: the triangle's, valid with every non-marker beat). A
//   textured tile's beats hold whole 2x2 quads (fine raster closes the mask), row-major,
//   one row pair (pixel rows 2m, 2m + 1) a beat at most (the interpolator stops a beat
//   there): a lane whose sample mask is 0 is a helper pixel, shaded for the derivatives
//   and dropped here (counted on helpers_o in the cycle its beat is taken).
// - An untextured beat or a marker passes straight through (same cycle) once nothing
//   textured is held or in flight, so the order of fragments and markers is kept.
// - Quad table (the derivatives, docs/texture.md "Level of detail"): a textured beat is
//   taken into the beat FIFO (BeatDepth beats: a row pair's and two more) and, as it is
//   taken, its lanes write the quad table: per quad column (TileMax / 2) of each of two
//   banks, the s, t of the quad's top-left, top-right and bottom-left pixels; the bottom-
//   left marks the quad ready. A bank is a row pair's: the beats of a new row pair take
//   the other bank once the row pair that last used it has all its covered fragments
//   serialised (cnt_q). The fragments leave in the reference's order (row-major), so a
//   top-row fragment waits in the FIFO until the row below has been taken (the FIFO's
//   depth lets the tap run a row pair ahead).
// - A textured tile's covered fragments, one a cycle (the serialiser, from the FIFO's
//   head), each with its quad's coarse derivatives (ds/dx = s(x0 + 1, y0) - s(x0, y0),
//   ds/dy = s(x0, y0 + 1) - s(x0, y0), t alike), go through rast_texture_lod (the levels
//   and the trilinear weight, a fragment a cycle: the quad's result for each of its
//   fragments), the level sequencer (one level sample a cycle into rast_texture_address:
//   level k, and level k + 1 where trilinear reads two), the texel fetch port (tex_req_*:
//   one level sample a request, its 1 or 4 byte addresses; tex_rsp_*: the texels as
//   RGBA8, in request order, any number of cycles later), rast_texture_filter (a
//   trilinear second level blended with the first's output, chained; the first's output
//   dropped) and rast_texture_combine (texenv), and leave on lane 0, one fragment a beat,
//   the tile's last flagged. A fragment is held in the serialiser (pend) until the next
//   covered lane is loaded, so that the tile's last covered fragment carries `last`.
// - Mip levels: level k is max(1, W >> k) x max(1, H >> k) texels at in_base_i + off[k];
//   off[] (the reference's placement: each level's footprint by layout and format,
//   aligned to 256 bytes) is a table of LevelsMax offsets filled by a small sequencer a
//   level a cycle when a mipmapped texture of another size than the table's arrives
//   (its fragments wait; level 0 never needs it).
// - In flight: at most Depth fragments between the serialiser and the output (a ring of
//   their data, read in order at the level sequencer, the request, the filter's input,
//   the filter's output and the output).
// - Early Z (Early = 1, depth.early; docs/depth-culling.md "Early Z in the RTL"): in_culled_i
//   flags the lanes rast_early_z culled (the test between the interpolator and this stage).
//   A culled lane is covered (its quad's derivatives are still written) but not a
//   fragment of the serialiser: it takes no serialiser cycle, no LOD, no level sample, no
//   texel fetch, no filter or combine work (the rule of model/sc/texture.cpp: a culled
//   fragment is not sampled; a beat without a kept lane costs its one cycle, as a beat of
//   helper pixels). It keeps its place: the order queue (OqDepth entries, one a kept
//   fragment loaded or a beat without one) holds, in the reference's order, the culled
//   lanes of the beat before a kept fragment (pre), the kept fragment (its colour from the
//   combine) and the culled lanes after the beat's last kept one (post), or a beat's
//   culled lanes alone; an entry leaves as one beat, its lanes in their places (the culled
//   ones as interpolated, out_culled_o set: the ROP's late test fails them, their depth
//   reads are the reference's early reads). The tile's last output carries `last`: an
//   entry with culled lanes not yet known to be the tile's last waits at the queue's head
//   until an entry follows it or the tile's last beat flags it. Early = 0 builds no queue.
`default_nettype none

module rast_texture_stage #(
  parameter int Lanes       = 4,   // fragments a beat (interp.fragments_per_cycle)
  parameter int PixelW      = 14,  // pixel index bits
  parameter int DepthW      = 24,  // depth bits
  parameter int MaxSamples  = 16,  // sample mask bits a pixel
  parameter int TexW        = 28,  // s, t: 1 + I + F of interp.texcoord_format, signed
  parameter int TexFrac     = 20,  // F of interp.texcoord_format
  parameter int WeightBits  = 8,   // texture.weight_bits
  parameter int SizeW       = 15,  // a texture side, texels: 1 .. 2^(SizeW-1)
  parameter int AddrW       = 42,  // a texel's byte address
  parameter int Depth       = 16,  // fragments in flight (a power of two)
  parameter int TileLog2Max = 4,   // largest tile: 2^TileLog2Max pixels square
  parameter int LevelW      = 4,   // a mip level index
  parameter int BiasW       = 14,  // texlod_bias in s.8, signed
  parameter int Early       = 0,   // depth.early: 1 builds the culled lanes' order queue
  localparam int HelpW = $clog2(Lanes + 1)  // derived: helper count bits
) (
  input  wire logic                        clk_i,
  input  wire logic                        rst_ni,        // asynchronous reset, active low
  input  wire logic [1:0]                  format_i,      // texture.format: 0 rgba8888, 1 rgb565, 2 l8 (static)
  input  wire logic [1:0]                  layout_i,      // texture.layout: 0 linear, 1 tiled, 2 morton (static)
  // The interpolator's beats (rast_interpolate's out_*).
  input  wire logic                        in_valid_i,
  output      logic                        in_ready_o,
  input  wire logic                        in_marker_i,
  input  wire logic                        in_last_i,
  input  wire logic [Lanes-1:0]            in_lanes_i,
  input  wire logic [Lanes*PixelW-1:0]     in_x_i,
  input  wire logic [Lanes*PixelW-1:0]     in_y_i,
  input  wire logic [Lanes*DepthW-1:0]     in_z_i,
  input  wire logic [Lanes*24-1:0]         in_rgb_i,      // {b, g, r}
  input  wire logic [Lanes*TexW-1:0]       in_s_i,
  input  wire logic [Lanes*TexW-1:0]       in_t_i,
  input  wire logic [Lanes*MaxSamples-1:0] in_smask_i,    // 0: a helper pixel
  input  wire logic [Lanes-1:0]            in_culled_i,   // lane j culled early (Early; a covered lane)
  // The tile's texture state (the triangle's), with every non-marker beat.
  input  wire logic                        in_tex_on_i,   // a texture bound
  input  wire logic                        in_bilinear_i, // texfilter bilinear (else nearest, or trilinear)
  input  wire logic                        in_trilinear_i,// texfilter trilinear (bilinear on each level)
  input  wire logic [1:0]                  in_wrap_s_i,   // 0 repeat, 1 clamp, 2 mirror
  input  wire logic [1:0]                  in_wrap_t_i,
  input  wire logic [1:0]                  in_env_i,      // texenv: 0 replace, 1 modulate, 2 decal
  input  wire logic [SizeW-1:0]            in_width_i,    // level 0, texels
  input  wire logic [SizeW-1:0]            in_height_i,
  input  wire logic [AddrW-1:0]            in_base_i,     // level 0's byte address
  input  wire logic [LevelW-1:0]           in_levels_i,   // levels sampled: the chain's, 1 with mipmap off
  input  wire logic [BiasW-1:0]            in_bias_i,     // texlod_bias, s.8
  // Out: beats as the interpolator's, into the beat packer.
  output      logic                        out_valid_o,
  input  wire logic                        out_ready_i,
  output      logic                        out_marker_o,
  output      logic                        out_last_o,
  output      logic [Lanes-1:0]            out_lanes_o,
  output      logic [Lanes*PixelW-1:0]     out_x_o,
  output      logic [Lanes*PixelW-1:0]     out_y_o,
  output      logic [Lanes*DepthW-1:0]     out_z_o,
  output      logic [Lanes*24-1:0]         out_rgb_o,
  output      logic [Lanes*TexW-1:0]       out_s_o,
  output      logic [Lanes*TexW-1:0]       out_t_o,
  output      logic [Lanes*MaxSamples-1:0] out_smask_o,
  output      logic [Lanes-1:0]            out_culled_o,  // lane j culled early (passed through, or a culled group)
  // The texel fetch port (docs/texture.md "RTL": the texture cache's interface).
  output      logic                        tex_req_valid_o,
  input  wire logic                        tex_req_ready_i,
  output      logic [4*AddrW-1:0]          tex_req_addr_o,    // texel k's byte address at [k*AddrW +: AddrW]
  output      logic [2:0]                  tex_req_count_o,   // 1 nearest, 4 bilinear
  output      logic [1:0]                  tex_req_format_o,  // texture.format
  input  wire logic                        tex_rsp_valid_i,
  output      logic                        tex_rsp_ready_o,
  input  wire logic [127:0]                tex_rsp_texels_i,  // texel k as RGBA8 at [32k +: 32], R at [7:0]
  output      logic [HelpW-1:0]            helpers_o,     // helper pixels dropped this cycle
  output      logic                        busy_o         // a textured fragment held or in flight
);
  if ((Depth & (Depth - 1)) != 0 || Depth < 2) begin : g_check_depth
    $error("rast_texture_stage: Depth (%0d) must be a power of two >= 2", Depth);
  end
  if (TileLog2Max < 1) begin : g_check_tile
    $error("rast_texture_stage: TileLog2Max (%0d) must be >= 1 (quads)", TileLog2Max);
  end
  localparam int PtrW = $clog2(Depth);  // derived
  localparam int LaneW = Lanes > 1 ? $clog2(Lanes) : 1;  // derived: a lane's index
  localparam int PosW = $clog2(Lanes + 1);  // derived: next lane to look at, 0 .. Lanes
  localparam int QCols = TileLog2Max > 1 ? 1 << (TileLog2Max - 1) : 1;  // derived: quad columns of a tile
  localparam int QW = QCols > 1 ? $clog2(QCols) : 1;  // derived: a quad column's index
  localparam int RpBeats = (4 * QCols + Lanes - 1) / Lanes;  // derived: beats of a full row pair
  localparam int BeatDepth = RpBeats + 2;  // derived: the beat FIFO
  // derived: the order queue (Early): a tile's beats (QCols row pairs of RpBeats), the
  // ring's fragments and pend, to a power of two; never full behind the open fragment.
  localparam int OqDepth = 1 << $clog2(QCols * RpBeats + Depth + 4);
  localparam int CntW = TileLog2Max + 3;   // derived: covered fragments of a bank, 0 .. 2 TileMax
  localparam int DW = TexW + 1;            // derived: a derivative (difference of two coordinates)
  localparam int LevelsMax = SizeW;        // derived: levels of a 2^(SizeW-1) side
  localparam int OffW = 2 * SizeW + 2;     // derived: a level's offset from level 0, bytes
  localparam int LgW = $clog2(SizeW + 1);  // derived: log2 of a side

  // The per-draw texture state.
  typedef struct packed {
    logic                  bilinear, trilinear;
    logic [1:0]            wrap_s, wrap_t, env;
    logic [SizeW-1:0]      width, height;
    logic [AddrW-1:0]      base;
    logic [LevelW-1:0]     levels;
    logic [BiasW-1:0]      bias;
  } state_t;
  // A textured beat in the FIFO.
  typedef struct packed {
    logic                        last;
    logic [Lanes-1:0]            lanes;
    logic [Lanes*PixelW-1:0]     x, y;
    logic                        bank;   // its row pair's quad table bank
    logic [Lanes*DepthW-1:0]     z;
    state_t                      st;
    logic [Lanes*24-1:0]         rgb;
    logic [Lanes*TexW-1:0]       s, t;
    logic [Lanes*MaxSamples-1:0] smask;
    logic [Lanes-1:0]            cul;    // culled early (Early)
  } beat_t;
  // A fragment in flight.
  typedef struct packed {
    logic                  last;   // the tile's last covered fragment
    logic [PixelW-1:0]     x, y;
    logic [DepthW-1:0]     z;
    logic [23:0]           rgb;
    logic [TexW-1:0]       s, t;
    logic [MaxSamples-1:0] smask;
    logic                  bilinear, trilinear;
    logic [1:0]            wrap_s, wrap_t, env;
    logic [SizeW-1:0]      width, height;
    logic [AddrW-1:0]      base;
  } frag_t;
  // The serialiser's held fragment: with its quad's derivatives and its LOD inputs.
  typedef struct packed {
    frag_t                 f;
    logic [DW-1:0]         dsdx, dtdx, dsdy, dtdy;
    logic [LevelW-1:0]     levels;
    logic [BiasW-1:0]      bias;
  } pend_t;

  // ---- Tap: a textured beat into the FIFO, its lanes into the quad table ----
  logic             tex_in, new_rp, bank_in, tap_ok, accept, fifo_room, fifo_valid, fifo_empty, pop;
  logic             open_q, bank_q;          // a tile open at the tap; the bank of its row pair
  logic [PixelW-2:0] rp_q;                    // that row pair (y >> 1)
  logic [CntW-1:0]  cnt_q [2];               // kept fragments taken into a bank, not yet serialised
  logic [Lanes-1:0] cov_in, kept_in;         // covered lanes; those not culled early
  // The quad table, entry {bank, quad column}.
  logic [TexW-1:0]  tl_s_q [2*QCols], tl_t_q [2*QCols], tr_s_q [2*QCols], tr_t_q [2*QCols];
  logic [TexW-1:0]  bl_s_q [2*QCols], bl_t_q [2*QCols];
  logic [QCols-1:0] blv_q [2];               // the quad's bottom-left taken: its derivatives known
  beat_t            b_in, h;
  logic             pipe_empty;
  assign tex_in = in_valid_i && !in_marker_i && in_tex_on_i;
  assign new_rp = !open_q || in_y_i[1 +: PixelW-1] != rp_q;
  assign bank_in = new_rp ? !bank_q : bank_q;
  assign tap_ok = !new_rp || cnt_q[!bank_q] == '0;
  assign accept = tex_in && fifo_room && tap_ok;
  always_comb begin
    for (int j = 0; j < Lanes; j++) begin
      cov_in[j] = in_lanes_i[j] && in_smask_i[j*MaxSamples +: MaxSamples] != '0;
      kept_in[j] = cov_in[j] && !(Early != 0 && in_culled_i[j]);
    end
    helpers_o = '0;
    if (accept)
      for (int j = 0; j < Lanes; j++) helpers_o = helpers_o + HelpW'(in_lanes_i[j] && !cov_in[j]);
  end
  always_comb begin
    b_in.last = in_last_i;
    b_in.bank = bank_in;
    b_in.lanes = in_lanes_i;
    b_in.x = in_x_i;
    b_in.y = in_y_i;
    b_in.z = in_z_i;
    b_in.rgb = in_rgb_i;
    b_in.s = in_s_i;
    b_in.t = in_t_i;
    b_in.smask = in_smask_i;
    b_in.cul = Early != 0 ? in_culled_i : '0;
    b_in.st.bilinear = in_bilinear_i;
    b_in.st.trilinear = in_trilinear_i;
    b_in.st.wrap_s = in_wrap_s_i;
    b_in.st.wrap_t = in_wrap_t_i;
    b_in.st.env = in_env_i;
    b_in.st.width = in_width_i;
    b_in.st.height = in_height_i;
    b_in.st.base = in_base_i;
    b_in.st.levels = in_levels_i;
    b_in.st.bias = in_bias_i;
  end
  rast_fifo #(.Width($bits(b_in)), .Depth(BeatDepth)) u_beats (
    .clk_i, .rst_ni, .in_valid_i(accept), .in_ready_o(fifo_room), .in_data_i(b_in),
    .out_valid_o(fifo_valid), .out_ready_i(pop), .out_data_o(h), .empty_o(fifo_empty));

  // The serialiser's view of the head beat: rem, its kept (covered, not culled) lanes at
  // or after pos_q; c the first, more another after it. The culled lanes at or after
  // pos_q: before c (pre), after c when no kept lane follows (post), or all of them when
  // no kept lane is left (grp); each goes to the order queue with c's load or the beat's
  // pop (Early).
  logic             pend_valid_q, load, push, tail, pipe_accept;
  pend_t            pend_q, lane_pend;
  logic [Lanes-1:0] rem, pre, post, grp;
  logic [PosW-1:0]  pos_q;
  logic [LaneW-1:0] c;      // the next kept lane at or after pos_q
  logic             more;   // a kept lane after c
  logic [QW-1:0]    qc;     // c's quad column
  logic             ready_c;  // c's quad's derivatives known
  always_comb begin
    logic found;
    logic [Lanes-1:0] cov, cul;
    found = 1'b0;
    c = '0;
    more = 1'b0;
    for (int j = 0; j < Lanes; j++) begin
      cov[j] = h.lanes[j] && h.smask[j*MaxSamples +: MaxSamples] != '0 && PosW'(j) >= pos_q;
      cul[j] = cov[j] && h.cul[j];
      rem[j] = cov[j] && !h.cul[j];
      if (rem[j] && found) more = 1'b1;
      if (rem[j] && !found) begin
        found = 1'b1;
        c = LaneW'(j);
      end
    end
    for (int j = 0; j < Lanes; j++) begin
      pre[j] = cul[j] && found && LaneW'(j) < c;
      post[j] = cul[j] && found && !more && LaneW'(j) > c;
      grp[j] = cul[j] && !found;
    end
  end
  function automatic logic [QW-1:0] qcol(input logic [PixelW-1:0] x);
    qcol = QW'((x >> 1) & PixelW'(QCols - 1));
  endfunction
  assign qc = qcol(h.x[c*PixelW +: PixelW]);
  assign ready_c = blv_q[h.bank][qc];
  always_comb begin
    lane_pend.f.last      = !more && post == '0 && h.last;
    lane_pend.f.x         = h.x[c*PixelW +: PixelW];
    lane_pend.f.y         = h.y[c*PixelW +: PixelW];
    lane_pend.f.z         = h.z[c*DepthW +: DepthW];
    lane_pend.f.rgb       = h.rgb[c*24 +: 24];
    lane_pend.f.s         = h.s[c*TexW +: TexW];
    lane_pend.f.t         = h.t[c*TexW +: TexW];
    lane_pend.f.smask     = h.smask[c*MaxSamples +: MaxSamples];
    lane_pend.f.bilinear  = h.st.bilinear;
    lane_pend.f.trilinear = h.st.trilinear;
    lane_pend.f.wrap_s    = h.st.wrap_s;
    lane_pend.f.wrap_t    = h.st.wrap_t;
    lane_pend.f.env       = h.st.env;
    lane_pend.f.width     = h.st.width;
    lane_pend.f.height    = h.st.height;
    lane_pend.f.base      = h.st.base;
    lane_pend.levels      = h.st.levels;
    lane_pend.bias        = h.st.bias;
    lane_pend.dsdx = DW'($signed(tr_s_q[{h.bank, qc}])) - DW'($signed(tl_s_q[{h.bank, qc}]));
    lane_pend.dtdx = DW'($signed(tr_t_q[{h.bank, qc}])) - DW'($signed(tl_t_q[{h.bank, qc}]));
    lane_pend.dsdy = DW'($signed(bl_s_q[{h.bank, qc}])) - DW'($signed(tl_s_q[{h.bank, qc}]));
    lane_pend.dtdy = DW'($signed(bl_t_q[{h.bank, qc}])) - DW'($signed(tl_t_q[{h.bank, qc}]));
  end
  // load: a kept lane (its quad ready) into pend (pushing the one held), flagged last
  // when it is the tile's last output; push: pend into the LOD unit and the ring (a
  // flagged one at once; else with the next load, or now where the tile's last beat has no
  // kept lane left: flagged last unless culled lanes follow it). The order queue (Early)
  // takes an entry with each load and with the pop of a beat whose culled lanes are left
  // (grp); oq_room (1 without Early) holds both.
  logic oq_room, oq_open, pend_open, grp_ok;
  assign pend_open = pend_valid_q && !pend_q.f.last;
  assign grp_ok = grp == '0 || oq_room;
  assign tail = fifo_valid && rem == '0 && h.last && pend_open && grp_ok;
  assign load = fifo_valid && rem != '0 && ready_c && (!pend_valid_q || pipe_accept) && oq_room;
  assign push = pend_valid_q && pipe_accept && (load || pend_q.f.last || tail);
  assign pop  = fifo_valid && ((rem != '0 && !more && load) || (rem == '0 && !h.last && grp_ok) ||
                               (rem == '0 && h.last && grp_ok && (!pend_open || push)));

  // Tap and serialiser state.
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      open_q <= 1'b0;
      bank_q <= 1'b0;
      rp_q <= '0;
      cnt_q[0] <= '0;
      cnt_q[1] <= '0;
      blv_q[0] <= '0;
      blv_q[1] <= '0;
      pos_q <= '0;
      pend_valid_q <= 1'b0;
    end else begin
      if (accept) begin
        open_q <= !in_last_i;
        bank_q <= bank_in;
        rp_q <= in_y_i[1 +: PixelW-1];
        if (new_rp) blv_q[bank_in] <= '0;
        for (int j = 0; j < Lanes; j++)
          if (in_lanes_i[j] && in_y_i[j*PixelW] && !in_x_i[j*PixelW])
            blv_q[bank_in][qcol(in_x_i[j*PixelW +: PixelW])] <= 1'b1;
      end
      for (int b = 0; b < 2; b++) begin
        logic [CntW-1:0] n;
        n = cnt_q[b];
        if (accept && bank_in == 1'(b))
          for (int j = 0; j < Lanes; j++) n = n + CntW'(kept_in[j]);
        if (load && h.bank == 1'(b)) n = n - 1'b1;
        cnt_q[b] <= n;
      end
      if (pop) pos_q <= '0;
      else if (load) pos_q <= PosW'(c) + 1'b1;
      if (load) pend_valid_q <= 1'b1;
      else if (push) pend_valid_q <= 1'b0;
    end
  end
  always_ff @(posedge clk_i) begin
    if (accept)
      for (int j = 0; j < Lanes; j++)
        if (in_lanes_i[j]) begin
          if (!in_y_i[j*PixelW] && !in_x_i[j*PixelW]) begin
            tl_s_q[{bank_in, qcol(in_x_i[j*PixelW +: PixelW])}] <= in_s_i[j*TexW +: TexW];
            tl_t_q[{bank_in, qcol(in_x_i[j*PixelW +: PixelW])}] <= in_t_i[j*TexW +: TexW];
          end else if (!in_y_i[j*PixelW]) begin
            tr_s_q[{bank_in, qcol(in_x_i[j*PixelW +: PixelW])}] <= in_s_i[j*TexW +: TexW];
            tr_t_q[{bank_in, qcol(in_x_i[j*PixelW +: PixelW])}] <= in_t_i[j*TexW +: TexW];
          end else if (!in_x_i[j*PixelW]) begin
            bl_s_q[{bank_in, qcol(in_x_i[j*PixelW +: PixelW])}] <= in_s_i[j*TexW +: TexW];
            bl_t_q[{bank_in, qcol(in_x_i[j*PixelW +: PixelW])}] <= in_t_i[j*TexW +: TexW];
          end
        end
    if (load) pend_q <= lane_pend;
  end

  // ---- Level table: off[k], level k's byte offset from level 0 (off[0] = 0) ----
  logic [OffW-1:0]   off_q [LevelsMax];
  logic              tab_ok_q, fill_q, need_tab;
  logic [SizeW-1:0]  key_w_q, key_h_q, fw_q, fh_q;
  logic [LevelW-1:0] fk_q;
  logic [OffW-1:0]   acc_q, fp, fp_al;
  logic [PtrW:0]     unseq_q;  // fragments pushed, not yet through the level sequencer
  logic              seq_done;
  assign need_tab = pend_valid_q && pend_q.levels > LevelW'(1) &&
                    (!tab_ok_q || key_w_q != pend_q.f.width || key_h_q != pend_q.f.height);
  // The level's footprint (ref/texture/texture_unit.cpp level_footprint): linear W H, tiled
  // the 4 x 4 tiles' texels, morton the power-of-two square; times the texel's bytes.
  always_comb begin
    logic [SizeW-1:0] a, b, m;
    logic [LgW-1:0] lg;
    a = layout_i == 2'd1 ? (fw_q + SizeW'(3)) >> 2 : fw_q;
    b = layout_i == 2'd1 ? (fh_q + SizeW'(3)) >> 2 : fh_q;
    m = fw_q > fh_q ? fw_q : fh_q;
    lg = '0;
    for (int k = SizeW - 1; k >= 0; k--)
      if ((SizeW'(1) << k) >= m) lg = LgW'(k);  // ceil(log2 m)
    fp = layout_i == 2'd2 ? OffW'(1) << (2 * lg) : (OffW'(a) * OffW'(b)) << (layout_i == 2'd1 ? 4 : 0);
    fp = fp << (format_i == 2'd0 ? 2 : format_i == 2'd1 ? 1 : 0);
    fp_al = (fp + OffW'(255)) & ~OffW'(255);
  end
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      tab_ok_q <= 1'b0;
      fill_q <= 1'b0;
    end else if (fill_q) begin
      if ((fw_q == SizeW'(1) && fh_q == SizeW'(1)) || fk_q == LevelW'(LevelsMax - 2)) begin
        fill_q <= 1'b0;
        tab_ok_q <= 1'b1;
      end
    end else if (need_tab && unseq_q == '0) begin
      fill_q <= 1'b1;
    end
  end
  always_ff @(posedge clk_i) begin
    if (fill_q) begin
      off_q[fk_q + 1'b1] <= acc_q + fp_al;
      acc_q <= acc_q + fp_al;
      fw_q <= fw_q > SizeW'(1) ? fw_q >> 1 : fw_q;
      fh_q <= fh_q > SizeW'(1) ? fh_q >> 1 : fh_q;
      fk_q <= fk_q + 1'b1;
    end else if (need_tab && unseq_q == '0) begin
      key_w_q <= pend_q.f.width;
      key_h_q <= pend_q.f.height;
      fw_q <= pend_q.f.width;
      fh_q <= pend_q.f.height;
      fk_q <= '0;
      acc_q <= '0;
    end
  end
  wire unused_off0 = &{1'b0, off_q[0]};  // level 0's offset is 0, not read

  // ---- The ring of fragments in flight: written at push, read in order at the level
  // sequencer (seq), the request (req), the filter's input (flt), its output (cmb: the
  // combine's input) and the output (out); seq, req, flt and cmb step a level sample at
  // a time (sub: the second of a trilinear pair) ----
  frag_t           ring_q [Depth];
  logic            two_q [Depth];              // trilinear reads two levels
  logic [7:0]      frac_q [Depth];             // the second level's weight
  logic [7:0]      alpha_q [2*Depth], beta_q [2*Depth];  // the address unit's weights, by level sample
  logic [PtrW-1:0] wr_q, seq_q, req_q, flt_q, cmb_q, out_q;
  logic            seq_sub_q, req_sub_q, flt_sub_q, cmb_sub_q;
  frag_t           seq_e, req_e, flt_e, cmb_e, out_e;  // the entries at the read pointers
  logic            req_take, flt_take, fo_take, out_take, req_fin, flt_fin, cmb_fin, discard;
  logic            lod_in_ready, ring_full_q;
  logic [PtrW:0]   count;  // fragments in the ring
  assign seq_e = ring_q[seq_q];
  assign req_e = ring_q[req_q];
  assign flt_e = ring_q[flt_q];
  assign cmb_e = ring_q[cmb_q];
  assign out_e = ring_q[out_q];
  wire unused_e = &{1'b0, seq_e, req_e, flt_e, cmb_e, out_e};  // each pointer reads only some fields
  assign count = (PtrW + 1)'(PtrW'(wr_q - out_q)) + ((PtrW + 1)'(ring_full_q) << PtrW);
  assign pipe_accept = lod_in_ready && count != (PtrW + 1)'(Depth) && !fill_q && !need_tab;
  assign req_fin = req_sub_q || !two_q[req_q];
  assign flt_fin = flt_sub_q || !two_q[flt_q];
  assign cmb_fin = cmb_sub_q || !two_q[cmb_q];
  assign discard = two_q[cmb_q] && !cmb_sub_q;  // a trilinear pair's first level: chained, not combined
  frag_t pushed;
  always_comb begin
    pushed = pend_q.f;
    pushed.last = pend_q.f.last || (tail && grp == '0 && !oq_open);  // else a culled group ends the tile
  end
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      {wr_q, seq_q, req_q, flt_q, cmb_q, out_q} <= '0;
      {seq_sub_q, req_sub_q, flt_sub_q, cmb_sub_q} <= '0;
      ring_full_q <= 1'b0;
      unseq_q <= '0;
    end else begin
      if (push) wr_q <= wr_q + 1'b1;
      if (seq_done) seq_q <= seq_q + 1'b1;
      if (req_take) {req_q, req_sub_q} <= req_fin ? {req_q + 1'b1, 1'b0} : {req_q, 1'b1};
      if (flt_take) {flt_q, flt_sub_q} <= flt_fin ? {flt_q + 1'b1, 1'b0} : {flt_q, 1'b1};
      if (fo_take) {cmb_q, cmb_sub_q} <= cmb_fin ? {cmb_q + 1'b1, 1'b0} : {cmb_q, 1'b1};
      if (out_take) out_q <= out_q + 1'b1;
      if (push != out_take) ring_full_q <= push && PtrW'(wr_q + 1'b1) == out_q;
      unseq_q <= unseq_q + (PtrW + 1)'(push) - (PtrW + 1)'(seq_done);
    end
  end
  always_ff @(posedge clk_i) begin
    if (push) ring_q[wr_q] <= pushed;
  end

  // ---- Level of detail (the quad's, for each of its fragments) ----
  logic              lod_valid;
  logic [LevelW-1:0] lod_level0, lod_level1;
  logic [7:0]        lod_frac;
  rast_texture_lod #(.TexW(TexW), .TexFrac(TexFrac), .SizeW(SizeW), .LevelW(LevelW), .BiasW(BiasW)) u_lod (
    .clk_i, .rst_ni, .in_valid_i(push), .in_ready_o(lod_in_ready), .dsdx_i(pend_q.dsdx), .dtdx_i(pend_q.dtdx),
    .dsdy_i(pend_q.dsdy), .dtdy_i(pend_q.dtdy), .width_i(pend_q.f.width), .height_i(pend_q.f.height),
    .levels_i(pend_q.levels), .bias_i(pend_q.bias), .trilinear_i(pend_q.f.trilinear), .out_valid_o(lod_valid),
    .out_ready_i(seq_done), .level0_o(lod_level0), .level1_o(lod_level1), .frac_o(lod_frac));

  // ---- Level sequencer: a level sample a cycle into the address unit ----
  logic              addr_in_ready, addr_take, two;
  logic [LevelW-1:0] lvl;
  logic [SizeW-1:0]  lvl_w, lvl_h;
  logic [AddrW-1:0]  lvl_base;
  assign two = lod_level1 != lod_level0;
  assign lvl = seq_sub_q ? lod_level1 : lod_level0;
  always_comb begin
    lvl_w = seq_e.width >> lvl;
    lvl_h = seq_e.height >> lvl;
    if (lvl_w == '0) lvl_w = SizeW'(1);
    if (lvl_h == '0) lvl_h = SizeW'(1);
    lvl_base = lvl == '0 ? seq_e.base : seq_e.base + AddrW'(off_q[lvl]);
  end
  // A fragment takes a slot a level it reads: level k, then for trilinear level k + 1
  // where its weight is not 0 (TextureStats::level_samples, the SystemC stage's term B).
  assign addr_take = lod_valid && addr_in_ready;
  assign seq_done = addr_take && (seq_sub_q || !two);
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) seq_sub_q <= 1'b0;
    else if (addr_take) seq_sub_q <= !seq_done;
  end
  always_ff @(posedge clk_i) begin
    if (addr_take && !seq_sub_q) begin
      two_q[seq_q] <= two;
      frac_q[seq_q] <= lod_frac;
    end
  end

  // ---- Address ----
  logic                   addr_valid;
  logic [4*(SizeW-1)-1:0] addr_i, addr_j;
  logic [7:0]             addr_alpha, addr_beta;
  rast_texture_address #(.TexW(TexW), .TexFrac(TexFrac), .WeightBits(WeightBits), .SizeW(SizeW), .AddrW(AddrW)) u_address (
    .clk_i, .rst_ni, .in_valid_i(lod_valid), .in_ready_o(addr_in_ready), .s_i(seq_e.s), .t_i(seq_e.t),
    .width_i(lvl_w), .height_i(lvl_h), .bilinear_i(seq_e.bilinear || seq_e.trilinear), .wrap_s_i(seq_e.wrap_s),
    .wrap_t_i(seq_e.wrap_t), .layout_i, .format_i, .base_i(lvl_base), .out_valid_o(addr_valid),
    .out_ready_i(tex_req_ready_i), .i_o(addr_i), .j_o(addr_j), .alpha_o(addr_alpha), .beta_o(addr_beta),
    .addr_o(tex_req_addr_o));
  wire unused_ij = &{1'b0, addr_i, addr_j};  // the texels' indices: the testbench's view only
  assign tex_req_valid_o = addr_valid;
  assign tex_req_count_o = (req_e.bilinear || req_e.trilinear) ? 3'd4 : 3'd1;
  assign tex_req_format_o = format_i;
  assign req_take = addr_valid && tex_req_ready_i;
  always_ff @(posedge clk_i) begin
    if (req_take) begin
      alpha_q[{req_q, req_sub_q}] <= addr_alpha;
      beta_q[{req_q, req_sub_q}] <= addr_beta;
    end
  end

  // ---- Filter (a trilinear pair's second level chained to the first's output) ----
  logic        flt_in_ready, flt_valid, cmb_in_ready;
  logic [31:0] flt_color;
  rast_texture_filter u_filter (
    .clk_i, .rst_ni, .in_valid_i(tex_rsp_valid_i), .in_ready_o(flt_in_ready), .texels_i(tex_rsp_texels_i),
    .alpha_i(alpha_q[{flt_q, flt_sub_q}]), .beta_i(beta_q[{flt_q, flt_sub_q}]),
    .bilinear_i(flt_e.bilinear || flt_e.trilinear), .blend_i(flt_sub_q), .prev_i('0), .chain_i(flt_sub_q),
    .frac_i(frac_q[flt_q]), .out_valid_o(flt_valid), .out_ready_i(discard || cmb_in_ready), .color_o(flt_color));
  assign tex_rsp_ready_o = flt_in_ready;
  assign flt_take = tex_rsp_valid_i && flt_in_ready;
  assign fo_take = flt_valid && (discard || cmb_in_ready);

  // ---- Combine ----
  // The order queue's head (below): the combine's output leaves with its entry.
  typedef struct packed {
    logic [Lanes-1:0]            pre, post;  // culled lanes before and after the kept one
    logic [Lanes-1:0]            kl;         // the kept lane (one-hot; 0: culled lanes alone)
    logic                        last;       // post ends the tile
    logic [Lanes*PixelW-1:0]     x, y;
    logic [Lanes*DepthW-1:0]     z;
    logic [Lanes*24-1:0]         rgb;
    logic [Lanes*TexW-1:0]       s, t;
    logic [Lanes*MaxSamples-1:0] smask;
  } oq_t;
  oq_t  oq_h;     // the head entry
  // The entry loaded this cycle. Here, not in g_order: Yosys 0.23 cannot resolve the members
  // of a struct declared in a generate block (`rastsim area` with depth.early failed on it).
  oq_t  oq_in;
  logic oq_valid, oq_final, oq_go, oq_empty, k_ready;
  logic        cmb_valid;
  logic [23:0] cmb_color;
  rast_texture_combine u_combine (
    .clk_i, .rst_ni, .in_valid_i(flt_valid && !discard), .in_ready_o(cmb_in_ready), .tex_i(flt_color),
    .color_i(cmb_e.rgb), .env_i(cmb_e.env), .out_valid_o(cmb_valid), .out_ready_i(out_ready_i && k_ready),
    .color_o(cmb_color));
  assign out_take = cmb_valid && out_ready_i && k_ready;

  // ---- Order queue (Early): an entry a kept fragment loaded (with the culled lanes of its
  // beat before it, pre, and, where no kept lane follows in the beat, after it, post) or a
  // beat popped with culled lanes and no kept one (post alone), in the serialiser's order,
  // which is the reference's. The head leaves as one beat, its lanes in their places: the
  // culled ones as interpolated, the kept one with the combine's colour, so a culled lane
  // costs no output cycle of its own (the SystemC stage's culled fragments cost none). An
  // entry with post waits until it is known not to end its tile unflagged (oq_final: it
  // carries last, or another entry follows it; the tile's last beat flags the newest entry,
  // still queued, where no culled lane of that beat and no open fragment takes the flag).
  // Without Early every head is a kept fragment: the ring's order alone. ----
  if (Early != 0) begin : g_order
    localparam int OqPtrW = $clog2(OqDepth);  // derived
    oq_t               oq_q [OqDepth];
    logic [OqPtrW-1:0] oq_rd_q, oq_wr_q;
    logic [OqPtrW:0]   oq_count_q;
    logic              oq_push, oq_flag, oq_take, open_q2;
    logic [OqDepth-1:0] oq_last_q;  // each entry's last flag, apart from oq_q: oq_flag sets it late
    assign oq_push = load || (pop && rem == '0 && grp != '0);
    // The tile's last beat popped with nothing of its own to flag: the newest entry's post.
    assign oq_flag = pop && rem == '0 && h.last && grp == '0 && open_q2;
    always_comb begin
      oq_in.pre = load ? pre : '0;
      oq_in.post = load ? post : grp;
      oq_in.kl = load ? Lanes'(1) << c : '0;
      oq_in.last = h.last && (load ? !more && post != '0 : 1'b1);
      oq_in.x = h.x;
      oq_in.y = h.y;
      oq_in.z = h.z;
      oq_in.rgb = h.rgb;
      oq_in.s = h.s;
      oq_in.t = h.t;
      oq_in.smask = h.smask;
    end
    assign oq_room = oq_count_q != (OqPtrW + 1)'(OqDepth);
    assign oq_valid = oq_count_q != '0;
    assign oq_empty = !oq_valid;
    always_comb begin
      oq_h = oq_q[oq_rd_q];
      oq_h.last = oq_last_q[oq_rd_q];
    end
    assign oq_final = oq_h.last || oq_count_q > (OqPtrW + 1)'(1);
    assign oq_go = oq_valid && (oq_h.post == '0 || oq_final);  // the head may leave (with its fragment)
    assign k_ready = oq_go && oq_h.kl != '0;
    assign oq_take = oq_valid && out_valid_o && out_ready_i;  // the head's beat taken (not a pass-through)
    assign oq_open = open_q2;
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        oq_rd_q <= '0;
        oq_wr_q <= '0;
        oq_count_q <= '0;
        open_q2 <= 1'b0;
      end else begin
        if (oq_push) oq_wr_q <= oq_wr_q + 1'b1;
        if (oq_take) oq_rd_q <= oq_rd_q + 1'b1;
        oq_count_q <= oq_count_q + (OqPtrW + 1)'(oq_push) - (OqPtrW + 1)'(oq_take);
        // The newest entry's post is open: it may end its tile, not yet flagged.
        if (oq_push) open_q2 <= oq_in.post != '0 && !oq_in.last;
        else if (oq_flag || (pop && h.last)) open_q2 <= 1'b0;
      end
    end
    always_ff @(posedge clk_i) begin
      if (oq_push) oq_q[oq_wr_q] <= oq_in;
      if (oq_push) oq_last_q[oq_wr_q] <= oq_in.last;
      if (oq_flag) oq_last_q[oq_wr_q - 1'b1] <= 1'b1;
    end
  end else begin : g_no_order
    assign oq_room = 1'b1;
    assign oq_open = 1'b0;
    assign oq_valid = 1'b0;
    assign oq_empty = 1'b1;
    assign oq_final = 1'b1;
    assign oq_go = 1'b0;
    assign k_ready = 1'b1;
    assign oq_h = '0;
    assign oq_in = '0;
    wire unused_order = &{1'b0, pre, post, oq_h, oq_in, oq_final, oq_go};
  end

  // ---- Out: a textured fragment on lane 0, an order queue entry's beat (Early), or the
  // beat passed through ----
  logic pass;
  assign pipe_empty = fifo_empty && !pend_valid_q && count == '0 && !fill_q && oq_empty;
  assign pass = in_valid_i && (in_marker_i || !in_tex_on_i) && pipe_empty;
  assign in_ready_o = accept || (pass && out_ready_i);
  always_comb begin
    out_culled_o = '0;
    if (Early != 0 && oq_valid) begin
      out_valid_o  = oq_go && (oq_h.kl == '0 || cmb_valid);
      out_marker_o = 1'b0;
      out_last_o   = oq_h.post != '0 ? oq_h.last : out_e.last;
      out_lanes_o  = oq_h.pre | oq_h.kl | oq_h.post;
      out_culled_o = oq_h.pre | oq_h.post;
      out_x_o      = oq_h.x;
      out_y_o      = oq_h.y;
      out_z_o      = oq_h.z;
      out_rgb_o    = oq_h.rgb;
      for (int j = 0; j < Lanes; j++)
        if (oq_h.kl[j]) out_rgb_o[j*24 +: 24] = cmb_color;
      out_s_o      = oq_h.s;
      out_t_o      = oq_h.t;
      out_smask_o  = oq_h.smask;
    end else if (cmb_valid) begin
      out_valid_o  = 1'b1;
      out_marker_o = 1'b0;
      out_last_o   = out_e.last;
      out_lanes_o  = Lanes'(1);
      out_x_o      = (Lanes*PixelW)'(out_e.x);
      out_y_o      = (Lanes*PixelW)'(out_e.y);
      out_z_o      = (Lanes*DepthW)'(out_e.z);
      out_rgb_o    = (Lanes*24)'(cmb_color);
      out_s_o      = (Lanes*TexW)'(out_e.s);
      out_t_o      = (Lanes*TexW)'(out_e.t);
      out_smask_o  = (Lanes*MaxSamples)'(out_e.smask);
    end else begin
      out_valid_o  = pass;
      out_culled_o = Early != 0 ? in_culled_i : '0;
      out_marker_o = in_marker_i;
      out_last_o   = in_last_i;
      out_lanes_o  = in_lanes_i;
      out_x_o      = in_x_i;
      out_y_o      = in_y_i;
      out_z_o      = in_z_i;
      out_rgb_o    = in_rgb_i;
      out_s_o      = in_s_i;
      out_t_o      = in_t_i;
      out_smask_o  = in_smask_i;
    end
  end
  assign busy_o = !pipe_empty;
endmodule

`default_nettype wire
