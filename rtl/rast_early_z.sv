// SPDX-License-Identifier: Apache-2.0
// rast_early_z: the early depth test (depth.early; docs/depth-culling.md "Early Z in the
// RTL"), in rast_top: the test between the interpolator's output and the texture stage
// (which textures no culled lane), on the depth the interpolator computed for the ROP (the
// same wires: one formula, ref's), and its interlock at the interpolator's input.
//
// - Each fragment of a beat is tested against the depth stored at its samples (rd_*: the
//   lanes' pixels out, every sample's stored depth back in the same cycle, from the
//   depth surface as the ROP's writes left it). A fragment failing at every covered
//   sample (one sample: sample 0; else its mask) is culled: out_culled_o. A helper pixel
//   (a textured quad's lane with sample mask 0) is neither read nor culled. A culled
//   fragment is not textured (rast_texture_stage) and still goes to the ROP, which makes
//   its depth reads in their place in the stream (the reference's early_depth_cull reads)
//   and, its late test failing on the same stored depth, writes nothing; it is not a
//   shaded fragment (fragments_culled_early). The beat passes on in its cycle (this unit
//   holds no beat; the texture stage latches the flags with the beat it takes).
// - The interlock: a tile at the pixel FIFO's head (q_*) enters the interpolator only once
//   no tile that entered before it on the same pixels (and no marker: a depth clear) is
//   still in flight to the ROP's end (q_wait_o), so when its fragments reach the test the
//   stored depth is the one the ROP will test them against: every decision is the
//   reference's zero-lag early test's (model/ref/pipeline.cpp). rast_hiz_inflight with
//   pixel blocks (BlockLog2 0) keeps the entries, one a tile or marker taken (q_take_i):
//   a tile's footprint (its 2^tile_log2_i square) or every pixel (a marker); the ROP ends
//   the oldest batch (rop_end_i: its last group decided, its writes taken in that cycle)
//   or marker (rop_marker_i: a pass at its take, a depth clear at its last fill write).
//   Held at the input rather than at the test: the interpolator's input is where the
//   timed model's interpolator reads a batch, so both wait for the same end.
// - depth_func_i = always tests nothing (every lane kept) and nothing waits.
`default_nettype none

module rast_early_z #(
  parameter int PixelW        = 14,  // pixel index bits
  parameter int DepthW        = 24,  // raster.depth_bits
  parameter int MaxSamples    = 4,   // largest raster.samples
  parameter int SampleLog2W   = 3,   // samples_log2_i bits
  parameter int Lanes         = 4,   // fragment lanes a beat
  parameter int TileLog2W     = 3,   // tile_log2_i bits
  parameter int InflightDepth = 64   // interlock entries (a power of two)
) (
  input  wire logic                               clk_i,          // core clock
  input  wire logic                               rst_ni,         // asynchronous reset, active low
  input  wire logic [TileLog2W-1:0]               tile_log2_i,    // log2 tile size (static)
  input  wire logic [SampleLog2W-1:0]             samples_log2_i, // log2 raster.samples (static)
  input  wire logic [2:0]                         depth_func_i,   // raster.depth_func as ref DepthFunc (static)
  // The tile or marker at the pixel FIFO's head, and its take into the interpolator.
  input  wire logic                               q_valid_i,
  input  wire logic                               q_marker_i,
  input  wire logic [2*PixelW-1:0]                q_tile_i,       // {y, x} of the tile's corner
  output      logic                               q_wait_o,       // hold it: its pixels are in flight
  input  wire logic                               q_take_i,       // taken (never while q_wait_o)
  // The interpolator's beats offered to the texture stage (observed; they pass on unchanged).
  input  wire logic                               in_valid_i,     // a beat or marker
  input  wire logic                               in_marker_i,
  input  wire logic [Lanes-1:0]                   in_lanes_i,
  input  wire logic [Lanes*DepthW-1:0]            in_z_i,
  input  wire logic [Lanes*MaxSamples-1:0]        in_mask_i,      // lane j sample mask
  output      logic [Lanes-1:0]                   out_culled_o,   // lane j culled early
  output      logic [Lanes-1:0]                   rd_lanes_o,     // lanes whose stored depth is read (the beat's pixels)
  input  wire logic [Lanes*MaxSamples*DepthW-1:0] rd_depth_i,     // lane j sample s stored depth at [(j MaxSamples + s) DepthW]
  input  wire logic                               rop_end_i,      // the ROP ends its oldest batch
  input  wire logic                               rop_marker_i    // ... its oldest marker (after rop_end_i's)
);
  logic on;  // a depth function that reads the stored depth
  assign on = depth_func_i != 3'd7;

  // ---- The lanes' test ----
  logic [MaxSamples-1:0] full_mask;
  logic [Lanes-1:0]      has;  // lanes holding a fragment
  assign full_mask = MaxSamples'(((MaxSamples + 1)'(1) << (1 << samples_log2_i)) - 1'b1);
  for (genvar j = 0; j < Lanes; j++) begin : g_lane
    logic [MaxSamples-1:0] pass, covered;
    for (genvar s = 0; s < MaxSamples; s++) begin : g_sample
      rast_depth_pass #(.DepthW(DepthW)) u_pass (
        .func_i(depth_func_i), .z_i(in_z_i[j*DepthW +: DepthW]),
        .stored_i(rd_depth_i[(j*MaxSamples + s)*DepthW +: DepthW]), .pass_o(pass[s]));
    end
    assign covered = samples_log2_i == '0 ? MaxSamples'(1) : in_mask_i[j*MaxSamples +: MaxSamples] & full_mask;
    assign has[j] = in_lanes_i[j] && in_mask_i[j*MaxSamples +: MaxSamples] != '0;  // not a helper pixel
    assign out_culled_o[j] = on && has[j] && !in_marker_i && (pass & covered) == '0;
  end
  assign rd_lanes_o = in_valid_i && !in_marker_i && on ? has : '0;

  // ---- The interlock ----
  logic [PixelW-1:0] tx, ty, size;
  assign {ty, tx} = q_tile_i;
  assign size = PixelW'(1) << tile_log2_i;
  logic [4*PixelW-1:0] fp;  // {y1, x1, y0, x0}, half-open
  assign fp = {ty + size, tx + size, ty, tx};
  logic wait_q, room;
  logic [3:0] unused_inflight;  // the interlock's Hi-Z accepts, emptiness and markers: not used here
  wire unused = ^unused_inflight;
  assign q_wait_o = on && q_valid_i && ((!q_marker_i && wait_q) || !room);
  rast_hiz_inflight #(.PixelW(PixelW), .BlockLog2(0), .Depth(InflightDepth), .Queries(1)) u_inflight (
    .clk_i, .rst_ni, .push_i(on && q_take_i), .push_all_i(q_marker_i), .push_fp_i(fp), .push_accept_i(1'b0),
    .room_o(room), .fine_valid_i(1'b0), .fine_drop_i(1'b0), .rop_end_i(on && rop_end_i),
    .rop_marker_i(on && rop_marker_i), .rop_accept_o(unused_inflight[0]), .rop_accept_next_o(unused_inflight[1]),
    .q_fp_i(fp), .wait_o(wait_q), .marker_o(unused_inflight[3]), .empty_o(unused_inflight[2]));
endmodule

`default_nettype wire
