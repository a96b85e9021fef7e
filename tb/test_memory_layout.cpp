// SPDX-License-Identifier: Apache-2.0
// The framebuffer's surface layout in memory (ref/memory/surface_layout.h): addresses of a
// few pixels worked by hand, linear and tiled, and sample_at inverting address_of over
// whole surfaces (edge tiles' padding included), and for_each_sample's and for_each_run's
// runs against it.
#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "ref/memory/surface_layout.h"

namespace rastsim {
namespace {

TEST(MemoryLayout, LinearAddressesByHand) {
  // 10 x 6 pixels, one sample, 4 bytes, from 0x1000: (x, y) at 0x1000 + (10 y + x) 4.
  const SurfaceLayout l(FbLayout::Linear, 8, 8, 0x1000, 10, 6, 1, 4);
  EXPECT_EQ(l.address_of(0, 0, 0), 0x1000u);
  EXPECT_EQ(l.address_of(1, 0, 0), 0x1004u);
  EXPECT_EQ(l.address_of(9, 0, 0), 0x1000u + 36);
  EXPECT_EQ(l.address_of(0, 1, 0), 0x1000u + 40);
  EXPECT_EQ(l.address_of(3, 5, 0), 0x1000u + (50 + 3) * 4);
  EXPECT_EQ(l.footprint_bytes(), 240u);
  // 4 samples of 2 bytes: pixel (2, 1) is pixel number 12, its sample 3 at (12 x 4 + 3) x 2.
  const SurfaceLayout m(FbLayout::Linear, 8, 8, 0, 10, 6, 4, 2);
  EXPECT_EQ(m.address_of(2, 1, 3), uint64_t((12 * 4 + 3) * 2));
}

TEST(MemoryLayout, TiledAddressesByHand) {
  // 10 x 6 pixels in 4 x 2 tiles: 3 tiles a row (the third padded to x = 12), 3 rows of
  // tiles; a tile is 8 pixels = 32 bytes.
  const SurfaceLayout t(FbLayout::Tiled, 4, 2, 0, 10, 6, 1, 4);
  EXPECT_EQ(t.address_of(0, 0, 0), 0u);
  EXPECT_EQ(t.address_of(3, 0, 0), 12u);    // end of tile 0's first row
  EXPECT_EQ(t.address_of(0, 1, 0), 16u);    // tile 0, row 1: pixel 4 of the tile
  EXPECT_EQ(t.address_of(4, 0, 0), 32u);    // tile 1
  EXPECT_EQ(t.address_of(9, 1, 0), 64u + (4 + 1) * 4);  // tile 2, row 1, column 1
  EXPECT_EQ(t.address_of(5, 3, 0), 4 * 32u + (4 + 1) * 4);  // tile 4 (row 1 of tiles, column 1)
  EXPECT_EQ(t.address_of(9, 5, 0), 8 * 32u + (4 + 1) * 4);  // tile 8, the last
  EXPECT_EQ(t.footprint_bytes(), 9 * 32u);  // 9 whole tiles, padding included
  // Two samples a pixel lie together: pixel (1, 1) is pixel 5 of tile 0, sample 1 at (5 x 2 + 1) x 4.
  const SurfaceLayout m(FbLayout::Tiled, 4, 2, 0x100, 10, 6, 2, 4);
  EXPECT_EQ(m.address_of(1, 1, 1), 0x100u + (5 * 2 + 1) * 4);
}

// Samples and bytes a sample of 3, 13 and 21 pixels a row (2 and 3 tiles) take
// sample_at's divisions, the powers of two its shifts.
TEST(MemoryLayout, SampleAtInvertsAddressOf) {
  for (FbLayout layout : {FbLayout::Linear, FbLayout::Tiled})
    for (int width : {13, 21})
      for (int samples : {1, 3, 4})
        for (int bpp : {2, 3}) {
          const SurfaceLayout l(layout, 8, 4, 4096, width, 7, samples, bpp);
          int stored = 0;
          for (uint64_t off = 0; off < l.footprint_bytes(); off += uint64_t(bpp)) {
            int x, y, s;
            if (!l.sample_at(off, x, y, s)) continue;
            ++stored;
            ASSERT_EQ(l.offset_of(x, y, s), off) << "offset " << off;
            int x2, y2, s2;
            ASSERT_TRUE(l.sample_at(off + uint64_t(bpp) - 1, x2, y2, s2));  // any byte of the sample
            ASSERT_EQ(x2 * 100 + y2 * 10 + s2, x * 100 + y * 10 + s);
          }
          EXPECT_EQ(stored, width * 7 * samples);  // every sample once, padding skipped
        }
}

using Samples = std::vector<std::array<int, 3>>;

// sample_at on each sample of the bytes [off, off + len) of l (bpp bytes a sample).
Samples samples_at(const SurfaceLayout& l, uint64_t off, uint64_t len, uint64_t bpp) {
  Samples want;
  for (uint64_t o = off - off % bpp; o < off + len; o += bpp) {
    int x, y, s;
    if (l.sample_at(o, x, y, s)) want.push_back({x, y, s});
  }
  return want;
}

// for_each_sample's samples, and for_each_run's runs expanded a sample at a time, against
// sample_at on each sample of every range of a few lengths and offsets (rows, tile rows
// and padding crossed); each run stays on one row inside one tile row (linear: the row)
// and the surface.
TEST(MemoryLayout, ForEachSampleAndRunVisitWhatSampleAtFinds) {
  for (FbLayout layout : {FbLayout::Linear, FbLayout::Tiled})
    for (int samples : {1, 2, 4})
      for (int bpp : {2, 4}) {
        const SurfaceLayout l(layout, 4, 2, 0, 13, 7, samples, bpp);
        for (uint64_t len : {2u, 4u, 16u, 30u, 64u, 100u, 130u})
          for (uint64_t off = 0; off < l.footprint_bytes(); off += 6) {
            const Samples want = samples_at(l, off, len, uint64_t(bpp));
            Samples got, runs;
            l.for_each_sample(off, len, [&](int x, int y, int s) {
              got.push_back({x, y, s});
              return true;
            });
            ASSERT_EQ(got, want) << "offset " << off << " length " << len;
            l.for_each_run(off, len, [&](int x, int y, int s, uint64_t n) {
              EXPECT_GT(n, 0u);
              const int last_x = x + int((uint64_t(s) + n - 1) / uint64_t(samples));  // the run's last pixel
              EXPECT_LT(last_x, 13);
              if (layout == FbLayout::Tiled) {
                EXPECT_EQ(x / 4, last_x / 4) << "run crosses a tile edge";
              }
              for (; n > 0; --n) {
                runs.push_back({x, y, s});
                if (++s == samples) s = 0, ++x;
              }
              return true;
            });
            ASSERT_EQ(runs, want) << "offset " << off << " length " << len;
          }
      }
}

}  // namespace
}  // namespace rastsim
