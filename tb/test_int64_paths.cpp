// SPDX-License-Identifier: Apache-2.0
// The 64-bit paths against the exact i128 ones (docs/fixed-point.md, "64-bit paths"):
// on thousands of seeded random triangles per shipped config, and per format at the
// edges of the range (the widest format with edges64, s15.15, and vertices at the
// format's extreme raw values), the int64 fine raster, the int64 plane interpolation
// and PlaneStepper must give exactly what the i128 code gives. The i128 side is the same
// triangle with edges64 cleared, which takes the wide path everywhere. A quarter of the
// random triangles have flat attributes (PlaneStepper's no-division case).
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "config/raster_state_config.h"
#include "ref/fine_raster.h"
#include "ref/interpolate.h"
#include "ref/tri_setup.h"

namespace rastsim {
namespace {

struct Emitted {
  int x, y;
  uint32_t m;
  bool operator==(const Emitted&) const = default;
};

template <class T>
std::vector<Emitted> walk(const SetupTriangle& t, const PixelRect& fp, int F) {
  std::vector<Emitted> out;
  auto emit = [&](int x, int y, uint32_t m) { out.push_back({x, y, m}); };
  fine_raster_walk<T>(t, fp, F, emit);
  return out;
}

// A vertex at raw (rx, ry) of the format, relative to the state's origin, as an exact Q64.
SceneVertex vertex_at(const RasterState& st, int64_t rx, int64_t ry, std::mt19937_64& rng) {
  const int F = st.coord_format.frac_bits;
  SceneVertex v;
  v.x.q = (i128(st.origin_x()) << Q64::kFracBits) + (i128(rx) << (Q64::kFracBits - F));
  v.y.q = (i128(st.origin_y()) << Q64::kFracBits) + (i128(ry) << (Q64::kFracBits - F));
  v.z = double(rng() % 1000001) / 1000000.0;
  v.r = uint8_t(rng()), v.g = uint8_t(rng()), v.b = uint8_t(rng());
  return v;
}

struct Counts {
  int triangles = 0, stepped = 0, fast_points = 0;
};

// One random triangle: small near the viewport (most), or with vertices anywhere in the
// format's range, half of those at its extreme raw values.
void check_one(const RasterState& st, std::mt19937_64& rng, Counts& n) {
  const FixedFormat& fmt = st.coord_format;
  const int F = fmt.frac_bits;
  auto uni = [&](int64_t lo, int64_t hi) { return lo + int64_t(rng() % uint64_t(hi - lo + 1)); };
  std::array<SceneVertex, 3> v;
  const int kind = int(rng() % 4);
  const int64_t half_w = int64_t(st.viewport_width / 2) << F, half_h = int64_t(st.viewport_height / 2) << F;
  const int64_t cx = uni(-half_w, half_w), cy = uni(-half_h, half_h);
  const int64_t r = kind == 0 ? (int64_t(1) << F) * 2 : (int64_t(1) << F) * 64;
  for (auto& vx : v) {
    int64_t x, y;
    if (kind == 3) {  // anywhere, extremes included
      const auto pick = [&] {
        switch (rng() % 3) {
          case 0: return fmt.raw_min();
          case 1: return fmt.raw_max();
          default: return uni(fmt.raw_min(), fmt.raw_max());
        }
      };
      x = pick(), y = pick();
    } else {
      x = std::clamp(cx + uni(-r, r), fmt.raw_min(), fmt.raw_max());
      y = std::clamp(cy + uni(-r, r), fmt.raw_min(), fmt.raw_max());
    }
    vx = vertex_at(st, x, y, rng);
  }
  // A quarter with some attributes flat (the same at the three vertices), which
  // PlaneStepper sets once and never divides (interpolate.h).
  if (rng() % 4 == 0) {
    const unsigned flat = unsigned(rng() % 16);
    for (auto& vx : v) {
      if (flat & 1) vx.z = v[0].z;
      if (flat & 2) vx.r = v[0].r;
      if (flat & 4) vx.g = v[0].g;
      if (flat & 8) vx.b = v[0].b;
    }
  }
  SetupTriangle t;
  if (setup_triangle(v, st, SourceLoc{"random", 1}, t) != SetupOutcome::Accepted) return;
  ++n.triangles;
  ASSERT_EQ(t.edges64, edges_fit_int64(fmt));
  SetupTriangle wide = t;
  wide.edges64 = false;
  // A footprint of at most 24 x 24 pixels somewhere in the box (huge boxes included).
  const int fx = t.bbox.x0 + int(rng() % uint64_t(t.bbox.x1 - t.bbox.x0));
  const int fy = t.bbox.y0 + int(rng() % uint64_t(t.bbox.y1 - t.bbox.y0));
  const PixelRect fp = PixelRect{fx, fy, fx + 24, fy + 24}.intersect(t.bbox);
  const auto cover = walk<i128>(wide, fp, F);
  if (t.edges64) {
    ASSERT_EQ(walk<int64_t>(t, fp, F), cover);
  }
  // Plane interpolation at every pixel of the footprint (covered or not: msaa centres
  // outside the triangle are extrapolated) and at the covered pixels' samples.
  const SamplePattern& pat = sample_pattern(t.samples, F);
  for (int py = fp.y0; py < fp.y1; ++py)
    for (int px = fp.x0; px < fp.x1; ++px) {
      const int64_t sx = t.sample_x(px, F), sy = t.sample_y(py, F);
      ASSERT_EQ(interpolate_plane_at(t, px, py, sx, sy), interpolate_plane_at(wide, px, py, sx, sy))
          << "pixel " << px << "," << py;
      n.fast_points += t.edges64 && t.area2 <= t.w64_limit;
    }
  for (const Emitted& e : cover)
    for (int s = 0; s < t.samples; ++s) {
      const int64_t sx = t.sample_x(e.x, F) + pat.dx[size_t(s)], sy = t.sample_y(e.y, F) + pat.dy[size_t(s)];
      ASSERT_EQ(interpolate_plane_at(t, e.x, e.y, sx, sy), interpolate_plane_at(wide, e.x, e.y, sx, sy));
    }
  // PlaneStepper over the covered centres in walk order (one sample only).
  PlaneStepper step(t, F);
  if (step.active()) {
    ++n.stepped;
    for (const Emitted& e : cover) ASSERT_EQ(step.at(e.x, e.y), interpolate_plane(wide, e.x, e.y, F));
  }
}

RasterState state_of(const std::string& config) {
  Config cfg;
  cfg.load_file(std::string(RASTSIM_SOURCE_DIR) + "/configs/" + config + ".toml");
  RasterState st = raster_state_from_config(cfg);
  st.out_of_range = OutOfRange::Cull;
  st.cull = CullMode::None;
  return st;
}

void run_many(RasterState st, uint64_t seed, int triangles) {
  std::mt19937_64 rng(seed);
  SCOPED_TRACE("format " + st.coord_format.name() + ", samples " + std::to_string(st.samples) + ", seed " +
               std::to_string(seed));
  Counts n;
  for (int k = 0; k < triangles && !::testing::Test::HasFatalFailure(); ++k) check_one(st, rng, n);
  EXPECT_GT(n.triangles, triangles / 2);
  if (edges_fit_int64(st.coord_format)) {
    EXPECT_GT(n.fast_points, 0);
    if (st.samples == 1) {
      EXPECT_GT(n.stepped, triangles / 10);  // small ones: area2 <= w64_limit (2^37.4 at 24-bit depth)
    }
  }
}

class Int64Paths : public ::testing::TestWithParam<std::string> {};

TEST_P(Int64Paths, AgreeWithI128OnRandomTriangles) {
  RasterState st = state_of(GetParam());
  for (int samples : {1, 4}) {
    st.samples = samples;
    run_many(st, 0x64b175u + uint64_t(samples), 1500);
  }
}

INSTANTIATE_TEST_SUITE_P(ShippedConfigs, Int64Paths, ::testing::Values("default", "d3d11", "desktop", "embedded"));

// The format widths at the edge: s15.15 (N = 30, the widest with edges64), s16.15
// (N = 31: the i128 path only), and a narrow s4.2.
TEST(Int64Paths, AgreeAtTheWidestFormats) {
  for (const char* f : {"s15.15", "s16.15", "s4.2"}) {
    RasterState st = state_of("default");
    st.coord_format = FixedFormat::parse(f);
    const int64_t ext = max_viewport_extent(st.coord_format);
    st.fb_width = st.viewport_width = int(std::min<int64_t>(st.fb_width, ext));
    st.fb_height = st.viewport_height = int(std::min<int64_t>(st.fb_height, ext));
    EXPECT_EQ(edges_fit_int64(st.coord_format), std::string(f) != "s16.15") << f;
    run_many(st, 0x5ca1eu, 1500);
  }
}

}  // namespace
}  // namespace rastsim
