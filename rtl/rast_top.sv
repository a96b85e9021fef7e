// SPDX-License-Identifier: Apache-2.0
// rast_top: the raster pipeline from snapped triangles to shaded fragments.
//
//   triangle FIFO -> rast_tri_setup -> setup FIFO (latency) -> rast_coarse_raster
//     -> tile FIFO -> rast_fine_raster -> pixel FIFO -> rast_interpolate
//     -> [rast_early_z: depth.early] -> rast_texture_stage (textured tiles) -> fragment FIFO
//        | texel fetch port -> rast_texture_cache -> line fill port (tex_mem_*)
//     -> rast_rop -> memory request/response port
//
//   Each FIFO is followed by a rast_hold: a stage pops its transaction in the first
//   cycle it works on it (the FIFO slot frees at once, as in the SystemC model).
//
// - Every parameter comes from the config through the exported header rast_params.vh
//   (`rastsim export-rtl`, model/rtlsim/rtl_params.cpp): widths of docs/fixed-point.md,
//   the timing keys and FIFO depths. The same stages, FIFOs and timing equations as the
//   SystemC model (docs/microarchitecture.md, docs/rtl.md).
// - The raster state is run-time input, held constant while the pipeline is busy: the
//   tile size 2^tile_log2_i with 1 <= tile_log2_i <= TileLog2Max; fill rule, cull mode
//   and front face (encoded as model/ref/raster_state.h's enums, see rast_tri_setup);
//   the perspective datapath (interp.perspective, the newton reciprocal's seed bits and
//   steps, recip.lanes) is built from parameters.
//   multisampling: 2^samples_log2_i samples a pixel (1 .. MaxSamples) at the offsets
//   sample_dx_i / sample_dy_i from the pixel centre (raw s.I.F, signed SampleOffW bits;
//   sample 0's offset is 0 with one sample), whose bounding box widens setup's box and
//   moves the coarse raster's corners; fragments carry their pixel's sample mask.
// - Triangles arrive snapped (s.I.F raw, relative to the origin), with the clip
//   rectangle and origin of the state they were drawn in, their vertices' depth, colour,
//   texture coordinates (interp.texcoord_format) and perspective weights Q_k, and the
//   affine flag of ref tri_setup (the testbench's front end divides clip space by w); a marker (a state command in
//   order with the triangles) travels through every stage and leaves as a marker beat.
// - Fragments leave the interpolator FragmentsPerCycle lanes a beat, a tile's last beat
//   flagged (frag_*_o: observation of the beats the fragment FIFO takes), into the
//   fragment FIFO and the ROP (rast_rop: depth test, colour and depth write, clears), whose
//   memory port (rd_*, wr_*) and command port (cmd_*: one command a marker, in stream
//   order) are rast_top's. The fragment FIFO holds FragmentFifoEntries whole tiles (the
//   SystemC model's fragment FIFO of batches, TimingParams::fragment_fifo_entries): the
//   ROP starts a tile once its last beat is in (the model's ROP reads whole batches). An
//   untextured tile or a marker enters the interpolator only while at most
//   FragmentFifoEntries tiles are between its input and the ROP's start of them (credits,
//   the pipeline's beats and the ROP's access buffer included: the model's interpolator
//   blocked in its write), and a textured tile enters the texture stage only while at
//   most FragmentFifoEntries tiles are between the stage's input and the ROP's start (the
//   model's texture stage blocked in its write).
`default_nettype none

module rast_top #(
`include "rast_params.vh"
) (
  input  wire logic                                  clk_i,           // core clock
  input  wire logic                                  rst_ni,          // asynchronous reset, active low
  input  wire logic [TileLog2W-1:0]                  tile_log2_i,     // log2 tile size (static)
  input  wire logic [1:0]                            fill_rule_i,     // raster.fill_rule (static)
  input  wire logic [1:0]                            cull_mode_i,     // raster.cull (static)
  input  wire logic                                  front_ccw_i,     // raster.front_face = ccw (static)
  input  wire logic [SampleLog2W-1:0]                samples_log2_i,  // log2 raster.samples, 0 .. log2 MaxSamples (static)
  input  wire logic [MaxSamples*SampleOffW-1:0]      sample_dx_i,     // sample s x offset, raw, at [s*SampleOffW +: SampleOffW] (static)
  input  wire logic [MaxSamples*SampleOffW-1:0]      sample_dy_i,     // sample s y offset, raw (static)
  input  wire logic                                  tri_valid_i,     // a triangle or marker
  output      logic                                  tri_ready_o,     // taken (triangle FIFO not full)
  input  wire logic                                  tri_marker_i,    // a marker
  input  wire logic [CoordW-1:0]                     tri_x0_i,        // vertex 0 x, raw s.I.F
  input  wire logic [CoordW-1:0]                     tri_y0_i,        // vertex 0 y
  input  wire logic [CoordW-1:0]                     tri_x1_i,        // vertex 1 x
  input  wire logic [CoordW-1:0]                     tri_y1_i,        // vertex 1 y
  input  wire logic [CoordW-1:0]                     tri_x2_i,        // vertex 2 x
  input  wire logic [CoordW-1:0]                     tri_y2_i,        // vertex 2 y
  input  wire logic [DepthW-1:0]                     tri_z0_i,        // vertex 0 depth, unorm
  input  wire logic [DepthW-1:0]                     tri_z1_i,        // vertex 1 depth
  input  wire logic [DepthW-1:0]                     tri_z2_i,        // vertex 2 depth
  input  wire logic [3*(8+ColorFrac)-1:0]            tri_rgb0_i,      // vertex 0 colour {b, g, r}, unsigned 8.ColorFrac a channel
  input  wire logic [3*(8+ColorFrac)-1:0]            tri_rgb1_i,      // vertex 1 colour
  input  wire logic [3*(8+ColorFrac)-1:0]            tri_rgb2_i,      // vertex 2 colour
  input  wire logic [3*TexW-1:0]                     tri_s_i,         // vertex k texture coordinate s at [k*TexW +: TexW], raw signed
  input  wire logic [3*TexW-1:0]                     tri_t_i,         // vertex k t
  input  wire logic [3*24-1:0]                       tri_q_i,         // vertex k perspective weight Q_k at [k*24 +: 24] (docs/clip-space.md)
  input  wire logic                                  tri_affine_i,    // interpolation needs no reciprocal (ref tri_setup's affine)
  // The triangle's texture state (docs/texture.md "RTL"; rast_texture_stage's in_*).
  input  wire logic                                  tri_tex_on_i,       // a texture bound: quads, the texture stage
  input  wire logic                                  tri_tex_bilinear_i, // texfilter bilinear (else nearest, or trilinear)
  input  wire logic                                  tri_tex_trilinear_i,// texfilter trilinear (bilinear on each level)
  input  wire logic [1:0]                            tri_tex_wrap_s_i,   // texwrap s: 0 repeat, 1 clamp, 2 mirror
  input  wire logic [1:0]                            tri_tex_wrap_t_i,   // texwrap t
  input  wire logic [1:0]                            tri_tex_env_i,      // texenv: 0 replace, 1 modulate, 2 decal
  input  wire logic [TexSizeW-1:0]                   tri_tex_width_i,    // level 0 width, texels
  input  wire logic [TexSizeW-1:0]                   tri_tex_height_i,   // level 0 height, texels
  input  wire logic [TexAddrW-1:0]                   tri_tex_base_i,     // level 0 byte address
  input  wire logic [TexLevelW-1:0]                  tri_tex_levels_i,   // levels sampled: the chain's (mipmap on), else 1
  input  wire logic [TexBiasW-1:0]                   tri_tex_bias_i,     // texlod_bias in s.8, signed
  input  wire logic [PixelW-1:0]                     tri_clip_x0_i,   // clip rect, half-open px
  input  wire logic [PixelW-1:0]                     tri_clip_y0_i,   //
  input  wire logic [PixelW-1:0]                     tri_clip_x1_i,   //
  input  wire logic [PixelW-1:0]                     tri_clip_y1_i,   //
  input  wire logic [PixelW-1:0]                     tri_origin_x_i,  // pixel of raw x = 0
  input  wire logic [PixelW-1:0]                     tri_origin_y_i,  // pixel of raw y = 0
  input  wire logic [PixelW-1:0]                     fb_width_i,      // framebuffer width, px (static)
  input  wire logic [PixelW-1:0]                     fb_height_i,     // framebuffer height, px (static)
  input  wire logic [31:0]                           color_base_i,    // colour surface, byte address (static)
  input  wire logic [31:0]                           depth_base_i,    // depth surface, byte address (static)
  input  wire logic [2:0]                            depth_func_i,    // raster.depth_func as ref DepthFunc (static)
  input  wire logic                                  depth_write_i,   // raster.depth_write (static)
  input  wire logic [1:0]                            tex_format_i,    // texture.format: 0 rgba8888, 1 rgb565, 2 l8 (static)
  input  wire logic [1:0]                            tex_layout_i,    // texture.layout: 0 linear, 1 tiled, 2 morton (static)
  // The texture cache's memory port (rast_texture_cache's mem_*; docs/texture.md "RTL"):
  // one line fill at a time, the line's TexLineBytes / TexBeatBytes beats in order.
  output      logic                                  tex_mem_req_valid_o,
  input  wire logic                                  tex_mem_req_ready_i,
  output      logic [TexAddrW-1:0]                   tex_mem_req_addr_o,  // the line's byte address (TexLineBytes bytes)
  input  wire logic                                  tex_mem_rsp_valid_i, // a beat of the line
  output      logic                                  tex_mem_rsp_ready_o,
  input  wire logic [127:0]                          tex_mem_rsp_data_i,  // the beat's byte i at [8i +: 8], i < TexBeatBytes
  output      logic [2:0]                            tex_hits_o,          // texture cache hits this cycle
  output      logic                                  tex_miss_o,          // a texture cache miss this cycle
  output      logic [$clog2(InterpFragmentsPerCycle+1)-1:0] tex_helpers_o,  // helper pixels dropped this cycle
  output      logic                                  dbg_tex_busy_o,    // the texture stage holds textured work
  output      logic                                  dbg_tex_blocked_o, // its output is refused (the fragment FIFO), or its input held for a credit
  output      logic                                  frag_valid_o,    // a fragment beat or marker
  output      logic                                  frag_ready_o,    // taken by the fragment FIFO
  output      logic                                  frag_marker_o,   // the beat is a marker
  output      logic                                  frag_last_o,     // last beat of a tile
  output      logic [InterpFragmentsPerCycle-1:0]    frag_lanes_o,    // lanes holding a fragment
  output      logic [InterpFragmentsPerCycle*PixelW-1:0] frag_x_o,    // lane j x
  output      logic [InterpFragmentsPerCycle*PixelW-1:0] frag_y_o,    // lane j y
  output      logic [InterpFragmentsPerCycle*DepthW-1:0] frag_z_o,    // lane j depth
  output      logic [InterpFragmentsPerCycle*24-1:0]     frag_rgb_o,  // lane j colour {b, g, r}
  output      logic [InterpFragmentsPerCycle*TexW-1:0]   frag_s_o,    // lane j texture coordinate s, raw signed
  output      logic [InterpFragmentsPerCycle*TexW-1:0]   frag_t_o,    // lane j t
  output      logic [InterpFragmentsPerCycle*MaxSamples-1:0] frag_mask_o,  // lane j sample mask (bit s: sample s)
  // Early Z (DepthEarly; rtl/rast_early_z.sv): lane j of the beat culled early (still sent
  // to the ROP for its depth reads, never textured), and the early test's depth read on the
  // interpolator's beat into the texture stage: the lanes whose pixels (ez_rd_x_o,
  // ez_rd_y_o) are read, every sample's stored depth back in the same cycle (lane j sample
  // s at [(j MaxSamples + s) DepthW +: DepthW]). 0 without.
  output      logic [InterpFragmentsPerCycle-1:0]    frag_culled_o,
  output      logic [InterpFragmentsPerCycle-1:0]    ez_rd_lanes_o,
  output      logic [InterpFragmentsPerCycle*PixelW-1:0] ez_rd_x_o,   // lane j x
  output      logic [InterpFragmentsPerCycle*PixelW-1:0] ez_rd_y_o,   // lane j y
  input  wire logic [InterpFragmentsPerCycle*MaxSamples*DepthW-1:0] ez_rd_depth_i,
  // The ROP's commands, one a marker in stream order (rast_rop's cmd_*).
  input  wire logic                                  cmd_valid_i,     // a command
  output      logic                                  cmd_ready_o,     // taken with its marker (high while a marker waits for it)
  input  wire logic [2:0]                            cmd_op_i,        // 0 pass, 1 clear colour, 2 clear depth; binned: 4 begin bin, 5 end bin
  input  wire logic [31:0]                           cmd_value_i,     // clear word: colour {a, b, g, r}, or depth; bin: bit 0 colour, bit 1 depth loaded / stored
  input  wire logic [4*PixelW-1:0]                   cmd_bin_i,       // bin commands: the bin {y1, x1, y0, x0}, half-open px
  // The ROP's memory port (rast_rop's rd_*, wr_*; docs/rtl.md "ROP").
  output      logic                                  rd_valid_o,
  input  wire logic                                  rd_ready_i,
  output      logic [RopPixelsPerCycle-1:0]          rd_lanes_o,
  output      logic [RopPixelsPerCycle*32-1:0]       rd_addr_o,
  output      logic [RopPixelsPerCycle*RopLenW-1:0]  rd_len_o,
  output      logic                                  rd_no_depth_o,   // the group reads no depth (Hi-Z accepted tile)
  input  wire logic                                  rd_rvalid_i,
  input  wire logic [RopPixelsPerCycle*MaxSamples*32-1:0] rd_rdata_i,
  output      logic                                  wr_valid_o,
  input  wire logic                                  wr_ready_i,
  output      logic [2*RopPixelsPerCycle-1:0]        wr_lanes_o,
  output      logic [2*RopPixelsPerCycle*32-1:0]     wr_addr_o,
  output      logic [2*RopPixelsPerCycle*RopLenW-1:0] wr_len_o,
  output      logic                                  wr_fill_o,
  output      logic [2*RopPixelsPerCycle*MaxSamples*4-1:0] wr_be_o,
  output      logic [2*RopPixelsPerCycle*32-1:0]     wr_data_o,
  // Binned mode (TileBufferSamples > 0): the tile buffer's memory port (rast_tile_buffer's
  // tl_*: a bin's loads and stores; the ROP's rd_* / wr_* above stay low).
  output      logic                                  tl_valid_o,
  input  wire logic                                  tl_ready_i,
  output      logic                                  tl_write_o,
  output      logic [31:0]                           tl_addr_o,
  output      logic [$clog2(TilePortWords+1)-1:0]    tl_count_o,
  output      logic [TilePortWords*32-1:0]           tl_wdata_o,
  input  wire logic                                  tl_rvalid_i,
  input  wire logic [TilePortWords*32-1:0]           tl_rdata_i,
  output      logic                                  idle_o,          // no work anywhere: pipeline, fragment FIFO and ROP drained
  // Stage handshake observation for the co-simulation's per-stage statistics (bit s:
  // 0 setup, 1 coarse raster, 2 fine raster, 3 interpolation, 4 ROP;
  // docs/microarchitecture.md "Stage statistics"). Wires of existing handshakes only: no
  // state, a few gates.
  output      logic [4:0]                            dbg_has_o,       // stage s holds a transaction (the ROP: works this cycle)
  output      logic [4:0]                            dbg_done_o,      // stage s finishes its transaction this cycle
  output      logic [4:0]                            dbg_blocked_o,   // stage s offers an output that is not taken
  output      logic                                  dbg_rop_start_o, // the ROP starts a batch or command (rast_rop's dbg_start_o)
  // Hi-Z (HizMode != 0; docs/depth-culling.md "RTL"): tiles coarse raster culled this
  // cycle, and a tile it sent accepted (tiles_culled_hiz, tiles_accepted_hiz). 0 without.
  output      logic [$clog2(CoarseTilesPerCycle+1)-1:0] dbg_hiz_culled_o,
  output      logic                                  dbg_hiz_accepted_o,
  // Hi-Z's spilled entries (HizSpillBlocks > 0; rast_hiz_spill): the memory port the
  // testbench serves as client `hiz`, requests in order, read responses in order, an
  // entry (2^HizEntryBytesLog2 bytes) in the low bits of the 512. Tied off without.
  input  wire logic [39:0]                           hiz_base_i,           // depth.hiz_base (static)
  output      logic                                  hiz_mem_req_valid_o,
  input  wire logic                                  hiz_mem_req_ready_i,
  output      logic                                  hiz_mem_req_write_o,  // a write-back
  output      logic                                  hiz_mem_req_flush_o,  // a flush's read (else a test's)
  output      logic [39:0]                           hiz_mem_req_addr_o,   // the entry's byte address
  output      logic [511:0]                          hiz_mem_req_data_o,
  input  wire logic                                  hiz_mem_rsp_valid_i,
  input  wire logic [511:0]                          hiz_mem_rsp_data_i,
  output      logic                                  dbg_hiz_error_o       // its write FIFO overflowed
);
  localparam int MaskW = 1 << (2 * TileLog2Max);      // derived: coverage mask bits
  localparam int SMaskW = MaskW * MaxSamples;         // derived: sample mask bits of a tile
  localparam int ColorW = 8 + ColorFrac;              // derived: a vertex colour channel, unsigned 8.ColorFrac
  localparam int Lanes = InterpFragmentsPerCycle;     // derived: fragment lanes a beat
  // derived: beats of the largest tile at the fewest lanes a beat (a perspective beat
  // fills InterpPerspLanes), and the fragment FIFO's beats: FragmentFifoEntries tiles
  // waiting, one more complete tile held back, one being written, one being read.
  localparam int TileBeats = ((1 << (2 * TileLog2Max)) + (InterpPerspective != 0 ? InterpPerspLanes : Lanes) - 1) /
                             (InterpPerspective != 0 ? InterpPerspLanes : Lanes);
  localparam int FragBeats = (FragmentFifoEntries + 3) * TileBeats;
  localparam int BatchW = $clog2(FragmentFifoEntries + 2);  // derived: complete tiles waiting, 0 .. Entries + 1

  // ---- Transaction bundles: what each FIFO holds, one field a line. A FIFO's width is
  // derived from its bundle ($bits of a signal of its type: Yosys 0.23 takes $bits of a
  // signal, not of a type). Per-vertex and per-edge fields are {2, 1, 0}.
  // A triangle's texture state (rast_texture_stage's in_tex_*), with its tiles to the
  // texture stage.
  typedef struct packed {
    logic                on;
    logic                bilinear;
    logic                trilinear;
    logic [1:0]          wrap_s;
    logic [1:0]          wrap_t;
    logic [1:0]          env;
    logic [TexSizeW-1:0] width;
    logic [TexSizeW-1:0] height;
    logic [TexAddrW-1:0] base;
    logic [TexLevelW-1:0] levels;
    logic [TexBiasW-1:0] bias;
  } tex_t;
  typedef struct packed {
    logic [3*DepthW-1:0] z;       // depth, unorm
    logic [9*ColorW-1:0] rgb;     // colour {b, g, r} a vertex, ColorW bits a channel
    logic [3*TexW-1:0]   s;       // texture coordinate, raw signed
    logic [3*TexW-1:0]   t;
    logic [3*24-1:0]     q;       // perspective weights Q_k
    logic                affine;  // no reciprocal needed
    tex_t                tex;     // the texture state
  } attr_t;
  // A set-up triangle's edge functions E(x, y) = a x + b y + c (rast_tri_setup).
  typedef struct packed {
    logic [3*CoefW-1:0] a;     // signed
    logic [3*CoefW-1:0] b;     // signed
    logic [3*EdgeW-1:0] c;     // signed
    logic [2:0]         bias;  // fill-rule bias of each edge
  } edges_t;
  // Triangle FIFO: a snapped triangle (or marker) with the state it was drawn in.
  typedef struct packed {
    logic                marker;
    logic [3*CoordW-1:0] x;       // raw s.I.F
    logic [3*CoordW-1:0] y;
    logic [4*PixelW-1:0] clip;    // {y1, x1, y0, x0}, half-open px
    logic [2*PixelW-1:0] origin;  // {y, x}: pixel of raw 0
    attr_t               attr;
  } tri_t;
  // Setup FIFO: a set-up triangle.
  typedef struct packed {
    logic                marker;
    edges_t              edges;
    logic [4*PixelW-1:0] bbox;    // {y1, x1, y0, x0}
    logic [2*PixelW-1:0] origin;
    logic [AreaW-1:0]    area2;
    attr_t               attr;
  } set_t;
  // Tile FIFO: one tile of a triangle.
  typedef struct packed {
    logic                marker;
    logic                accepted;  // wholly covered: fine raster tests no sample
    logic [4*PixelW-1:0] fp;        // footprint {y1, x1, y0, x0}
    edges_t              edges;
    logic [2*PixelW-1:0] origin;
    logic [AreaW-1:0]    area2;
    attr_t               attr;
  } tile_t;
  // Pixel FIFO: one tile's coverage; interpolation needs the edges but not their bias.
  // Fragment FIFO: one beat of the interpolator, what the ROP reads.
  typedef struct packed {
    logic                            marker;
    logic                            last;   // a tile's last beat
    logic [Lanes-1:0]                lanes;
    logic [Lanes*PixelW-1:0]         x;
    logic [Lanes*PixelW-1:0]         y;
    logic [Lanes*DepthW-1:0]         z;
    logic [Lanes*24-1:0]             rgb;    // {b, g, r}
    logic [Lanes*MaxSamples-1:0]     mask;
  } beat_t;
  typedef struct packed {
    logic                marker;
    logic [MaskW-1:0]    mask;    // covered pixels
    logic [SMaskW-1:0]   smask;   // covered samples, {pixel, sample}
    logic [2*PixelW-1:0] tile;    // {y, x} of the tile
    logic [3*CoefW-1:0]  a;
    logic [3*CoefW-1:0]  b;
    logic [3*EdgeW-1:0]  c;
    logic [2*PixelW-1:0] origin;
    logic [AreaW-1:0]    area2;
    attr_t               attr;
  } pix_t;

  // Elaboration-time checks of the exported parameters.
  if (SetupLatency < SetupInterval) begin : g_check_setup
    $error("rast_top: SetupLatency (%0d) must be at least SetupInterval (%0d)", SetupLatency, SetupInterval);
  end
  if (RopLenW != $clog2(RopClearPixelsPerCycle * MaxSamples + 1)) begin : g_check_rop_len
    $error("rast_top: RopLenW (%0d) must be clog2(RopClearPixelsPerCycle MaxSamples + 1)", RopLenW);
  end
  if (TileLog2Max < 1 || TileLog2Max > (1 << TileLog2W) - 1) begin : g_check_tile
    $error("rast_top: TileLog2Max (%0d) must be in 1..%0d (the tile_log2_i port)", TileLog2Max, (1 << TileLog2W) - 1);
  end

  if (MaxSamples < 2 || (MaxSamples & (MaxSamples - 1)) != 0 || $clog2(MaxSamples) > (1 << SampleLog2W) - 1) begin : g_check_samples
    $error("rast_top: MaxSamples (%0d) must be a power of two >= 2 whose log2 fits samples_log2_i (%0d bits)",
           MaxSamples, SampleLog2W);
  end

  // ---- The static raster state, registered (loaded every cycle; no reset) ----
  // The ports are static while the pipeline is busy, so a copy that lags them by one
  // cycle is the same value whenever it is used (the testbench sets them before reset,
  // whose cycle loads them). Why a register: the logic downstream then depends on state
  // only, not on a port, so Verilator evaluates it once a clock edge instead of on every
  // eval() call too (its input-combinational region re-runs all port-dependent logic on
  // each call; without this the interpolator's lanes ran three times a cycle).
  logic [TileLog2W-1:0]             tile_log2_q;     // tile_log2_i
  logic [1:0]                       fill_rule_q;     // fill_rule_i
  logic [1:0]                       cull_mode_q;     // cull_mode_i
  logic                             front_ccw_q;     // front_ccw_i
  logic [SampleLog2W-1:0]           samples_log2_q;  // samples_log2_i
  logic [MaxSamples*SampleOffW-1:0] sample_dx_q;     // sample_dx_i
  logic [MaxSamples*SampleOffW-1:0] sample_dy_q;     // sample_dy_i
  logic [1:0]                       tex_format_q;    // tex_format_i
  logic [1:0]                       tex_layout_q;    // tex_layout_i
  always_ff @(posedge clk_i) begin
    tile_log2_q    <= tile_log2_i;
    fill_rule_q    <= fill_rule_i;
    cull_mode_q    <= cull_mode_i;
    front_ccw_q    <= front_ccw_i;
    samples_log2_q <= samples_log2_i;
    sample_dx_q    <= sample_dx_i;
    sample_dy_q    <= sample_dy_i;
    tex_format_q   <= tex_format_i;
    tex_layout_q   <= tex_layout_i;
  end

  // ---- The sample offsets' bounding box {dy_max, dy_min, dx_max, dx_min} (static) ----
  logic [4*SampleOffW-1:0] box;
  always_comb begin
    logic signed [SampleOffW-1:0] dx, dy, dx_min, dx_max, dy_min, dy_max;
    dx_min = '0;
    dx_max = '0;
    dy_min = '0;
    dy_max = '0;
    for (int k = 0; k < MaxSamples; k++) begin
      dx = sample_dx_q[k*SampleOffW +: SampleOffW];
      dy = sample_dy_q[k*SampleOffW +: SampleOffW];
      if (k == 0 || (k >> samples_log2_q) == 0) begin
        if (k == 0 || dx < dx_min) dx_min = dx;
        if (k == 0 || dx > dx_max) dx_max = dx;
        if (k == 0 || dy < dy_min) dy_min = dy;
        if (k == 0 || dy > dy_max) dy_max = dy;
      end
    end
    box = {dy_max, dy_min, dx_max, dx_min};
  end

  // ---- Triangle FIFO (fifo.triangle_depth) ----
  logic  t_valid, t_ready, t_empty;
  tri_t  t_push, t_in;
  attr_t t_attr;
  localparam int TriW = $bits(t_push);   // derived
  localparam int AttrW = $bits(t_attr);  // derived
  assign t_push.marker = tri_marker_i;
  assign t_push.x = {tri_x2_i, tri_x1_i, tri_x0_i};
  assign t_push.y = {tri_y2_i, tri_y1_i, tri_y0_i};
  assign t_push.clip = {tri_clip_y1_i, tri_clip_x1_i, tri_clip_y0_i, tri_clip_x0_i};
  assign t_push.origin = {tri_origin_y_i, tri_origin_x_i};
  assign t_push.attr.z = {tri_z2_i, tri_z1_i, tri_z0_i};
  assign t_push.attr.rgb = {tri_rgb2_i, tri_rgb1_i, tri_rgb0_i};
  assign t_push.attr.s = tri_s_i;
  assign t_push.attr.t = tri_t_i;
  assign t_push.attr.q = tri_q_i;
  assign t_push.attr.affine = tri_affine_i;
  assign t_push.attr.tex = {tri_tex_on_i, tri_tex_bilinear_i, tri_tex_trilinear_i, tri_tex_wrap_s_i, tri_tex_wrap_t_i,
                            tri_tex_env_i, tri_tex_width_i, tri_tex_height_i, tri_tex_base_i, tri_tex_levels_i,
                            tri_tex_bias_i};
  rast_fifo #(.Width(TriW), .Depth(TriangleFifoDepth)) u_triangle_fifo (
    .clk_i, .rst_ni, .in_valid_i(tri_valid_i), .in_ready_o(tri_ready_o), .in_data_i(t_push),
    .out_valid_o(t_valid), .out_ready_i(t_ready), .out_data_o(t_in), .empty_o(t_empty));
  assign t_attr = t_in.attr;

  // ---- Triangle setup ----
  logic                s_valid, s_ready, s_marker, s_busy, s_done;
  logic [3*CoefW-1:0]  s_a, s_b;
  logic [3*EdgeW-1:0]  s_c;
  logic [2:0]          s_bias;
  logic [AreaW-1:0]    s_area2;
  logic [4*PixelW-1:0] s_bbox;
  logic [2*PixelW-1:0] s_origin;
  attr_t               s_attr;
  set_t                s_push;
  localparam int SetW = $bits(s_push);  // derived
  rast_tri_setup #(
    .CoordW(CoordW), .CoordFrac(CoordFrac), .CoefW(CoefW), .EdgeW(EdgeW), .AreaW(AreaW),
    .PixelW(PixelW), .AttrW(AttrW), .SampleOffW(SampleOffW), .SetupInterval(SetupInterval)
  ) u_tri_setup (
    .clk_i, .rst_ni, .fill_rule_i(fill_rule_q), .cull_mode_i(cull_mode_q), .front_ccw_i(front_ccw_q), .box_i(box),
    .in_valid_i(t_valid), .in_ready_o(t_ready), .in_marker_i(t_in.marker),
    .in_x_i(t_in.x), .in_y_i(t_in.y), .in_clip_i(t_in.clip), .in_origin_i(t_in.origin), .in_attr_i(t_attr),
    .out_valid_o(s_valid), .out_ready_i(s_ready), .out_marker_o(s_marker), .out_a_o(s_a),
    .out_b_o(s_b), .out_c_o(s_c), .out_bias_o(s_bias), .out_area2_o(s_area2), .out_bbox_o(s_bbox),
    .out_origin_o(s_origin), .out_attr_o(s_attr), .busy_o(s_busy), .done_o(s_done));
  assign s_push.marker = s_marker;
  assign s_push.edges.a = s_a;
  assign s_push.edges.b = s_b;
  assign s_push.edges.c = s_c;
  assign s_push.edges.bias = s_bias;
  assign s_push.bbox = s_bbox;
  assign s_push.origin = s_origin;
  assign s_push.area2 = s_area2;
  assign s_push.attr = s_attr;

  // ---- Setup FIFO (SetupFifoEntries: fifo.setup_depth plus the triangles inside setup's
  // latency pipeline, TimingParams::setup_fifo_entries; entries wait setup.latency -
  // interval cycles) ----
  logic c_valid, c_ready, c_empty, c_busy;
  logic c_fifo_valid, c_fifo_ready;
  set_t c_fifo_data, c_in;
  rast_fifo #(.Width(SetW), .Depth(SetupFifoEntries), .Latency(SetupLatency - SetupInterval)) u_setup_fifo (
    .clk_i, .rst_ni, .in_valid_i(s_valid), .in_ready_o(s_ready), .in_data_i(s_push),
    .out_valid_o(c_fifo_valid), .out_ready_i(c_fifo_ready), .out_data_o(c_fifo_data), .empty_o(c_empty));
  rast_hold #(.Width(SetW)) u_coarse_hold (
    .clk_i, .rst_ni, .in_valid_i(c_fifo_valid), .in_ready_o(c_fifo_ready), .in_data_i(c_fifo_data),
    .out_valid_o(c_valid), .out_ready_i(c_ready), .out_data_o(c_in));

  // ---- Coarse raster ----
  logic                k_valid, k_ready, k_marker, k_accepted;
  logic [4*PixelW-1:0] k_fp;
  tile_t               k_push;
  localparam int TileW = $bits(k_push);  // derived
  // Hi-Z hooks (rast_top_hiz below): coarse raster's lanes and their answers.
  localparam int KLanes = CoarseTilesPerCycle;  // derived
  logic [KLanes*4*PixelW-1:0] k_lane_fp;
  logic [KLanes-1:0]   k_lane_keep, k_lane_wait, k_lane_cull, k_lane_accept;
  logic                k_hiz_accept, k_room;
  logic [$clog2(KLanes+1)-1:0] k_hiz_culled;
  logic                rop_hiz_always, rop_hiz_always_next, rop_hiz_end, rop_hiz_marker, rop_hiz_clear;
  logic [RopPixelsPerCycle-1:0]        rop_hiz_wr_lanes;
  logic [RopPixelsPerCycle*PixelW-1:0] rop_hiz_wr_x, rop_hiz_wr_y;
  logic [RopPixelsPerCycle*DepthW-1:0] rop_hiz_wr_z;
  logic                hiz_busy;  // Hi-Z's spilled entries: writes not yet written back
  rast_coarse_raster #(
    .CoordW(CoordW), .CoordFrac(CoordFrac), .CoefW(CoefW), .EdgeW(EdgeW), .PixelW(PixelW),
    .TileLog2W(TileLog2W), .SampleOffW(SampleOffW), .TilesPerCycle(CoarseTilesPerCycle)
  ) u_coarse_raster (
    .clk_i, .rst_ni, .tile_log2_i(tile_log2_q), .box_i(box), .in_valid_i(c_valid), .in_ready_o(c_ready),
    .in_marker_i(c_in.marker), .in_a_i(c_in.edges.a), .in_b_i(c_in.edges.b), .in_c_i(c_in.edges.c),
    .in_bias_i(c_in.edges.bias), .in_bbox_i(c_in.bbox), .in_origin_i(c_in.origin),
    .out_valid_o(k_valid), .out_ready_i(k_ready), .out_marker_o(k_marker), .out_accepted_o(k_accepted),
    .out_fp_o(k_fp), .busy_o(c_busy), .lane_fp_o(k_lane_fp), .lane_keep_o(k_lane_keep), .lane_wait_i(k_lane_wait), .lane_cull_i(k_lane_cull),
    .lane_accept_i(k_lane_accept), .out_hiz_accept_o(k_hiz_accept), .hiz_culled_o(k_hiz_culled));
  assign k_push.marker = k_marker;
  assign k_push.accepted = k_accepted;
  assign k_push.fp = k_fp;
  assign k_push.edges = c_in.edges;
  assign k_push.origin = c_in.origin;
  assign k_push.area2 = c_in.area2;
  assign k_push.attr = c_in.attr;

  // ---- Tile FIFO (fifo.tile_depth) ----
  logic  f_valid, f_ready, f_empty, f_busy;
  logic  f_fifo_valid, f_fifo_ready;
  tile_t f_fifo_data, f_in;
  logic k_fifo_ready;
  assign k_ready = k_fifo_ready && k_room;  // the interlock's entry fits (always, by its size)
  rast_fifo #(.Width(TileW), .Depth(TileFifoDepth)) u_tile_fifo (
    .clk_i, .rst_ni, .in_valid_i(k_valid && k_room), .in_ready_o(k_fifo_ready), .in_data_i(k_push),
    .out_valid_o(f_fifo_valid), .out_ready_i(f_fifo_ready), .out_data_o(f_fifo_data), .empty_o(f_empty));
  rast_hold #(.Width(TileW)) u_fine_hold (
    .clk_i, .rst_ni, .in_valid_i(f_fifo_valid), .in_ready_o(f_fifo_ready), .in_data_i(f_fifo_data),
    .out_valid_o(f_valid), .out_ready_i(f_ready), .out_data_o(f_in));

  // ---- Fine raster ----
  logic                m_valid, m_ready, m_marker;
  logic [MaskW-1:0]    m_mask;
  logic [SMaskW-1:0]   m_smask;
  logic [2*PixelW-1:0] m_tile;
  pix_t                m_push;
  localparam int PixW = $bits(m_push);  // derived
  rast_fine_raster #(
    .CoordW(CoordW), .CoordFrac(CoordFrac), .CoefW(CoefW), .EdgeW(EdgeW), .PixelW(PixelW),
    .TileLog2Max(TileLog2Max), .TileLog2W(TileLog2W), .SamplesPerCycle(FineSamplesPerCycle),
    .AcceptedTileCycles(FineAcceptedTileCycles), .MaxSamples(MaxSamples), .SampleLog2W(SampleLog2W),
    .SampleOffW(SampleOffW)
  ) u_fine_raster (
    .clk_i, .rst_ni, .tile_log2_i(tile_log2_q), .samples_log2_i(samples_log2_q), .sample_dx_i(sample_dx_q),
    .sample_dy_i(sample_dy_q), .in_valid_i(f_valid), .in_ready_o(f_ready), .in_marker_i(f_in.marker),
    .in_accepted_i(f_in.accepted), .in_fp_i(f_in.fp), .in_a_i(f_in.edges.a), .in_b_i(f_in.edges.b),
    .in_c_i(f_in.edges.c), .in_bias_i(f_in.edges.bias), .in_origin_i(f_in.origin), .in_quads_i(f_in.attr.tex.on),
    .out_valid_o(m_valid),
    .out_ready_i(m_ready), .out_marker_o(m_marker), .out_mask_o(m_mask), .out_smask_o(m_smask),
    .out_tile_o(m_tile), .busy_o(f_busy));
  assign m_push.marker = m_marker;
  assign m_push.mask = m_mask;
  assign m_push.smask = m_smask;
  assign m_push.tile = m_tile;
  assign m_push.a = f_in.edges.a;
  assign m_push.b = f_in.edges.b;
  assign m_push.c = f_in.edges.c;
  assign m_push.origin = f_in.origin;
  assign m_push.area2 = f_in.area2;
  assign m_push.attr = f_in.attr;

  // ---- Pixel FIFO (fifo.pixel_depth; one entry = one tile's coverage mask) ----
  logic p_valid, p_ready, p_empty, p_busy;
  logic p_fifo_valid, p_fifo_ready, p_hold_ready;
  pix_t p_fifo_data, p_in;
  rast_fifo #(.Width(PixW), .Depth(PixelFifoDepth)) u_pixel_fifo (
    .clk_i, .rst_ni, .in_valid_i(m_valid), .in_ready_o(m_ready), .in_data_i(m_push),
    .out_valid_o(p_fifo_valid), .out_ready_i(p_fifo_ready), .out_data_o(p_fifo_data), .empty_o(p_empty));
  logic ts_room, ts_valid, ts_empty, ts_pop;  // the tile texture-state FIFO (below)
  logic cr_admit;  // the fragment FIFO's credits admit the head (below, "Interpolator credits")
  logic ez_wait;   // early Z's interlock holds the head (below, "Early Z")
  // A tile enters the hold with room for its state and, untextured, a credit.
  assign p_fifo_ready = p_hold_ready && ts_room && cr_admit && !ez_wait;
  rast_hold #(.Width(PixW)) u_interp_hold (
    .clk_i, .rst_ni, .in_valid_i(p_fifo_valid && ts_room && cr_admit && !ez_wait), .in_ready_o(p_hold_ready), .in_data_i(p_fifo_data),
    .out_valid_o(p_valid), .out_ready_i(p_ready), .out_data_o(p_in));

  // ---- Tile texture-state FIFO: a tile's texture state from the interpolator's input
  // (pushed as its hold takes the tile: the first cycle the interpolator works on it,
  // before any of its beats leaves) to the texture stage (popped with the tile's last beat).
  // TileStateDepth tiles cover the interpolator's pipeline (Latency + RecipLatency
  // stages, a tile at least a cycle) and its output hold. ----
  localparam int TileStateDepth = 32;
  tex_t ts_push, ts_head;
  localparam int TexStateW = $bits(ts_push);  // derived
  assign ts_push = p_fifo_data.attr.tex;
  rast_fifo #(.Width(TexStateW), .Depth(TileStateDepth)) u_tile_state_fifo (
    .clk_i, .rst_ni, .in_valid_i(p_fifo_valid && p_fifo_ready && !p_fifo_data.marker), .in_ready_o(ts_room), .in_data_i(ts_push),
    .out_valid_o(ts_valid), .out_ready_i(ts_pop), .out_data_o(ts_head), .empty_o(ts_empty));
  wire unused_ts_valid = ts_valid;  // a non-marker beat always has its tile's state

  // ---- Interpolation (out: i_*, into the texture stage) ----
  logic                                  i_valid, i_ready, i_marker, i_last;
  logic [Lanes-1:0]                      i_lanes;
  logic [Lanes*PixelW-1:0]               i_x, i_y;
  logic [Lanes*DepthW-1:0]               i_z;
  logic [Lanes*24-1:0]                   i_rgb;
  logic [Lanes*TexW-1:0]                 i_s, i_t;
  logic [Lanes*MaxSamples-1:0]           i_smask;
  rast_interpolate #(
    .CoordW(CoordW), .CoordFrac(CoordFrac), .CoefW(CoefW), .EdgeW(EdgeW), .AreaW(AreaW),
    .ColorNumW(ColorNumW), .DepthNumW(DepthNumW), .DepthW(DepthW), .PixelW(PixelW),
    .TileLog2Max(TileLog2Max), .TileLog2W(TileLog2W), .FragmentsPerCycle(InterpFragmentsPerCycle), .Latency(InterpLatency),
    .MaxSamples(MaxSamples), .TexW(TexW), .ColorFrac(ColorFrac), .Perspective(InterpPerspective), .PerspLanes(InterpPerspLanes),
    .RecipSeedBits(RecipSeedBits), .RecipIterations(RecipIterations), .RecipLatency(InterpRecipLatency)
  ) u_interpolate (
    .clk_i, .rst_ni, .tile_log2_i(tile_log2_q), .in_valid_i(p_valid), .in_ready_o(p_ready), .in_marker_i(p_in.marker),
    .in_mask_i(p_in.mask), .in_smask_i(p_in.smask), .in_tile_i(p_in.tile), .in_rowpair_i(p_in.attr.tex.on),
    .in_a_i(p_in.a), .in_b_i(p_in.b),
    .in_c_i(p_in.c), .in_origin_i(p_in.origin), .in_area2_i(p_in.area2), .in_z_i(p_in.attr.z),
    .in_rgb_i(p_in.attr.rgb), .in_s_i(p_in.attr.s), .in_t_i(p_in.attr.t), .in_q_i(p_in.attr.q),
    .in_affine_i(p_in.attr.affine),
    .out_valid_o(i_valid), .out_ready_i(i_ready), .out_marker_o(i_marker),
    .out_last_o(i_last), .out_lanes_o(i_lanes), .out_x_o(i_x), .out_y_o(i_y),
    .out_z_o(i_z), .out_rgb_o(i_rgb), .out_s_o(i_s), .out_t_o(i_t), .out_smask_o(i_smask), .busy_o(p_busy));

  // ---- Texture stage (textured tiles; the rest passes through; with DepthEarly the lanes
  // the early test culled, ez_culled, are not textured and keep their place) ----
  logic x_busy;
  logic x_valid, x_ready;  // its output, into the fragment FIFO
  logic [Lanes-1:0] ez_culled;  // the early test's culls on the beat offered (below, "Early Z")
  logic                 tex_req_valid, tex_req_ready, tex_rsp_valid, tex_rsp_ready;
  logic [4*TexAddrW-1:0] tex_req_addr;
  logic [2:0]           tex_req_count;
  logic [1:0]           tex_req_format;
  logic [127:0]         tex_rsp_texels;
  logic                 x_hold;      // a textured tile's first beat held for a credit ("Interpolator credits")
  logic                 x_in_ready;  // the stage takes the beat
  assign i_ready = x_in_ready && !x_hold;
  rast_texture_stage #(
    .Lanes(Lanes), .PixelW(PixelW), .DepthW(DepthW), .MaxSamples(MaxSamples), .TexW(TexW), .TexFrac(TexFrac),
    .WeightBits(TexWeightBits), .SizeW(TexSizeW), .AddrW(TexAddrW), .TileLog2Max(TileLog2Max),
    .LevelW(TexLevelW), .BiasW(TexBiasW), .Early(DepthEarly)
  ) u_texture (
    .clk_i, .rst_ni, .format_i(tex_format_q), .layout_i(tex_layout_q),
    .in_valid_i(i_valid && !x_hold), .in_ready_o(x_in_ready), .in_marker_i(i_marker), .in_last_i(i_last), .in_lanes_i(i_lanes),
    .in_x_i(i_x), .in_y_i(i_y), .in_z_i(i_z), .in_rgb_i(i_rgb), .in_s_i(i_s), .in_t_i(i_t), .in_smask_i(i_smask),
    .in_culled_i(ez_culled),
    .in_tex_on_i(ts_head.on), .in_bilinear_i(ts_head.bilinear), .in_trilinear_i(ts_head.trilinear),
    .in_wrap_s_i(ts_head.wrap_s),
    .in_wrap_t_i(ts_head.wrap_t), .in_env_i(ts_head.env), .in_width_i(ts_head.width), .in_height_i(ts_head.height),
    .in_base_i(ts_head.base), .in_levels_i(ts_head.levels), .in_bias_i(ts_head.bias),
    .out_valid_o(x_valid), .out_ready_i(x_ready), .out_marker_o(frag_marker_o),
    .out_last_o(frag_last_o), .out_lanes_o(frag_lanes_o), .out_x_o(frag_x_o), .out_y_o(frag_y_o),
    .out_z_o(frag_z_o), .out_rgb_o(frag_rgb_o), .out_s_o(frag_s_o), .out_t_o(frag_t_o), .out_smask_o(frag_mask_o),
    .out_culled_o(frag_culled_o),
    .tex_req_valid_o(tex_req_valid), .tex_req_ready_i(tex_req_ready), .tex_req_addr_o(tex_req_addr),
    .tex_req_count_o(tex_req_count), .tex_req_format_o(tex_req_format), .tex_rsp_valid_i(tex_rsp_valid),
    .tex_rsp_ready_o(tex_rsp_ready), .tex_rsp_texels_i(tex_rsp_texels), .helpers_o(tex_helpers_o), .busy_o(x_busy));

  // ---- Texture cache (texture.cache_bytes, ways, line_bytes; TexPorts lookups a cycle)
  // on the stage's texel fetch port: hits answered from its lines, misses filled through
  // tex_mem_*. texture.cache_bytes = 0 (every fetch a miss of its own texel) has no RTL
  // cache: the port is tied off and co-simulation refuses textured scenes. ----
  if (TexCacheBytes > 0) begin : g_tex_cache
    rast_texture_cache #(
      .AddrW(TexAddrW), .CacheBytes(TexCacheBytes), .Ways(TexWays), .LineBytes(TexLineBytes), .Ports(TexPorts),
      .BeatBytes(TexBeatBytes)
    ) u_texture_cache (
      .clk_i, .rst_ni, .req_valid_i(tex_req_valid), .req_ready_o(tex_req_ready), .req_addr_i(tex_req_addr),
      .req_count_i(tex_req_count), .req_format_i(tex_req_format), .rsp_valid_o(tex_rsp_valid),
      .rsp_ready_i(tex_rsp_ready), .rsp_texels_o(tex_rsp_texels), .mem_req_valid_o(tex_mem_req_valid_o),
      .mem_req_ready_i(tex_mem_req_ready_i), .mem_req_addr_o(tex_mem_req_addr_o),
      .mem_rsp_valid_i(tex_mem_rsp_valid_i), .mem_rsp_ready_o(tex_mem_rsp_ready_o),
      .mem_rsp_data_i(tex_mem_rsp_data_i[8*TexBeatBytes-1:0]), .evt_hits_o(tex_hits_o), .evt_miss_o(tex_miss_o));
    if (TexBeatBytes < 16) begin : g_unused_beat
      wire unused_beat_bytes = ^tex_mem_rsp_data_i[127:8*TexBeatBytes];
    end
  end else begin : g_no_tex_cache
    assign tex_req_ready = 1'b0;
    assign tex_rsp_valid = 1'b0;
    assign tex_rsp_texels = '0;
    assign tex_mem_req_valid_o = 1'b0;
    assign tex_mem_req_addr_o = '0;
    assign tex_mem_rsp_ready_o = 1'b0;
    assign tex_hits_o = '0;
    assign tex_miss_o = 1'b0;
    wire unused_tex_port = ^{tex_req_valid, tex_req_addr, tex_req_count, tex_req_format, tex_rsp_ready,
                             tex_mem_req_ready_i, tex_mem_rsp_valid_i, tex_mem_rsp_data_i};
  end
  assign ts_pop = i_valid && i_ready && !i_marker && i_last;
  assign frag_valid_o = x_valid;
  assign x_ready = frag_ready_o;
  // Idle with a textured tile held for a credit (x_hold) is blocked: the SystemC stage
  // blocked in the write of its last batch.
  assign dbg_tex_busy_o = x_busy || x_hold;
  assign dbg_tex_blocked_o = x_busy ? frag_valid_o && !frag_ready_o : x_hold;

  // ---- Fragment FIFO (beats; whole tiles: FragmentFifoEntries of them waiting) ----
  // batches_q: complete tiles (a tile's last beat or a marker pushed) whose first beat
  // the ROP has not taken. The ROP reads a tile's beats only once the tile is complete
  // (in_tile_q: it took a tile's first beat and not yet its last). The interpolator's
  // beat is refused while FragmentFifoEntries + 1 tiles are complete and waiting (after
  // this cycle's take by the ROP); the credits below bind first (this guards the ring).
  beat_t            r_push, r_in;
  logic             r_fifo_valid, r_fifo_empty, r_fifo_room;
  logic             r_valid, r_ready, r_take, r_first, r_end, w_end;
  logic             beat_push;
  logic [BatchW-1:0] batches_q;
  logic             in_tile_q;
  logic             rop_idle, rop_has, rop_done, rop_blocked;
  localparam int BeatW = $bits(r_push);  // derived

  // ---- Beat packer: the interpolator's beats (a perspective-correct triangle's carry
  // InterpPerspLanes fragments, a row's last fewer) packed into beats of Lanes fragments,
  // so the ROP reads a tile at up to Lanes fragments a cycle (the SystemC ROP's
  // rop.pixels_per_cycle on a whole batch). A tile's last beat pushes what is held; when
  // held and new lanes overflow one beat, the rest is pushed the next cycle (flush_q),
  // in which the packer takes nothing. Lane j of a beat: {x, y, z, rgb, mask}. ----
  localparam int LaneW = 2 * PixelW + DepthW + 24 + MaxSamples;  // derived
  localparam int LaneCntW = $clog2(2 * Lanes + 1);               // derived: 0 .. 2 Lanes
  localparam int LaneIdxW = Lanes > 1 ? $clog2(Lanes) : 1;       // derived: a lane's index
  logic [LaneW-1:0]    acc_q [Lanes];   // lanes held, 0 .. acc_n_q - 1
  logic [LaneCntW-1:0] acc_n_q;
  logic                flush_q;         // the held lanes end a tile: push them, take nothing
  logic [LaneW-1:0]    pk_out [Lanes];  // the beat pushed
  logic [LaneW-1:0]    pk_rest [Lanes]; // lanes held after this cycle
  logic [LaneCntW-1:0] pk_total;        // held + new lanes
  logic                pk_push, pk_take;
  always_comb begin
    logic [LaneCntW-1:0] d;
    for (int i = 0; i < Lanes; i++) begin
      pk_out[i] = acc_q[i];
      pk_rest[i] = '0;
    end
    d = acc_n_q;
    for (int j = 0; j < Lanes; j++) begin
      if (frag_lanes_o[j] && !flush_q) begin
        if (d < LaneCntW'(Lanes)) pk_out[LaneIdxW'(d)] = {frag_x_o[j*PixelW +: PixelW], frag_y_o[j*PixelW +: PixelW],
            frag_z_o[j*DepthW +: DepthW], frag_rgb_o[j*24 +: 24], frag_mask_o[j*MaxSamples +: MaxSamples]};
        else pk_rest[LaneIdxW'(d - LaneCntW'(Lanes))] = {frag_x_o[j*PixelW +: PixelW], frag_y_o[j*PixelW +: PixelW],
            frag_z_o[j*DepthW +: DepthW], frag_rgb_o[j*24 +: 24], frag_mask_o[j*MaxSamples +: MaxSamples]};
        d = d + 1'b1;
      end
    end
    pk_total = d;
  end
  // Pushed: the flush; a marker; a full beat; a tile's last beat.
  assign pk_push = flush_q || (frag_valid_o && (frag_marker_o || frag_last_o || pk_total >= LaneCntW'(Lanes)));
  assign r_push.marker = !flush_q && frag_marker_o;
  assign r_push.last = flush_q || (frag_last_o && !frag_marker_o && pk_total <= LaneCntW'(Lanes));
  for (genvar i = 0; i < Lanes; i++) begin : g_pack
    assign r_push.lanes[i] = LaneCntW'(i) < (flush_q ? acc_n_q : pk_total);
    assign {r_push.x[i*PixelW +: PixelW], r_push.y[i*PixelW +: PixelW], r_push.z[i*DepthW +: DepthW],
            r_push.rgb[i*24 +: 24], r_push.mask[i*MaxSamples +: MaxSamples]} = pk_out[i];
  end
  assign pk_take = frag_valid_o && frag_ready_o;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      acc_n_q <= '0;
      flush_q <= 1'b0;
    end else if (flush_q) begin
      if (beat_push) begin
        acc_n_q <= '0;
        flush_q <= 1'b0;
      end
    end else if (pk_take && !frag_marker_o) begin
      acc_n_q <= pk_push ? (pk_total >= LaneCntW'(Lanes) ? pk_total - LaneCntW'(Lanes) : '0) : pk_total;
      flush_q <= frag_last_o && pk_total > LaneCntW'(Lanes);
    end
  end
  always_ff @(posedge clk_i) begin
    if (flush_q) begin
      if (beat_push) for (int i = 0; i < Lanes; i++) acc_q[i] <= '0;
    end else if (pk_take && !frag_marker_o) begin
      for (int i = 0; i < Lanes; i++) acc_q[i] <= pk_push ? pk_rest[i] : pk_out[i];
    end
  end
  assign r_valid = r_fifo_valid && (in_tile_q || batches_q != '0);
  assign r_take = r_valid && r_ready;
  assign r_first = r_take && !in_tile_q;
  assign r_end = r_take && (r_in.marker || r_in.last);
  assign frag_ready_o = !flush_q && (!pk_push || r_fifo_room) &&
                        (batches_q - BatchW'(r_first)) <= BatchW'(FragmentFifoEntries);
  assign w_end = beat_push && (r_push.marker || r_push.last);
  // A ring of FragBeats beats (rast_fifo's timing without its latency countdown, whose
  // loop over every entry Verilator cannot schedule at this depth): push and pop in one
  // cycle when full, an entry visible the cycle after its push. The beats are
  // rast_fragment_fifo_data (one read and one write port), a storage array to `rastsim
  // area` (row fragment_fifo.beats, FragBeats x BeatW bits); pointers and count are here.
  localparam int BeatPtrW = $clog2(FragBeats);      // derived
  localparam int BeatCntW = $clog2(FragBeats + 1);  // derived
  logic [BeatPtrW-1:0] beat_rd_q, beat_wr_q;
  logic [BeatCntW-1:0] beat_count_q;
  assign r_fifo_empty = beat_count_q == '0;
  assign r_fifo_valid = !r_fifo_empty;
  assign r_fifo_room = beat_count_q != BeatCntW'(FragBeats) || r_take;
  assign beat_push = flush_q ? r_fifo_room : pk_push && pk_take;
  rast_fragment_fifo_data #(.Depth(FragBeats), .Width(BeatW)) u_frag_beats (
    .clk_i, .rd_addr_i(beat_rd_q), .rd_data_o(r_in), .wr_en_i(beat_push), .wr_addr_i(beat_wr_q), .wr_data_i(r_push)
  );
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      beat_rd_q <= '0;
      beat_wr_q <= '0;
      beat_count_q <= '0;
      batches_q <= '0;
      in_tile_q <= 1'b0;
    end else begin
      if (beat_push) beat_wr_q <= beat_wr_q == BeatPtrW'(FragBeats - 1) ? '0 : beat_wr_q + 1'b1;
      if (r_take) beat_rd_q <= beat_rd_q == BeatPtrW'(FragBeats - 1) ? '0 : beat_rd_q + 1'b1;
      beat_count_q <= beat_count_q + BeatCntW'(beat_push) - BeatCntW'(r_take);
      batches_q <= batches_q + BatchW'(w_end) - BatchW'(r_first);
      if (r_take) in_tile_q <= !r_end;
    end
  end

  // ---- Interpolator credits: the fragment FIFO's FragmentFifoEntries slots, as the
  // SystemC model's interpolator holds them (docs/rtl.md "Fragment FIFO"). Its fragment
  // link has FragmentFifoEntries slots (fifo.fragment_depth + the interpolator's latency
  // slots) and its interpolator reads the next batch only once the previous one is in
  // the link: at most FragmentFifoEntries + 1 batches between the interpolator's input
  // and the ROP. cr_q counts them: an untextured tile or a marker from the cycle it
  // enters the interpolator's hold (its latency beats included: without this, the
  // frozen pipeline held Latency + RecipLatency beats, i.e. up to 12 one-beat tiles,
  // beyond the FIFO's tiles), a textured tile from the cycle its last fragment enters
  // the FIFO (before, it is the texture FIFO's: rast_texture_stage, x_busy while any is
  // in it), each until the ROP starts it (dbg_rop_start_o: a tile's first group's read
  // taken, a marker's take), not until it takes the tile's first beat: rast_rop's access
  // buffer takes beats of later tiles while a group waits for memory (up to Cap
  // accesses: dozens of one-fragment tiles), and the model's ROP reads a batch only when
  // it starts on it. An untextured tile or a marker at the pixel FIFO's head enters only
  // while at most FragmentFifoEntries are counted (after this cycle's start); a textured
  // one is not held here but at the texture stage's input (xq_q below), behind the
  // tiles ahead of it alone, so it never waits on an untextured tile behind it. ----
  // Derived: up to 2 (Entries + 1) tiles before the ROP, plus one a fragment in its
  // access buffer (textured tiles, counted without a bound, may fill it).
  localparam int CrW = $clog2(2 * FragmentFifoEntries + 3 + 2 * (RopPixelsPerCycle + Lanes * MaxSamples));
  logic [CrW-1:0] cr_q;
  logic           cr_counted, cr_take, cr_tex_end, cr_wait, cr_start;
  assign cr_counted = p_fifo_data.marker || !p_fifo_data.attr.tex.on;
  assign cr_start = dbg_rop_start_o;  // the ROP starts a tile or a marker
  assign cr_admit = !cr_counted || (cr_q - CrW'(cr_start)) <= CrW'(FragmentFifoEntries);
  assign cr_wait = p_fifo_valid && ts_room && !cr_admit && !p_valid;  // a tile waits for a credit
  assign cr_take = p_fifo_valid && p_fifo_ready && cr_counted;
  assign cr_tex_end = w_end && x_busy;  // a textured tile's last fragment pushed
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) cr_q <= '0;
    else cr_q <= cr_q + CrW'(cr_take) + CrW'(cr_tex_end) - CrW'(cr_start);
  end
  // The texture stage's credits: xq_q counts every tile and marker from the cycle the
  // texture stage takes its first beat until the ROP starts it, and a textured tile's
  // first beat enters the stage only while at most FragmentFifoEntries are counted
  // (after this cycle's start): the SystemC texture stage reads its next batch only once
  // its write of the last one is done, at most FragmentFifoEntries + 1 batches between
  // its input and the ROP, as the interpolator's. Without it the stage sampled the next
  // tile's head (its misses' fills) with FragmentFifoEntries + 1 complete tiles waiting,
  // a tile ahead of the model (textured_mip_cosim dram -2.66 %, docs/texture.md). Only
  // tiles ahead of the held one are counted, so it never waits on a tile behind it.
  logic [CrW-1:0] xq_q;
  logic           xq_in_tile_q, xq_take;  // the stage took a tile's first beat and not its last
  assign xq_take = i_valid && i_ready && (i_marker || !xq_in_tile_q);
  assign x_hold = i_valid && !i_marker && !xq_in_tile_q && ts_head.on &&
                  (xq_q - CrW'(cr_start)) > CrW'(FragmentFifoEntries);
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      xq_q <= '0;
      xq_in_tile_q <= 1'b0;
    end else begin
      xq_q <= xq_q + CrW'(xq_take) - CrW'(cr_start);
      if (i_valid && i_ready && !i_marker) xq_in_tile_q <= !i_last;
    end
  end

  // ---- ROP ----
  // Binned mode (TileBufferSamples > 0, docs/rtl.md "Tile buffer"): the ROP's memory port
  // goes to the tile buffer, its framebuffer is the current bin (bin-local pixels, its
  // width and height, colour at 0 and depth at TileBufferSamples 4), and a bin command
  // (op 4, 5) and a bin's clear (1, 2: the tile buffer's flash clear) reach it as a pass;
  // while the tile buffer loads, stores or clears, the ROP's port is not ready and its
  // next command waits.
  logic                                   rop_rd_valid, rop_rd_ready, rop_rd_rvalid, rop_rd_no_depth;
  logic [RopPixelsPerCycle-1:0]           rop_rd_lanes;
  logic [RopPixelsPerCycle*32-1:0]        rop_rd_addr;
  logic [RopPixelsPerCycle*RopLenW-1:0]   rop_rd_len;
  logic [RopPixelsPerCycle*MaxSamples*32-1:0] rop_rd_rdata;
  logic                                   rop_wr_valid, rop_wr_ready, rop_wr_fill;
  logic [2*RopPixelsPerCycle-1:0]         rop_wr_lanes;
  logic [2*RopPixelsPerCycle*32-1:0]      rop_wr_addr;
  logic [2*RopPixelsPerCycle*RopLenW-1:0] rop_wr_len;
  logic [2*RopPixelsPerCycle*MaxSamples*4-1:0] rop_wr_be;
  logic [2*RopPixelsPerCycle*32-1:0]      rop_wr_data;
  logic                                   rop_cmd_valid, rop_cmd_ready, tb_busy, tb_idle;
  logic [PixelW-1:0]                      rop_fb_w, rop_fb_h;
  logic [31:0]                            rop_color_base, rop_depth_base;
  logic [Lanes*PixelW-1:0]                rop_x, rop_y;
  logic [1:0]                             rop_cmd_op;
  assign rop_cmd_valid = cmd_valid_i && !tb_busy;
  // Binned: every command is a pass at the ROP (the tile buffer clears, loads and stores).
  assign rop_cmd_op = TileBufferSamples > 0 || cmd_op_i[2] ? 2'd0 : cmd_op_i[1:0];
  assign cmd_ready_o = rop_cmd_ready && !tb_busy;
  if (TileBufferSamples > 0) begin : g_bins
    logic [PixelW-1:0] bx0, by0;
    rast_tile_buffer #(
      .PixelW(PixelW), .DepthW(DepthW), .MaxSamples(MaxSamples), .SampleLog2W(SampleLog2W), .P(RopPixelsPerCycle),
      .LenW(RopLenW), .Slots(TileBufferSamples), .PortBytes(TilePortBytes), .ClearPixelsPerCycle(RopClearPixelsPerCycle),
      .AddrW(32), .PortWords(TilePortWords)
    ) u_tile_buffer (
      .clk_i, .rst_ni, .samples_log2_i(samples_log2_q), .fb_width_i, .color_base_i, .depth_base_i,
      .cmd_take_i(rop_cmd_valid && rop_cmd_ready), .cmd_op_i, .cmd_value_i, .cmd_bin_i,
      .busy_o(tb_busy), .bin_x0_o(bx0), .bin_y0_o(by0), .bin_w_o(rop_fb_w), .bin_h_o(rop_fb_h),
      .rd_valid_i(rop_rd_valid), .rd_ready_o(rop_rd_ready), .rd_lanes_i(rop_rd_lanes), .rd_addr_i(rop_rd_addr),
      .rd_len_i(rop_rd_len), .rd_rvalid_o(rop_rd_rvalid), .rd_rdata_o(rop_rd_rdata),
      .wr_valid_i(rop_wr_valid), .wr_ready_o(rop_wr_ready), .wr_lanes_i(rop_wr_lanes), .wr_addr_i(rop_wr_addr),
      .wr_len_i(rop_wr_len), .wr_be_i(rop_wr_be), .wr_data_i(rop_wr_data),
      .tl_valid_o, .tl_ready_i, .tl_write_o, .tl_addr_o, .tl_count_o, .tl_wdata_o, .tl_rvalid_i, .tl_rdata_i,
      .idle_o(tb_idle));
    assign rop_color_base = '0;
    assign rop_depth_base = 32'(TileBufferSamples * 4);
    for (genvar j = 0; j < Lanes; j++) begin : g_local
      assign rop_x[j*PixelW +: PixelW] = r_in.x[j*PixelW +: PixelW] - bx0;
      assign rop_y[j*PixelW +: PixelW] = r_in.y[j*PixelW +: PixelW] - by0;
    end
    assign {rd_valid_o, rd_lanes_o, rd_addr_o, rd_len_o, rd_no_depth_o} = '0;
    assign {wr_valid_o, wr_lanes_o, wr_addr_o, wr_len_o, wr_fill_o, wr_be_o, wr_data_o} = '0;
    wire unused_bin_port = ^{rd_ready_i, rd_rvalid_i, rd_rdata_i, wr_ready_i, fb_height_i, rop_wr_fill, rop_rd_no_depth};
  end else begin : g_immediate
    assign {rop_fb_w, rop_fb_h, rop_color_base, rop_depth_base} = {fb_width_i, fb_height_i, color_base_i, depth_base_i};
    assign {rop_x, rop_y} = {r_in.x, r_in.y};
    assign {tb_busy, tb_idle} = 2'b01;
    assign {rd_valid_o, rd_lanes_o, rd_addr_o, rd_len_o, rd_no_depth_o} =
        {rop_rd_valid, rop_rd_lanes, rop_rd_addr, rop_rd_len, rop_rd_no_depth};
    assign {rop_rd_ready, rop_rd_rvalid, rop_rd_rdata} = {rd_ready_i, rd_rvalid_i, rd_rdata_i};
    assign {wr_valid_o, wr_lanes_o, wr_addr_o, wr_len_o, wr_fill_o, wr_be_o, wr_data_o} =
        {rop_wr_valid, rop_wr_lanes, rop_wr_addr, rop_wr_len, rop_wr_fill, rop_wr_be, rop_wr_data};
    assign rop_wr_ready = wr_ready_i;
    assign {tl_valid_o, tl_write_o, tl_addr_o, tl_count_o, tl_wdata_o} = '0;
    wire unused_tile_port = ^{tl_ready_i, tl_rvalid_i, tl_rdata_i, cmd_bin_i};
  end
  rast_rop #(
    .PixelW(PixelW), .DepthW(DepthW), .MaxSamples(MaxSamples), .SampleLog2W(SampleLog2W), .Lanes(Lanes),
    .PixelsPerCycle(RopPixelsPerCycle), .ClearPixelsPerCycle(RopClearPixelsPerCycle), .AddrW(32), .LenW(RopLenW)
  ) u_rop (
    .clk_i, .rst_ni, .samples_log2_i(samples_log2_q), .fb_width_i(rop_fb_w), .fb_height_i(rop_fb_h),
    .color_base_i(rop_color_base), .depth_base_i(rop_depth_base), .depth_func_i, .depth_write_i,
    .in_valid_i(r_valid), .in_ready_o(r_ready), .in_marker_i(r_in.marker), .in_last_i(r_in.last),
    .in_lanes_i(r_in.lanes), .in_x_i(rop_x), .in_y_i(rop_y), .in_z_i(r_in.z), .in_rgb_i(r_in.rgb),
    .in_mask_i(r_in.mask),
    .cmd_valid_i(rop_cmd_valid), .cmd_ready_o(rop_cmd_ready), .cmd_op_i(rop_cmd_op),
    .cmd_value_i,
    .rd_valid_o(rop_rd_valid), .rd_ready_i(rop_rd_ready), .rd_lanes_o(rop_rd_lanes), .rd_addr_o(rop_rd_addr),
    .rd_len_o(rop_rd_len), .rd_no_depth_o(rop_rd_no_depth), .rd_rvalid_i(rop_rd_rvalid), .rd_rdata_i(rop_rd_rdata),
    .wr_valid_o(rop_wr_valid), .wr_ready_i(rop_wr_ready), .wr_lanes_o(rop_wr_lanes), .wr_addr_o(rop_wr_addr),
    .wr_len_o(rop_wr_len), .wr_fill_o(rop_wr_fill), .wr_be_o(rop_wr_be), .wr_data_o(rop_wr_data),
    .idle_o(rop_idle), .dbg_has_o(rop_has), .dbg_start_o(dbg_rop_start_o), .dbg_done_o(rop_done),
    .dbg_blocked_o(rop_blocked), .hiz_always_i(rop_hiz_always), .hiz_always_next_i(rop_hiz_always_next), .hiz_wr_lanes_o(rop_hiz_wr_lanes),
    .hiz_wr_x_o(rop_hiz_wr_x), .hiz_wr_y_o(rop_hiz_wr_y), .hiz_wr_z_o(rop_hiz_wr_z), .hiz_end_o(rop_hiz_end), .hiz_marker_o(rop_hiz_marker),
    .hiz_clear_o(rop_hiz_clear));

  // ---- Early Z (DepthEarly; rtl/rast_early_z.sv, docs/depth-culling.md "Early Z in the
  // RTL"): the interpolator's beats tested against the stored depth as the texture stage
  // is offered them (its culled lanes are not textured); a tile at the pixel
  // FIFO's head held (ez_wait) while a tile on its pixels or a marker is in flight to the
  // ROP's end. A depth clear's marker ends at its last fill write (rop_done after its
  // take), a pass at its take. ----
  if (DepthEarly != 0) begin : g_early
    logic clr_q;  // a depth clear taken, its writes not yet done
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) clr_q <= 1'b0;
      else if (rop_hiz_clear) clr_q <= 1'b1;
      else if (rop_done) clr_q <= 1'b0;
    end
    // derived: tiles from the interpolator's input to the ROP's end (its pipeline, the
    // texture stage's, the fragment FIFO's and the ROP's access buffer's, a fragment a
    // tile), to a power of two; a full interlock holds the next tile.
    localparam int EzDepth = 1 << $clog2(TileStateDepth + FragmentFifoEntries + 3 +
                                         2 * (RopPixelsPerCycle + Lanes * MaxSamples) + 16);
    rast_early_z #(
      .PixelW(PixelW), .DepthW(DepthW), .MaxSamples(MaxSamples), .SampleLog2W(SampleLog2W), .Lanes(Lanes),
      .TileLog2W(TileLog2W), .InflightDepth(EzDepth)
    ) u_early_z (
      .clk_i, .rst_ni, .tile_log2_i(tile_log2_q), .samples_log2_i(samples_log2_q), .depth_func_i,
      .q_valid_i(p_fifo_valid), .q_marker_i(p_fifo_data.marker), .q_tile_i(p_fifo_data.tile), .q_wait_o(ez_wait),
      .q_take_i(p_fifo_valid && p_fifo_ready),
      .in_valid_i(i_valid && !x_hold), .in_marker_i(i_marker), .in_lanes_i(i_lanes), .in_z_i(i_z),
      .in_mask_i(i_smask), .out_culled_o(ez_culled), .rd_lanes_o(ez_rd_lanes_o), .rd_depth_i(ez_rd_depth_i),
      .rop_end_i(rop_hiz_end), .rop_marker_i((rop_hiz_marker && !rop_hiz_clear) || (clr_q && rop_done)));
    assign ez_rd_x_o = i_x;
    assign ez_rd_y_o = i_y;
  end else begin : g_no_early
    assign ez_rd_x_o = '0;
    assign ez_rd_y_o = '0;
    assign ez_wait = 1'b0;
    assign ez_culled = '0;
    assign ez_rd_lanes_o = '0;
    wire unused_early = ^ez_rd_depth_i;
  end

  // ---- Hi-Z: the bound table, the tile test of every walk lane and the interlock
  // (rast_top_hiz); without a table (HizMode 0) nothing is tested and nothing waits. ----
  if (HizMode != 0) begin : g_hiz
    // Tiles between coarse raster and the ROP's end at most (derived: the tile and pixel
    // FIFOs, the holds and stages, the texture-state FIFO, the fragment FIFO's tiles and
    // the ROP's access buffer, a fragment a tile), to a power of two: never full.
    localparam int InflightDepth = 1 << $clog2(TileFifoDepth + PixelFifoDepth + TileStateDepth + FragmentFifoEntries +
                                               2 * (RopPixelsPerCycle + Lanes * MaxSamples) + 16);
    rast_top_hiz #(
      .CoordW(CoordW), .CoordFrac(CoordFrac), .CoefW(CoefW), .EdgeW(EdgeW), .AreaW(AreaW), .DepthW(DepthW),
      .PixelW(PixelW), .BlockLog2(HizBlockLog2), .MinMax(HizMode == 2 ? 1 : 0), .Blocks(HizBlocks),
      .TileLog2Max(TileLog2Max), .WriteLanes(RopPixelsPerCycle), .Lanes(KLanes), .SampleLog2W(SampleLog2W),
      .InflightDepth(InflightDepth), .SpillBlocks(HizSpillBlocks), .EntryBytesLog2(HizEntryBytesLog2),
      .Lagged(HizLagged)
    ) u_hiz (
      .clk_i, .rst_ni, .fb_width_i, .fb_height_i, .depth_func_i, .samples_log2_i(samples_log2_q),
      .tri_a_i(c_in.edges.a), .tri_b_i(c_in.edges.b), .tri_c_i(c_in.edges.c), .tri_area2_i(c_in.area2),
      .tri_z_i(c_in.attr.z), .tri_origin_i(c_in.origin), .lane_fp_i(k_lane_fp), .lane_wait_o(k_lane_wait),
      .lane_cull_o(k_lane_cull), .lane_accept_o(k_lane_accept),
      .push_i(k_valid && k_ready), .push_marker_i(k_marker), .push_fp_i(k_fp), .push_accept_i(k_hiz_accept),
      .room_o(k_room), .fine_valid_i(f_valid && f_ready), .fine_drop_i(!f_in.marker && !m_valid),
      .rop_end_i(rop_hiz_end), .rop_marker_i(rop_hiz_marker), .rop_always_o(rop_hiz_always), .rop_always_next_o(rop_hiz_always_next),
      .rop_clear_i(rop_hiz_clear),
      .rop_clear_z_i(cmd_value_i[DepthW-1:0]), .wr_lanes_i(rop_hiz_wr_lanes), .wr_x_i(rop_hiz_wr_x),
      .wr_y_i(rop_hiz_wr_y), .wr_z_i(rop_hiz_wr_z), .lane_keep_i(k_lane_keep), .culled_i(k_hiz_culled != '0),
      .base_i(hiz_base_i), .mem_req_valid_o(hiz_mem_req_valid_o), .mem_req_ready_i(hiz_mem_req_ready_i),
      .mem_req_write_o(hiz_mem_req_write_o), .mem_req_flush_o(hiz_mem_req_flush_o), .mem_req_addr_o(hiz_mem_req_addr_o),
      .mem_req_data_o(hiz_mem_req_data_o), .mem_rsp_valid_i(hiz_mem_rsp_valid_i), .mem_rsp_data_i(hiz_mem_rsp_data_i),
      .error_o(dbg_hiz_error_o), .busy_o(hiz_busy));
    assign dbg_hiz_culled_o = k_hiz_culled;
    assign dbg_hiz_accepted_o = k_valid && k_ready && !k_marker && k_hiz_accept;
  end else begin : g_no_hiz
    assign k_lane_wait = '0;
    assign k_lane_cull = '0;
    assign k_lane_accept = '0;
    assign k_room = 1'b1;
    assign rop_hiz_always = 1'b0;
    assign rop_hiz_always_next = 1'b0;
    assign dbg_hiz_culled_o = '0;
    assign dbg_hiz_accepted_o = 1'b0;
    assign {hiz_mem_req_valid_o, hiz_mem_req_write_o, hiz_mem_req_flush_o, hiz_mem_req_addr_o, hiz_mem_req_data_o} = '0;
    assign dbg_hiz_error_o = 1'b0;
    assign hiz_busy = 1'b0;
    wire unused_hiz = ^{k_lane_fp, k_lane_keep, k_hiz_accept, k_hiz_culled, rop_hiz_end, rop_hiz_marker, rop_hiz_clear,
                        rop_hiz_wr_lanes, rop_hiz_wr_x, rop_hiz_wr_y, rop_hiz_wr_z, hiz_base_i, hiz_mem_req_ready_i,
                        hiz_mem_rsp_valid_i, hiz_mem_rsp_data_i};
  end

  // ---- Stage observation (debug ports): setup holds a triangle from the FIFO head or
  // its hold registers; the others hold their rast_hold's transaction. The
  // interpolator is blocked when its pipeline is frozen (the fragment FIFO refuses its
  // beat). The ROP's bit is its own (rast_rop: works this cycle, finishes a tile or a
  // clear, a memory request not taken; its transactions' starts on dbg_rop_start_o, as
  // one may start in the cycle another finishes). Waiting for a credit with a tile at the
  // pixel FIFO's head (cr_wait) is blocked too: the SystemC interpolator blocked in the
  // write of its previous batch.
  assign dbg_has_o     = {rop_has, p_valid || cr_wait, f_valid, c_valid, t_valid || s_busy};
  assign dbg_done_o    = {rop_done, p_valid && p_ready, f_valid && f_ready, c_valid && c_ready, s_done};
  assign dbg_blocked_o = {rop_blocked, (i_valid && !i_ready) || cr_wait, m_valid && !m_ready, k_valid && !k_ready,
                          s_valid && !s_ready};

  // A held transaction shows as valid at the stage's input.
  assign idle_o = t_empty && !s_busy && c_empty && !c_valid && !c_busy && f_empty && !f_valid && !f_busy &&
                  p_empty && !p_valid && !p_busy && ts_empty && !x_busy && r_fifo_empty && rop_idle && tb_idle && !hiz_busy;
endmodule

`default_nettype wire
