// SPDX-License-Identifier: Apache-2.0
// Exact coverage of setup + tiled traversal against an independent reference.
//
// The reference takes the three snapped raw vertices and decides each pixel centre
// from the definitions alone: the sign of orient2d (a cross product in __int128) of each
// edge's endpoints and the sample, compared with the sign of the triangle's own
// orientation; a sample exactly on an edge is decided by the edge's geometry (top:
// horizontal with the third vertex below it, y down; left: not horizontal with the
// third vertex to the right of the edge's line), never by EdgeEq's a/b/c or bias.
//
// For thousands of seeded random triangles (slivers to screen-filling, vertices on pixel
// centres, corners, off-grid, horizontal/vertical edges, vertices out in the guard
// band) and every tile size 2..128 it checks:
// - snapping: every vertex snaps to the raw value it was built from;
// - setup outcome: zero area, outside clip (reference covers nothing), accepted;
// - the bounding box is exactly the clipped box of pixel centres inside the vertex hull;
// - pixel_covered over the whole candidate region == reference;
// - traverse_triangle emits exactly the reference set, once each, in tile order, and
//   its fragment count equals the set's size;
// - counters: visited = rejected + accepted + partial = tiles overlapping the bbox;
//   pixel_tests = total area of partial footprints; accepted footprints are fully
//   covered and rejected ones hold no covered pixel (per the reference).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "config/raster_state_config.h"
#include "ref/tri_setup.h"
#include "ref/coarse_raster.h"

