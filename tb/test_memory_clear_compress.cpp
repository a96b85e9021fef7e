// SPDX-License-Identifier: Apache-2.0
// Fast clear and depth plane compression (ref/memory/surface_client.h,
// depth_compression.h), worked by hand:
// - a full-screen clear: 0 bytes and one flag a block with fast clear, W H bpp without;
// - the first write of a flagged block: no fill read, and at write-back the line plus the
//   rest of each block it touches (the clear value) written;
// - an 8 x 8 block of depths on one plane: 50 bytes; a block off the plane: raw.
#include <gtest/gtest.h>

#include "ref/framebuffer.h"
#include "ref/memory/depth_compression.h"
#include "ref/memory/rop_memory.h"

namespace rastsim {
namespace {

MemoryParams params(bool fast_clear, DepthCompression compression) {
  MemoryParams p;
  p.enabled = true;
  p.layout = FbLayout::Linear;
  p.color_base = 0;
  p.depth_base = 1 << 20;
  p.color_cache = {1024, 4, 64};
  p.depth_cache = {1024, 4, 64};
  p.fast_clear = fast_clear;
  p.block_width = p.block_height = 8;
  p.depth_compression = compression;
  return p;
}

TEST(MemoryFastClear, FullScreenClearBytes) {
  const Framebuffer fb(64, 32);
  for (bool fast : {false, true}) {
    RopMemory m(params(fast, DepthCompression::None), fb, 24);
    m.clear_color();
    m.clear_depth();
    m.finish();
    const MemoryStats s = m.stats();
    // 64 x 32 pixels = 8 x 4 blocks of 8 x 8; colour 4 bytes, 24-bit depth in 4 bytes.
    EXPECT_EQ(s.rop_color.bytes_written, fast ? 0u : 64u * 32 * 4);
    EXPECT_EQ(s.rop_depth.bytes_written, fast ? 0u : 64u * 32 * 4);
    EXPECT_EQ(s.rop_color.fast_clear_blocks + s.rop_depth.fast_clear_blocks, fast ? 64u : 0u);
    EXPECT_EQ(s.rop_color.bytes_read + s.rop_depth.bytes_read, 0u);
  }
  // 16-bit depth: 2 bytes a sample.
  RopMemory m(params(false, DepthCompression::None), fb, 16);
  m.clear_depth();
  EXPECT_EQ(m.stats().rop_depth.bytes_written, 64u * 32 * 2);
}

TEST(MemoryFastClear, PartlyWrittenBlocksAreMaterialisedAtWriteBack) {
  // 16 x 16 linear colour, 64-byte lines = one row of 16 pixels, which crosses blocks 0
  // and 1 (8 x 8 pixels, 256 bytes each).
  const Framebuffer fb(16, 16);
  RopMemory m(params(true, DepthCompression::None), fb, 24);
  m.clear_color();          // 4 blocks flagged, 0 bytes
  m.color_write(0, 0, 0);   // miss on row 0: every sample in flagged blocks, no read
  m.color_write(0, 8, 0);   // miss on row 8 (blocks 2, 3): no read
  m.finish();               // two dirty lines written back: 2 x 64 bytes, and each
                            // materialises its two blocks: 4 x (256 - 32) = 896 bytes
  const MemoryClientStats& c = m.stats().rop_color;
  EXPECT_EQ(c.misses, 2u);
  EXPECT_EQ(c.bytes_read, 0u);
  EXPECT_EQ(c.clear_fill_bytes, 896u);
  EXPECT_EQ(c.bytes_written, 128u + 896u);
  // After materialising, the blocks are in memory: a fill reads again.
  RopMemory n(params(true, DepthCompression::None), fb, 24);
  n.clear_color();
  n.color_write(0, 0, 0);
  n.color.write_back_all();
  n.color.access(0, 1, 0, false);  // row 1: blocks 0 and 1, no longer flagged
  EXPECT_EQ(n.stats().rop_color.bytes_read, 64u);
}

TEST(MemoryCompression, PlaneBlockSizeByHand) {
  // D = 24: anchor 24 + two slopes of 25 + 64 residuals of 5 = 394 bits -> 50 bytes.
  EXPECT_EQ(plane_block_bytes(8, 8, 1, 24), 50u);
  // D = 16, 4 samples: 16 + 34 + 256 x 5 = 1330 bits -> 167 bytes.
  EXPECT_EQ(plane_block_bytes(8, 8, 4, 16), 167u);
}

TEST(MemoryCompression, ABlockOnOnePlaneIsWrittenCompressed) {
  // One 8 x 8 block, z = 1000 + 3 x + 5 y: residuals 0; the depth cache's line is the
  // block (8 x 8 x 4 = 256 bytes).
  Framebuffer fb(8, 8);
  RopMemory m(params(false, DepthCompression::Plane), fb, 24);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      fb.set_depth(x, y, 0, uint32_t(1000 + 3 * x + 5 * y));
      m.depth_write(x, y, 0);
    }
  m.finish();
  const MemoryClientStats& d = m.stats().rop_depth;
  EXPECT_EQ(d.misses, 1u);
  EXPECT_EQ(d.bytes_read, 256u);  // not compressed before: a raw fill
  EXPECT_EQ(d.bytes_written, 50u);
  EXPECT_EQ(d.compressed_bytes, 50u);
  EXPECT_EQ(d.compressed_blocks, 1u);
  // Residuals up to +-15/-16 still fit; one of 16 does not: the block is written raw.
  fb.set_depth(7, 7, 0, uint32_t(1000 + 21 + 35 + 15));
  EXPECT_TRUE(fits_plane(8, 8, 1, [&](int i, int j, int s) { return fb.depth_at(i, j, s); }));
  fb.set_depth(7, 7, 0, uint32_t(1000 + 21 + 35 + 16));
  EXPECT_FALSE(fits_plane(8, 8, 1, [&](int i, int j, int s) { return fb.depth_at(i, j, s); }));
  RopMemory raw(params(false, DepthCompression::Plane), fb, 24);
  raw.depth_write(7, 7, 0);
  raw.finish();
  EXPECT_EQ(raw.stats().rop_depth.bytes_written, 256u);
  EXPECT_EQ(raw.stats().rop_depth.compressed_bytes, 0u);
}

TEST(MemoryCompression, ACompressedBlockIsReadCompressed) {
  Framebuffer fb(8, 8);
  fb.clear_depth(77);
  RopMemory m(params(false, DepthCompression::Plane), fb, 24);
  m.clear_depth();  // a constant: one block of 50 bytes written
  EXPECT_EQ(m.stats().rop_depth.bytes_written, 50u);
  m.depth_read(3, 3, 0);  // the fill reads the 50 bytes
  EXPECT_EQ(m.stats().rop_depth.bytes_read, 50u);
}

}  // namespace
}  // namespace rastsim
