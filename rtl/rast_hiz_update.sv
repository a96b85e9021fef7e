// SPDX-License-Identifier: Apache-2.0
// rast_hiz_update: Hi-Z's update rule for one depth write (ref: model/ref/hiz.cpp
// HizTable::write; docs/depth-culling.md "The table: encoding and update rule"), the one
// copy used by the on-chip table (rast_hiz, a lane each) and by the spilled entries'
// update engine (rast_hiz_spill). Combinational.
//
// - An entry, {zmin, zmax, lmin, lmax, mask, count} from the top bit down: the bounds
//   and layer bounds (DepthW bits each), the B^2-bit layer mask (pixel (i, j) of the
//   block at bit j B + i) and its count of set bits (2 BlockLog2 + 1 bits).
// - A write of z at pixel (x, y): zmax = max(zmax, z), zmin = min(zmin, z), lmax =
//   max(lmax, z), lmin = min(lmin, z); a pixel new to the mask sets its bit, and when the
//   count reaches the block's on-screen pixels (the last column and row of blocks are
//   clipped to the framebuffer), zmax = min(zmax, lmax), zmin = max(zmin, lmin) and the
//   layer restarts empty (done_o).
`default_nettype none

module rast_hiz_update #(
  parameter int DepthW    = 24,  // D = raster.depth_bits
  parameter int PixelW    = 14,  // pixel index bits
  parameter int BlockLog2 = 3    // log2 depth.hiz_block
) (
  input  wire logic [PixelW-1:0] fb_width_i,   // framebuffer width, px
  input  wire logic [PixelW-1:0] fb_height_i,  // framebuffer height, px
  input  wire logic [4*DepthW+(1<<(2*BlockLog2))+2*BlockLog2:0] e_i,  // the entry before the write
  input  wire logic [PixelW-1:0] x_i,          // the pixel written
  input  wire logic [PixelW-1:0] y_i,
  input  wire logic [DepthW-1:0] z_i,          // its depth
  output      logic [4*DepthW+(1<<(2*BlockLog2))+2*BlockLog2:0] e_o,  // the entry after it
  output      logic              done_o        // the write completed the block's layer
);
  localparam int B     = 1 << BlockLog2;    // derived: block edge, px
  localparam int MaskW = B * B;             // derived: layer mask bits
  localparam int CntW  = 2 * BlockLog2 + 1; // derived: 0 .. B^2

  // The block's on-screen pixels: its width and height clipped to the framebuffer.
  logic [PixelW:0] rx, ry, wx, wy;  // pixels from the block's left (top) edge to the framebuffer's
  logic [CntW-1:0] full;
  logic [2*BlockLog2-1:0] pix;
  assign rx = {1'b0, fb_width_i} - {1'b0, x_i[PixelW-1:BlockLog2], {BlockLog2{1'b0}}};
  assign ry = {1'b0, fb_height_i} - {1'b0, y_i[PixelW-1:BlockLog2], {BlockLog2{1'b0}}};
  assign wx = rx > (PixelW + 1)'(B) ? (PixelW + 1)'(B) : rx;
  assign wy = ry > (PixelW + 1)'(B) ? (PixelW + 1)'(B) : ry;
  assign full = CntW'(wx * wy);
  assign pix = {y_i[BlockLog2-1:0], x_i[BlockLog2-1:0]};

  always_comb begin
    logic [DepthW-1:0] zmin, zmax, lmin, lmax;
    logic [MaskW-1:0]  mask;
    logic [CntW-1:0]   count;
    {zmin, zmax, lmin, lmax, mask, count} = e_i;
    if (z_i > zmax) zmax = z_i;
    if (z_i < zmin) zmin = z_i;
    if (z_i > lmax) lmax = z_i;
    if (z_i < lmin) lmin = z_i;
    done_o = 1'b0;
    if (!mask[pix]) begin
      mask[pix] = 1'b1;
      count = count + 1'b1;
      if (count == full) begin  // every pixel written during the layer
        if (lmax < zmax) zmax = lmax;
        if (lmin > zmin) zmin = lmin;
        mask = '0;
        count = '0;
        lmin = '1;
        lmax = '0;
        done_o = 1'b1;
      end
    end
    e_o = {zmin, zmax, lmin, lmax, mask, count};
  end
endmodule

`default_nettype wire