namespace rastsim {
namespace {

struct ExactCase {
  const char* name;
  FixedFormat fmt;
  int vw, vh;    // viewport
  int fbw, fbh;  // framebuffer
  bool scissor;
  PixelRect sc;  // scissor rectangle when enabled
  FillRule rule;
  int triangles;
  uint64_t seed;
};

void PrintTo(const ExactCase& c, std::ostream* os) { *os << c.name; }

i128 floor_div(i128 a, i128 b) {  // b > 0
  i128 q = a / b;
  if (q * b > a) --q;
  return q;
}

// orient2d: twice the signed area of (a, b, p); the sign says which side of a->b p is on.
i128 orient(int64_t ax, int64_t ay, int64_t bx, int64_t by, int64_t px, int64_t py) {
  return i128(bx - ax) * (py - ay) - i128(by - ay) * (px - ax);
}

// Does edge i -> j (third vertex k) own samples lying exactly on it?
bool edge_owns(const int64_t* x, const int64_t* y, int i, int j, int k, FillRule rule) {
  if (rule == FillRule::Inclusive) return true;
  if (rule == FillRule::Exclusive) return false;
  const bool top_left = rule == FillRule::TopLeft;
  if (y[i] == y[j]) {
    // Horizontal: top when the third vertex is below (larger y), bottom when above.
    return top_left ? y[k] > y[i] : y[k] < y[i];
  }
  // Sign of (x_k - x on the edge's line at height y_k): the third vertex is right of
  // the line (so this is a left edge) when positive.
  const i128 num = i128(x[k] - x[i]) * (y[j] - y[i]) - i128(x[j] - x[i]) * (y[k] - y[i]);
  const bool third_right = (num > 0) == (y[j] > y[i]);
  return top_left ? third_right : !third_right;
}

// Reference coverage of one raw sample.
bool ref_covered(const int64_t* x, const int64_t* y, int64_t sx, int64_t sy, FillRule rule) {
  const i128 area = orient(x[0], y[0], x[1], y[1], x[2], y[2]);
  if (area == 0) return false;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    const i128 d = orient(x[i], y[i], x[j], y[j], sx, sy);
    if (d == 0) {
      if (!edge_owns(x, y, i, j, k, rule)) return false;
    } else if ((d > 0) != (area > 0)) {
      return false;
    }
  }
  return true;
}

class RasterExact : public ::testing::TestWithParam<ExactCase> {};

// A random triangle in raw coordinates relative to the origin, within [lo, hi].
struct RawTri { int64_t x[3], y[3]; };

RawTri random_triangle(std::mt19937_64& rng, const ExactCase& c, const PixelRect& clip, int64_t ox,
                       int64_t oy) {
  const int F = c.fmt.frac_bits;
  const int64_t one = int64_t{1} << F, lo = c.fmt.raw_min(), hi = c.fmt.raw_max();
  auto uni = [&](int64_t a, int64_t b) { return a + int64_t(rng() % uint64_t(b - a + 1)); };
  auto clampr = [&](int64_t v) { return std::clamp(v, lo, hi); };
  // Centre of the triangle: inside the clip rectangle plus a margin of a quarter of it.
  const int64_t mx = std::max(clip.x1 - clip.x0, 4) / 4, my = std::max(clip.y1 - clip.y0, 4) / 4;
  const int64_t cx = clampr(uni((clip.x0 - ox - mx) * one, (clip.x1 - ox + mx) * one));
  const int64_t cy = clampr(uni((clip.y0 - oy - my) * one, (clip.y1 - oy + my) * one));
  // Size: 2^u LSBs; u mostly from a quarter pixel to the whole coordinate range, and
  // sometimes from a single LSB (sub-pixel triangles, most of which cover no centre).
  const int range_bits = c.fmt.int_bits + F + 1;
  auto size_bits = [&] {
    const int from = (rng() % 4 == 0) ? 0 : std::max(0, F - 2);
    return from + int(rng() % uint64_t(range_bits - from));
  };
  RawTri t;
  const int kind = int(rng() % 10);
  if (kind == 0) {
    // Anywhere in the format's range (mostly screen-filling or clipped away).
    for (int i = 0; i < 3; ++i) { t.x[i] = uni(lo, hi); t.y[i] = uni(lo, hi); }
  } else if (kind == 1) {
    // Sliver: the third vertex a few LSBs off the line through the other two.
    const int64_t s = int64_t{1} << size_bits();
    for (int i = 0; i < 2; ++i) { t.x[i] = clampr(cx + uni(-s, s)); t.y[i] = clampr(cy + uni(-s, s)); }
    const int64_t num = uni(0, 1024);
    t.x[2] = clampr(t.x[0] + int64_t(i128(t.x[1] - t.x[0]) * num / 1024) + uni(-3, 3));
    t.y[2] = clampr(t.y[0] + int64_t(i128(t.y[1] - t.y[0]) * num / 1024) + uni(-3, 3));
  } else {
    const int64_t s = int64_t{1} << size_bits();
    for (int i = 0; i < 3; ++i) { t.x[i] = clampr(cx + uni(-s, s)); t.y[i] = clampr(cy + uni(-s, s)); }
  }
  // Put vertices on pixel centres or corners (x and y independently) often.
  for (int i = 0; i < 3; ++i) {
    for (int64_t* v : {&t.x[i], &t.y[i]}) {
      const int r = int(rng() % 10);
      if (r < 3) *v = clampr(int64_t(floor_div(*v, one)) * one + one / 2);  // centre
      else if (r < 6) *v = clampr(int64_t(floor_div(*v, one)) * one);       // corner
    }
  }
  // Axis-aligned edges: copy one coordinate between two vertices.
  const int r = int(rng() % 6);
  const int a = int(rng() % 3), b = (a + 1 + int(rng() % 2)) % 3;
  if (r == 0) t.y[b] = t.y[a];
  if (r == 1) t.x[b] = t.x[a];
  if (r == 2) { t.y[b] = t.y[a]; t.x[(3 - a - b)] = t.x[a]; }  // a right angle
  return t;
}

TEST_P(RasterExact, CoverageMatchesReferenceForEveryTileSize) {
  const ExactCase& c = GetParam();
  SCOPED_TRACE("seed " + std::to_string(c.seed));
  std::mt19937_64 rng(c.seed);
  const int F = c.fmt.frac_bits;
  const int64_t one = int64_t{1} << F, half = one / 2;
  const int64_t ox = c.vw / 2, oy = c.vh / 2;  // viewport centre, rounded down

  RasterState st = raster_state_from_config(Config{});
  st.coord_format = c.fmt;
  st.fill_rule = c.rule;
  st.out_of_range = OutOfRange::Cull;
  st.fb_width = c.fbw;
  st.fb_height = c.fbh;
  st.viewport_width = c.vw;
  st.viewport_height = c.vh;
  st.scissor_enabled = c.scissor;
  st.scissor = c.sc;
  // Pixels a triangle may touch: viewport within the framebuffer, within the scissor.
  int cx0 = 0, cy0 = 0, cx1 = std::min(c.vw, c.fbw), cy1 = std::min(c.vh, c.fbh);
  if (c.scissor) {
    cx0 = std::max(cx0, c.sc.x0); cy0 = std::max(cy0, c.sc.y0);
    cx1 = std::min(cx1, c.sc.x1); cy1 = std::min(cy1, c.sc.y1);
  }

  uint64_t accepted = 0, zero_area = 0, outside = 0, fragments_total = 0, out_of_range = 0;
  uint64_t on_edge = 0;  // samples exactly on an edge's line: where the fill rule decides
  int failures = 0;
  std::vector<uint8_t> ref, hits;
  for (int n = 0; n < c.triangles && failures < 5; ++n) {
    RawTri rt = random_triangle(rng, c, PixelRect{cx0, cy0, cx1, cy1}, ox, oy);
    const bool push_out = rng() % 50 == 0;  // one vertex one LSB past the range
    if (push_out) rt.x[rng() % 3] = (rng() % 2) ? c.fmt.raw_max() + 1 : c.fmt.raw_min() - 1;
    std::array<SceneVertex, 3> v;
    for (int i = 0; i < 3; ++i) {
      // Exact scene position plus an offset below half an LSB, which snapping removes.
      const int sh = 64 - F;
      auto pos = [&](int64_t origin, int64_t raw) {
        const i128 lim = (i128(1) << (sh - 1)) - 1;
        const i128 off = (rng() % 2) ? 0 : i128(rng() % uint64_t(lim)) * ((rng() % 2) ? 1 : -1);
        return Q64{(i128(origin) << 64) + (i128(raw) << sh) + off};
      };
      v[i].x = pos(ox, rt.x[i]);
      v[i].y = pos(oy, rt.y[i]);
    }
    std::string where = "triangle " + std::to_string(n) + " raw (" + std::to_string(rt.x[0]) + "," +
                        std::to_string(rt.y[0]) + ") (" + std::to_string(rt.x[1]) + "," +
                        std::to_string(rt.y[1]) + ") (" + std::to_string(rt.x[2]) + "," +
                        std::to_string(rt.y[2]) + ")";
    SCOPED_TRACE(where);
    SetupTriangle t;
    const SetupOutcome out = setup_triangle(v, st, SourceLoc{"gen", n}, t);
    if (push_out) {
      EXPECT_EQ(out, SetupOutcome::CulledOutOfRange);
      ++out_of_range;
      continue;
    }
    ASSERT_NE(out, SetupOutcome::CulledOutOfRange);
    for (int i = 0; i < 3; ++i) {
      ASSERT_EQ(t.x[i], rt.x[i]);
      ASSERT_EQ(t.y[i], rt.y[i]);
    }
    const i128 area = orient(rt.x[0], rt.y[0], rt.x[1], rt.y[1], rt.x[2], rt.y[2]);
    if (area == 0) {
      EXPECT_EQ(out, SetupOutcome::CulledZeroArea);
      ++zero_area;
      continue;
    }

    // Reference over a generous candidate region: one pixel beyond the vertices' box,
    // clipped (a pixel whose centre is outside the hull's box cannot be covered).
    const int64_t xmin = std::min({rt.x[0], rt.x[1], rt.x[2]}), xmax = std::max({rt.x[0], rt.x[1], rt.x[2]});
    const int64_t ymin = std::min({rt.y[0], rt.y[1], rt.y[2]}), ymax = std::max({rt.y[0], rt.y[1], rt.y[2]});
    const int rx0 = int(std::max<i128>(cx0, ox + floor_div(xmin, one) - 1));
    const int rx1 = int(std::min<i128>(cx1, ox + floor_div(xmax, one) + 2));
    const int ry0 = int(std::max<i128>(cy0, oy + floor_div(ymin, one) - 1));
    const int ry1 = int(std::min<i128>(cy1, oy + floor_div(ymax, one) + 2));
    const int rw = std::max(0, rx1 - rx0), rh = std::max(0, ry1 - ry0);
    ref.assign(size_t(rw) * rh, 0);
    uint64_t ref_count = 0;
    for (int py = ry0; py < ry1; ++py) {
      const int64_t sy = (py - oy) * one + half;
      for (int px = rx0; px < rx1; ++px) {
        const int64_t sx = (px - ox) * one + half;
        for (int i = 0; i < 3; ++i)
          on_edge += orient(rt.x[i], rt.y[i], rt.x[(i + 1) % 3], rt.y[(i + 1) % 3], sx, sy) == 0;
        if (ref_covered(rt.x, rt.y, sx, sy, c.rule)) {
          ref[size_t(py - ry0) * rw + (px - rx0)] = 1;
          ++ref_count;
        }
      }
    }
    // The bbox setup should compute: pixels whose centres lie within [min, max], clipped.
    int bx0 = cx1, bx1 = cx0, by0 = cy1, by1 = cy0;
    for (int px = rx0; px < rx1; ++px) {
      const int64_t sx = (px - ox) * one + half;
      if (sx >= xmin && sx <= xmax) { bx0 = std::min(bx0, px); bx1 = std::max(bx1, px + 1); }
    }
    for (int py = ry0; py < ry1; ++py) {
      const int64_t sy = (py - oy) * one + half;
      if (sy >= ymin && sy <= ymax) { by0 = std::min(by0, py); by1 = std::max(by1, py + 1); }
    }
    if (bx0 >= bx1 || by0 >= by1) {
      EXPECT_EQ(out, SetupOutcome::CulledOutsideClip);
      EXPECT_EQ(ref_count, 0u);
      ++outside;
      continue;
    }
    if (out != SetupOutcome::Accepted) {
      ADD_FAILURE() << "setup outcome " << to_string(out) << ", expected accepted";
      ++failures;
      continue;
    }
    ++accepted;
    fragments_total += ref_count;
    EXPECT_EQ(t.bbox, (PixelRect{bx0, by0, bx1, by1}));

    // Brute force over the candidate region with the model's own per-pixel test.
    bool brute_ok = true;
    for (int py = ry0; py < ry1 && brute_ok; ++py)
      for (int px = rx0; px < rx1; ++px)
        if (pixel_covered(t, px, py, F) != bool(ref[size_t(py - ry0) * rw + (px - rx0)])) {
          ADD_FAILURE() << "pixel_covered(" << px << ", " << py << ") disagrees with the reference";
          brute_ok = false;
          ++failures;
          break;
        }

    for (int ts : {2, 4, 8, 16, 32, 64, 128}) {
      SCOPED_TRACE("tile " + std::to_string(ts));
      TraversalCounters cnt;
      hits.assign(ref.size(), 0);
      uint64_t emitted = 0, stray = 0, disorder = 0;
      int64_t last_key = -1;
      traverse_triangle(t, ts, F, cnt, [&](int px, int py) {
        ++emitted;
        if (px < rx0 || px >= rx1 || py < ry0 || py >= ry1) { ++stray; return; }
        ++hits[size_t(py - ry0) * rw + (px - rx0)];
        // Row-major tiles, row-major pixels within a tile: a strictly increasing key.
        const int64_t key = ((int64_t(py / ts) * 4096 + px / ts) * ts + py % ts) * ts + px % ts;
        if (key <= last_key) ++disorder;
        last_key = key;
      });
      uint64_t missing = 0, extra = 0, dup = 0;
      for (size_t i = 0; i < ref.size(); ++i) {
        if (ref[i] && hits[i] == 0) ++missing;
        if (!ref[i] && hits[i]) ++extra;
        if (hits[i] > 1) ++dup;
      }
      if (missing || extra || dup || stray || disorder) {
        ADD_FAILURE() << "traversal: " << missing << " missing, " << extra << " extra, " << dup
                      << " duplicated, " << stray << " outside, " << disorder << " out of order";
        ++failures;
      }
      EXPECT_EQ(cnt.fragments, ref_count);
      EXPECT_EQ(emitted, ref_count);

      // Tiles overlapping the bbox, enumerated and clipped here.
      uint64_t tiles = 0, rej = 0, acc = 0, part = 0, part_area = 0;
      for (int ty = by0 / ts; ty <= (by1 - 1) / ts; ++ty) {
        for (int tx = bx0 / ts; tx <= (bx1 - 1) / ts; ++tx) {
          ++tiles;
          const PixelRect fp{std::max(tx * ts, bx0), std::max(ty * ts, by0), std::min((tx + 1) * ts, bx1),
                             std::min((ty + 1) * ts, by1)};
          int64_t covered = 0;
          for (int py = fp.y0; py < fp.y1; ++py)
            for (int px = fp.x0; px < fp.x1; ++px) covered += ref[size_t(py - ry0) * rw + (px - rx0)];
          const int64_t area = int64_t(fp.x1 - fp.x0) * (fp.y1 - fp.y0);
          switch (classify_tile(t, fp, F)) {
            case TileClass::Rejected:
              ++rej;
              EXPECT_EQ(covered, 0) << "rejected tile " << tx << "," << ty << " has covered pixels";
              break;
            case TileClass::Accepted:
              ++acc;
              EXPECT_EQ(covered, area) << "accepted tile " << tx << "," << ty << " is not fully covered";
              break;
            case TileClass::Partial:
              ++part;
              part_area += uint64_t(area);
              break;
          }
        }
      }
      EXPECT_EQ(cnt.tiles_visited, tiles);
      EXPECT_EQ(cnt.tiles_visited, cnt.tiles_rejected + cnt.tiles_accepted + cnt.tiles_partial);
      EXPECT_EQ(cnt.tiles_rejected, rej);
      EXPECT_EQ(cnt.tiles_accepted, acc);
      EXPECT_EQ(cnt.tiles_partial, part);
      EXPECT_EQ(cnt.pixel_tests, part_area);
    }
  }
  // The generator must reach every outcome it aims at, or the test proves little.
  std::printf("[ %s ] %llu accepted (%llu fragments, %llu on-edge samples), %llu zero-area, "
              "%llu outside clip, %llu out of range\n",
              c.name, (unsigned long long)accepted, (unsigned long long)fragments_total,
              (unsigned long long)on_edge, (unsigned long long)zero_area, (unsigned long long)outside,
              (unsigned long long)out_of_range);
  EXPECT_GT(accepted, uint64_t(c.triangles) / 3);
  EXPECT_GT(fragments_total, accepted);
  EXPECT_GT(on_edge, accepted / 4);
  EXPECT_GT(zero_area, 0u);
  EXPECT_GT(outside, 0u);
}

// Viewport sizes: max_viewport_extent = 2^(I+1) - 2 is the largest that fits.
INSTANTIATE_TEST_SUITE_P(
    Formats, RasterExact,
    ::testing::Values(
        ExactCase{"S7F16Max254", {7, 16}, 254, 254, 254, 254, false, {}, FillRule::TopLeft, 3000, 0xe1a01},
        ExactCase{"S7F16Odd127Scissor", {7, 16}, 127, 127, 160, 140, true, {9, 20, 101, 93}, FillRule::TopLeft,
                  3000, 0xe1a02},
        ExactCase{"S7F16ViewportBeyondFb", {7, 16}, 200, 180, 150, 120, false, {}, FillRule::TopLeft, 2000,
                  0xe1a03},
        ExactCase{"S15F8", {15, 8}, 320, 200, 320, 200, false, {}, FillRule::TopLeft, 2000, 0xe1a04},
        ExactCase{"S10F4", {10, 4}, 200, 150, 200, 150, false, {}, FillRule::TopLeft, 3000, 0xe1a05},
        ExactCase{"S10F4BottomRight", {10, 4}, 120, 90, 120, 90, false, {}, FillRule::BottomRight, 2000, 0xe1a06},
        ExactCase{"S10F4Inclusive", {10, 4}, 120, 90, 120, 90, false, {}, FillRule::Inclusive, 2000, 0xe1a07},
        ExactCase{"S10F4Exclusive", {10, 4}, 120, 90, 120, 90, false, {}, FillRule::Exclusive, 2000, 0xe1a08},
        ExactCase{"S3F4Max14", {3, 4}, 14, 14, 14, 14, false, {}, FillRule::TopLeft, 6000, 0xe1a09},
        ExactCase{"S3F4Small9x5", {3, 4}, 9, 5, 16, 16, false, {}, FillRule::TopLeft, 4000, 0xe1a0a},
        ExactCase{"S2F1Max6", {2, 1}, 6, 6, 6, 6, false, {}, FillRule::TopLeft, 6000, 0xe1a0b},
        ExactCase{"S14F16Widest", {14, 16}, 300, 300, 300, 300, false, {}, FillRule::TopLeft, 1500, 0xe1a0c}),
    [](const ::testing::TestParamInfo<ExactCase>& i) { return std::string(i.param.name); });

}  // namespace
}  // namespace rastsim
