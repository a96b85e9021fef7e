// SPDX-License-Identifier: Apache-2.0
// rast_texture_stage: the texture unit in rast_top, between the interpolator and the
// fragment FIFO's beat packer (docs/texture.md "RTL"; ref: model/ref/texture/texture_unit.cpp
// TextureUnit::shade; model: model/sc/texture.cpp).
//
// - In: the interpolator's beats (Lanes fragments), with the texture state of the tile
//   they belong to (in_tex_*: the triangle's, valid with every non-marker beat). A
//   textured tile's beats hold whole 2x2 quads (fine raster closes the mask): a lane
//   whose sample mask is 0 is a helper pixel, shaded for the derivatives and dropped
//   here (counted on helpers_o in the cycle its beat is taken).
// - An untextured beat or a marker passes straight through (same cycle) once nothing
//   textured is in flight, so the order of fragments and markers is kept.
// - A textured tile's covered fragments, one a cycle (the serialiser), go through
//   rast_texture_address (level 0: mipmaps off), the texel fetch port (tex_req_*: one
//   level sample a request, its 1 or 4 byte addresses; tex_rsp_*: the texels as RGBA8,
//   responses in request order, any number of cycles later), rast_texture_filter
//   (nearest or bilinear) and rast_texture_combine (texenv), and leave on lane 0, one
//   fragment a beat, the tile's last flagged. A fragment is held in the serialiser
//   (pend) until the next covered lane is loaded, so that the tile's last covered
//   fragment carries `last` even where the tile's last beat holds helpers only; a lane
//   known to be the last (the tile's last beat has no covered lane after it) is held
//   flagged and leaves without waiting, while the next tile's first lane loads: a tile
//   costs a cycle per covered fragment and per beat without one.
// - In flight: at most Depth fragments between the serialiser and the output (a ring of
//   their data, read at the request, the filter's input, the combine's input and the
//   output, all in order).
`default_nettype none

module rast_texture_stage #(
  parameter int Lanes      = 4,   // fragments a beat (interp.fragments_per_cycle)
  parameter int PixelW     = 14,  // pixel index bits
  parameter int DepthW     = 24,  // depth bits
  parameter int MaxSamples = 16,  // sample mask bits a pixel
  parameter int TexW       = 28,  // s, t: 1 + I + F of interp.texcoord_format, signed
  parameter int TexFrac    = 20,  // F of interp.texcoord_format
  parameter int WeightBits = 8,   // texture.weight_bits
  parameter int SizeW      = 15,  // a texture side, texels: 1 .. 2^(SizeW-1)
  parameter int AddrW      = 42,  // a texel's byte address
  parameter int Depth      = 16,  // fragments in flight (a power of two)
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
  // The tile's texture state (the triangle's), with every non-marker beat.
  input  wire logic                        in_tex_on_i,   // a texture bound
  input  wire logic                        in_bilinear_i, // texfilter bilinear (else nearest)
  input  wire logic [1:0]                  in_wrap_s_i,   // 0 repeat, 1 clamp, 2 mirror
  input  wire logic [1:0]                  in_wrap_t_i,
  input  wire logic [1:0]                  in_env_i,      // texenv: 0 replace, 1 modulate, 2 decal
  input  wire logic [SizeW-1:0]            in_width_i,    // level 0, texels
  input  wire logic [SizeW-1:0]            in_height_i,
  input  wire logic [AddrW-1:0]            in_base_i,     // level 0's byte address
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
  localparam int PtrW = $clog2(Depth);  // derived
  localparam int LaneW = Lanes > 1 ? $clog2(Lanes) : 1;  // derived: a lane's index
  localparam int PosW = $clog2(Lanes + 1);  // derived: next lane to look at, 0 .. Lanes

  // A fragment in flight.
  typedef struct packed {
    logic                  last;   // the tile's last covered fragment
    logic [PixelW-1:0]     x, y;
    logic [DepthW-1:0]     z;
    logic [23:0]           rgb;
    logic [TexW-1:0]       s, t;
    logic [MaxSamples-1:0] smask;
    logic                  bilinear;
    logic [1:0]            wrap_s, wrap_t, env;
    logic [SizeW-1:0]      width, height;
    logic [AddrW-1:0]      base;
  } frag_t;

  // ---- Serialiser: a textured beat's covered lanes one a cycle, through pend ----
  logic             textured, pass;
  logic [Lanes-1:0] cov, rem;
  logic [PosW-1:0]  pos_q;
  logic [LaneW-1:0] c;      // the next covered lane at or after pos_q
  logic             more;   // a covered lane after c
  logic             pend_valid_q;
  frag_t            pend_q, lane_frag;
  logic             pipe_accept, push, load, pop, pipe_empty;
  logic [PtrW:0]    count;  // fragments in the ring
  assign textured = in_valid_i && !in_marker_i && in_tex_on_i;
  always_comb begin
    logic found;
    found = 1'b0;
    c = '0;
    more = 1'b0;
    for (int j = 0; j < Lanes; j++) begin
      cov[j] = in_lanes_i[j] && in_smask_i[j*MaxSamples +: MaxSamples] != '0;
      rem[j] = cov[j] && PosW'(j) >= pos_q;
      if (rem[j] && found) more = 1'b1;
      if (rem[j] && !found) begin
        found = 1'b1;
        c = LaneW'(j);
      end
    end
  end
  always_comb begin
    lane_frag.last     = !more && in_last_i;
    lane_frag.x        = in_x_i[c*PixelW +: PixelW];
    lane_frag.y        = in_y_i[c*PixelW +: PixelW];
    lane_frag.z        = in_z_i[c*DepthW +: DepthW];
    lane_frag.rgb      = in_rgb_i[c*24 +: 24];
    lane_frag.s        = in_s_i[c*TexW +: TexW];
    lane_frag.t        = in_t_i[c*TexW +: TexW];
    lane_frag.smask    = in_smask_i[c*MaxSamples +: MaxSamples];
    lane_frag.bilinear = in_bilinear_i;
    lane_frag.wrap_s   = in_wrap_s_i;
    lane_frag.wrap_t   = in_wrap_t_i;
    lane_frag.env      = in_env_i;
    lane_frag.width    = in_width_i;
    lane_frag.height   = in_height_i;
    lane_frag.base     = in_base_i;
  end
  logic addr_in_ready;
  assign pipe_accept = addr_in_ready && count != (PtrW + 1)'(Depth);
  // load: a covered lane into pend (pushing the one held), flagged last when it is the
  // tile's last; push: pend into the pipeline (a flagged one at once; else with the next
  // load, or flagged now where the tile's last beat has no covered lane left).
  logic tail;  // the tile's last beat, no covered lane left: pend is the tile's last
  assign tail = textured && rem == '0 && in_last_i && pend_valid_q && !pend_q.last;
  assign load = textured && rem != '0 && (!pend_valid_q || pipe_accept);
  assign push = pend_valid_q && pipe_accept && (load || pend_q.last || tail);
  assign pop  = textured && ((rem != '0 && !more && load) || (rem == '0 && !in_last_i) || (tail && push));
  assign pipe_empty = !pend_valid_q && count == '0;
  assign pass = in_valid_i && (in_marker_i || !in_tex_on_i) && pipe_empty;
  assign in_ready_o = pop || (pass && out_ready_i);
  always_comb begin
    helpers_o = '0;
    if (pop)
      for (int j = 0; j < Lanes; j++) helpers_o = helpers_o + HelpW'(in_lanes_i[j] && !cov[j]);
  end
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      pos_q <= '0;
      pend_valid_q <= 1'b0;
    end else begin
      if (pop) pos_q <= '0;
      else if (load) pos_q <= PosW'(c) + 1'b1;
      if (load) pend_valid_q <= 1'b1;
      else if (push) pend_valid_q <= 1'b0;
    end
  end
  always_ff @(posedge clk_i) begin
    if (load) pend_q <= lane_frag;
  end

  // ---- The ring of fragments in flight: written at push, read in order at the request
  // (req), the filter's input (flt), the combine's input (cmb) and the output (out) ----
  frag_t           ring_q [Depth];
  logic [7:0]      alpha_q [Depth], beta_q [Depth];  // the address unit's weights, by request
  logic [PtrW-1:0] wr_q, req_q, flt_q, cmb_q, out_q;
  frag_t           pushed;
  frag_t           req_e, flt_e, cmb_e, out_e;  // the entries at the read pointers
  logic            req_take, flt_take, cmb_take, out_take;
  always_comb begin
    pushed = pend_q;
    pushed.last = pend_q.last || tail;
  end
  assign req_e = ring_q[req_q];
  assign flt_e = ring_q[flt_q];
  assign cmb_e = ring_q[cmb_q];
  assign out_e = ring_q[out_q];
  wire unused_e = &{1'b0, req_e, flt_e, cmb_e, out_e};  // each pointer reads only some fields
  logic ring_full_q;  // wr_q == out_q with Depth entries
  assign count = (PtrW + 1)'(PtrW'(wr_q - out_q)) + ((PtrW + 1)'(ring_full_q) << PtrW);
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      wr_q <= '0;
      req_q <= '0;
      flt_q <= '0;
      cmb_q <= '0;
      out_q <= '0;
      ring_full_q <= 1'b0;
    end else begin
      if (push) wr_q <= wr_q + 1'b1;
      if (req_take) req_q <= req_q + 1'b1;
      if (flt_take) flt_q <= flt_q + 1'b1;
      if (cmb_take) cmb_q <= cmb_q + 1'b1;
      if (out_take) out_q <= out_q + 1'b1;
      if (push != out_take) ring_full_q <= push && PtrW'(wr_q + 1'b1) == out_q;
    end
  end

  // ---- Address (level 0) ----
  logic                   addr_valid;
  logic [4*(SizeW-1)-1:0] addr_i, addr_j;
  logic [7:0]             addr_alpha, addr_beta;
  rast_texture_address #(.TexW(TexW), .TexFrac(TexFrac), .WeightBits(WeightBits), .SizeW(SizeW), .AddrW(AddrW)) u_address (
    .clk_i, .rst_ni, .in_valid_i(push), .in_ready_o(addr_in_ready), .s_i(pend_q.s), .t_i(pend_q.t),
    .width_i(pend_q.width), .height_i(pend_q.height), .bilinear_i(pend_q.bilinear), .wrap_s_i(pend_q.wrap_s),
    .wrap_t_i(pend_q.wrap_t), .layout_i, .format_i, .base_i(pend_q.base), .out_valid_o(addr_valid),
    .out_ready_i(tex_req_ready_i), .i_o(addr_i), .j_o(addr_j), .alpha_o(addr_alpha), .beta_o(addr_beta),
    .addr_o(tex_req_addr_o));
  wire unused_ij = &{1'b0, addr_i, addr_j};  // the texels' indices: the testbench's view only
  assign tex_req_valid_o = addr_valid;
  assign tex_req_count_o = req_e.bilinear ? 3'd4 : 3'd1;
  assign tex_req_format_o = format_i;
  assign req_take = addr_valid && tex_req_ready_i;
  always_ff @(posedge clk_i) begin
    if (req_take) begin
      alpha_q[req_q] <= addr_alpha;
      beta_q[req_q] <= addr_beta;
    end
  end

  // ---- Filter ----
  logic        flt_in_ready, flt_valid, cmb_in_ready;
  logic [31:0] flt_color;
  rast_texture_filter u_filter (
    .clk_i, .rst_ni, .in_valid_i(tex_rsp_valid_i), .in_ready_o(flt_in_ready), .texels_i(tex_rsp_texels_i),
    .alpha_i(alpha_q[flt_q]), .beta_i(beta_q[flt_q]), .bilinear_i(flt_e.bilinear), .blend_i(1'b0),
    .prev_i('0), .frac_i('0), .out_valid_o(flt_valid), .out_ready_i(cmb_in_ready), .color_o(flt_color));
  assign tex_rsp_ready_o = flt_in_ready;
  assign flt_take = tex_rsp_valid_i && flt_in_ready;

  // ---- Combine ----
  logic        cmb_valid;
  logic [23:0] cmb_color;
  rast_texture_combine u_combine (
    .clk_i, .rst_ni, .in_valid_i(flt_valid), .in_ready_o(cmb_in_ready), .tex_i(flt_color),
    .color_i(cmb_e.rgb), .env_i(cmb_e.env), .out_valid_o(cmb_valid), .out_ready_i(out_ready_i),
    .color_o(cmb_color));
  assign cmb_take = flt_valid && cmb_in_ready;
  assign out_take = cmb_valid && out_ready_i;

  always_ff @(posedge clk_i) begin
    if (push) ring_q[wr_q] <= pushed;
  end

  // ---- Out: a textured fragment on lane 0, or the beat passed through ----
  always_comb begin
    if (cmb_valid) begin
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
