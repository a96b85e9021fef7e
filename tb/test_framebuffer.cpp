// SPDX-License-Identifier: Apache-2.0
// The sparse framebuffer (ref/framebuffer.h) against a dense one written here: plain
// arrays of every sample, the ROP rule and the box-filter resolve restated, the CRC by
// zlib's crc32 over the dense bytes. Random operation sequences (clears, scissored
// fragment rectangles, direct writes) and random scenes through render_scene, at several
// tile sizes and sample counts; the CRC of untouched and cleared buffers of odd sizes.
#include <gtest/gtest.h>
#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "config/config.h"
#include "config/raster_state_config.h"
#include "image/image_io.h"
#include "ref/pipeline.h"
#include "ref/rop.h"

namespace rastsim {
namespace {

// Every sample in one array, pixel (x, y) sample s at (y W + x) S + s.
struct DenseFb {
  int w, h, S;
  std::vector<uint8_t> rgba;
  std::vector<uint32_t> depth;
  DenseFb(int w_, int h_, int s_) : w(w_), h(h_), S(s_), rgba(size_t(w_) * h_ * s_ * 4), depth(size_t(w_) * h_ * s_, 0) {
    clear_color(0, 0, 0);
  }
  size_t at(int x, int y, int s) const { return (size_t(y) * w + x) * S + s; }
  void clear_color(uint8_t r, uint8_t g, uint8_t b) {
    for (size_t i = 0; i < rgba.size(); i += 4) rgba[i] = r, rgba[i + 1] = g, rgba[i + 2] = b, rgba[i + 3] = 255;
  }
  void clear_depth(uint32_t z) { std::fill(depth.begin(), depth.end(), z); }
  bool rop(const Fragment& f, DepthFunc func, bool depth_write) {
    bool any = false;
    for (int s = 0; s < S; ++s) {
      if (S > 1 && !((f.mask >> s) & 1)) continue;
      const size_t i = at(f.x, f.y, s);
      if (!depth_test(func, f.z, depth[i])) continue;
      if (depth_write) depth[i] = f.z;
      rgba[i * 4] = f.r, rgba[i * 4 + 1] = f.g, rgba[i * 4 + 2] = f.b, rgba[i * 4 + 3] = 255;
      any = true;
    }
    return any;
  }
  // The one-sample image: each channel (sum + S/2) / S.
  std::vector<uint8_t> resolved() const {
    std::vector<uint8_t> out(size_t(w) * h * 4);
    for (size_t p = 0; p < size_t(w) * h; ++p)
      for (int c = 0; c < 4; ++c) {
        unsigned sum = 0;
        for (int s = 0; s < S; ++s) sum += rgba[(p * S + s) * 4 + c];
        out[p * 4 + c] = uint8_t((sum + unsigned(S) / 2) / unsigned(S));
      }
    return out;
  }
  uint32_t crc() const {
    const std::vector<uint8_t> img = resolved();
    return uint32_t(crc32(crc32(0L, Z_NULL, 0), img.data(), uInt(img.size())));
  }
};

// Colour and depth of every sample, every row as read_row gives it, the resolve and the
// CRC: all as the dense buffer's.
void expect_same(const Framebuffer& fb, const DenseFb& d, const std::string& what) {
  SCOPED_TRACE(what);
  ASSERT_EQ(fb.width, d.w);
  ASSERT_EQ(fb.height, d.h);
  ASSERT_EQ(fb.samples, d.S);
  for (int y = 0; y < d.h; ++y)
    for (int x = 0; x < d.w; ++x)
      for (int s = 0; s < d.S; ++s) {
        const size_t i = d.at(x, y, s);
        ASSERT_TRUE(std::equal(&d.rgba[i * 4], &d.rgba[i * 4] + 4, fb.sample(x, y, s)))
            << "colour of (" << x << ", " << y << ") sample " << s;
        ASSERT_EQ(fb.depth_at(x, y, s), d.depth[i]) << "depth of (" << x << ", " << y << ") sample " << s;
      }
  std::vector<uint8_t> row(size_t(d.w) * 4);
  for (int y = 0; y < d.h; ++y) {
    fb.read_row(y, row.data());
    for (int x = 0; x < d.w; ++x)
      ASSERT_TRUE(std::equal(&row[size_t(x) * 4], &row[size_t(x) * 4] + 4, &d.rgba[d.at(x, y, 0) * 4]))
          << "read_row " << y << " pixel " << x;
  }
  const Framebuffer r = fb.resolve();
  const std::vector<uint8_t> want = d.resolved();
  ASSERT_EQ(r.samples, 1);
  for (int y = 0; y < d.h; ++y)
    for (int x = 0; x < d.w; ++x) {
      const size_t p = size_t(y) * d.w + x;
      ASSERT_TRUE(std::equal(&want[p * 4], &want[p * 4] + 4, r.pixel(x, y))) << "resolved (" << x << ", " << y << ")";
      ASSERT_EQ(r.depth_at(x, y), d.depth[d.at(x, y, 0)]) << "resolved depth (" << x << ", " << y << ")";
    }
  EXPECT_EQ(fb.color_crc32(), d.crc());
}

constexpr DepthFunc kFuncs[] = {DepthFunc::Never,   DepthFunc::Less,     DepthFunc::LEqual, DepthFunc::Equal,
                                DepthFunc::Greater, DepthFunc::GEqual,   DepthFunc::NotEqual, DepthFunc::Always};

TEST(SparseFramebuffer, RandomOperationsAgreeWithDense) {
  std::mt19937 rng(14);
  for (int tile_log2 : {0, 1, 2, 3, 5, 7}) {
    for (int S : {1, 2, 4, 8}) {
      for (int round = 0; round < 3; ++round) {
        const int w = std::uniform_int_distribution<int>(1, 70)(rng), h = std::uniform_int_distribution<int>(1, 50)(rng);
        Framebuffer fb(w, h, S, tile_log2);
        DenseFb d(w, h, S);
        const std::string what = std::to_string(w) + "x" + std::to_string(h) + " S=" + std::to_string(S) +
                                 " tile 2^" + std::to_string(tile_log2) + " round " + std::to_string(round);
        expect_same(fb, d, what + " fresh");
        EXPECT_EQ(fb.color_tiles_allocated() + fb.depth_tiles_allocated(), 0u);
        std::uniform_int_distribution<int> px(0, w - 1), py(0, h - 1), byte(0, 255), pct(0, 99);
        for (int op = 0; op < 120; ++op) {
          const int kind = pct(rng);
          if (kind < 6) {
            const uint8_t r = uint8_t(byte(rng)), g = uint8_t(byte(rng)), b = uint8_t(byte(rng));
            fb.clear_color(r, g, b);
            d.clear_color(r, g, b);
            ASSERT_EQ(fb.color_tiles_allocated(), 0u);  // a clear frees what was written
          } else if (kind < 12) {
            const uint32_t z = uint32_t(byte(rng) % 8);
            fb.clear_depth(z);
            d.clear_depth(z);
            ASSERT_EQ(fb.depth_tiles_allocated(), 0u);
          } else if (kind < 20) {  // direct writes (the 2D engine's kind of access)
            const int x = px(rng), y = py(rng), s = std::uniform_int_distribution<int>(0, S - 1)(rng);
            uint8_t* p = fb.sample(x, y, s);
            for (int c = 0; c < 4; ++c) p[c] = d.rgba[d.at(x, y, s) * 4 + c] = uint8_t(byte(rng));
          } else {  // a scissored rectangle of fragments
            int x0 = px(rng), x1 = px(rng), y0 = py(rng), y1 = py(rng);
            if (x0 > x1) std::swap(x0, x1);
            if (y0 > y1) std::swap(y0, y1);
            const DepthFunc func = kFuncs[size_t(pct(rng)) % 8];
            const bool depth_write = pct(rng) < 70;
            const uint8_t r = uint8_t(byte(rng)), g = uint8_t(byte(rng)), b = uint8_t(byte(rng));
            const size_t color_before = fb.color_tiles_allocated(), depth_before = fb.depth_tiles_allocated();
            for (int y = y0; y <= y1; ++y)
              for (int x = x0; x <= x1; ++x) {
                if (pct(rng) < 30) continue;
                Fragment f;
                f.x = x, f.y = y, f.z = uint32_t(byte(rng) % 8), f.r = r, f.g = uint8_t(g + x), f.b = uint8_t(b + y);
                f.samples = uint8_t(S);
                f.mask = uint16_t(std::uniform_int_distribution<int>(1, (1 << S) - 1)(rng));
                ASSERT_EQ(rop_write(fb, f, func, depth_write), d.rop(f, func, depth_write));
              }
            if (func == DepthFunc::Never) {  // every test fails: nothing is allocated
              ASSERT_EQ(fb.color_tiles_allocated(), color_before);
              ASSERT_EQ(fb.depth_tiles_allocated(), depth_before);
            }
          }
          if (op % 30 == 29) expect_same(fb, d, what + " op " + std::to_string(op));
        }
        expect_same(fb, d, what + " end");
        const Framebuffer copy = fb;
        expect_same(copy, d, what + " copy");
        Framebuffer assigned(1, 1);
        assigned = copy;
        EXPECT_TRUE(assigned.same_color(fb));
        EXPECT_TRUE(assigned.same_depth(fb));
        const Framebuffer moved = std::move(assigned);
        expect_same(moved, d, what + " moved");
        // Another tiling holds the same pixels.
        Framebuffer other(w, h, S, tile_log2 == 0 ? 4 : 0);
        for (int y = 0; y < h; ++y)
          for (int x = 0; x < w; ++x)
            for (int s = 0; s < S; ++s) {
              std::copy_n(std::as_const(fb).sample(x, y, s), 4, other.sample(x, y, s));
              other.set_depth(x, y, s, fb.depth_at(x, y, s));
            }
        EXPECT_TRUE(other.same_color(fb));
        EXPECT_TRUE(other.same_depth(fb));
        if (w > 1) {
          other.pixel(w - 1, h - 1)[1] ^= 1;
          EXPECT_FALSE(other.same_color(fb));
        }
      }
    }
  }
}

// A random scene: triangles, colour and depth clears, scissors on and off.
Scene random_scene(std::mt19937& rng, int w, int h) {
  Scene sc;
  sc.source = "random";
  std::uniform_int_distribution<int> pct(0, 99), byte(0, 255);
  std::uniform_real_distribution<double> cx(-8, w + 8), cy(-8, h + 8), z(0, 1);
  const int n = std::uniform_int_distribution<int>(4, 14)(rng);
  for (int line = 1; line <= n; ++line) {
    const int k = pct(rng);
    CommandBody body;
    if (k < 12) {
      body = CmdClear{uint8_t(byte(rng)), uint8_t(byte(rng)), uint8_t(byte(rng))};
    } else if (k < 20) {
      body = CmdClearDepth{z(rng)};
    } else if (k < 32) {
      CmdScissor s;
      s.enabled = pct(rng) < 70;
      s.x = std::uniform_int_distribution<int>(0, w - 1)(rng);
      s.y = std::uniform_int_distribution<int>(0, h - 1)(rng);
      s.width = std::uniform_int_distribution<int>(0, w)(rng);
      s.height = std::uniform_int_distribution<int>(0, h)(rng);
      body = s;
    } else {
      CmdPrimitives p;
      const int tris = std::uniform_int_distribution<int>(1, 3)(rng);
      for (int t = 0; t < 3 * tris; ++t) {
        SceneVertex v;
        v.x = Q64::from_double(cx(rng));
        v.y = Q64::from_double(cy(rng));
        v.z = z(rng);
        v.r = uint8_t(byte(rng)), v.g = uint8_t(byte(rng)), v.b = uint8_t(byte(rng));
        p.vertices.push_back(v);
      }
      body = p;
    }
    sc.commands.push_back({body, {"random", line}});
  }
  return sc;
}

// render_scene (sparse, at several tile sizes) against the scene replayed on the dense
// buffer: each command's fragments are the ones its prefix of the scene adds.
TEST(SparseFramebuffer, RandomScenesAgreeWithDenseReplay) {
  std::mt19937 rng(1414);
  size_t fragments = 0, clears = 0, allocated = 0;
  for (int S : {1, 4}) {
    for (int scene_no = 0; scene_no < 6; ++scene_no) {
      const int w = std::uniform_int_distribution<int>(9, 61)(rng), h = std::uniform_int_distribution<int>(7, 45)(rng);
      const Scene scene = random_scene(rng, w, h);
      RasterState st = raster_state_from_config(Config{});
      st.fb_width = st.viewport_width = w;
      st.fb_height = st.viewport_height = h;
      st.samples = S;
      st.out_of_range = OutOfRange::Cull;
      st.depth_write = scene_no % 3 != 2;
      st.depth_func = kFuncs[size_t(scene_no) % 8 == 0 ? 1 : size_t(scene_no) % 8];
      // Fragments of each command: prefix k + 1 minus prefix k.
      std::vector<std::vector<Fragment>> per_command;
      std::vector<Fragment> before;
      for (size_t k = 1; k <= scene.commands.size(); ++k) {
        Scene prefix = scene;
        prefix.commands.resize(k);
        std::vector<Fragment> frags;
        RenderStats stats;
        render_scene(prefix, st, stats, [&](const Fragment& f) { frags.push_back(f); });
        ASSERT_TRUE(std::equal(before.begin(), before.end(), frags.begin()));
        per_command.emplace_back(frags.begin() + std::ptrdiff_t(before.size()), frags.end());
        before = std::move(frags);
      }
      fragments += before.size();
      for (const Command& c : scene.commands) clears += std::holds_alternative<CmdClear>(c.body);
      DenseFb d(w, h, S);
      d.clear_depth(uint32_t((uint64_t{1} << st.depth_bits) - 1));
      for (size_t k = 0; k < scene.commands.size(); ++k) {
        if (const auto* c = std::get_if<CmdClear>(&scene.commands[k].body)) d.clear_color(c->r, c->g, c->b);
        if (const auto* c = std::get_if<CmdClearDepth>(&scene.commands[k].body))
          d.clear_depth(*quantize_unorm(c->z, st.depth_bits));
        for (const Fragment& f : per_command[k]) d.rop(f, st.depth_func, st.depth_write);
      }
      DenseFb want(w, h, 1);
      want.rgba = d.resolved();
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) want.depth[want.at(x, y, 0)] = d.depth[d.at(x, y, 0)];
      for (int tile_log2 : {0, 1, 3, 4, 5, 6}) {
        RenderStats stats;
        const Framebuffer fb = render_scene(scene, st, stats, {}, tile_log2);
        allocated += fb.color_tiles_allocated();
        EXPECT_EQ(stats.framebuffer_crc32, d.crc());
        expect_same(fb, want,
                    "scene " + std::to_string(scene_no) + " " + std::to_string(w) + "x" + std::to_string(h) +
                        " S=" + std::to_string(S) + " tile 2^" + std::to_string(tile_log2) + ", " +
                        std::to_string(before.size()) + " fragments");
      }
    }
  }
  EXPECT_GT(fragments, 5000u);  // the scenes draw, clear and leave tiles untouched
  EXPECT_GT(clears, 5u);
  EXPECT_GT(allocated, 0u);
  std::printf("%zu fragments, %zu colour clears, %zu colour tiles allocated in all\n", fragments, clears, allocated);
}

// The CRC of a buffer nobody drew in is zlib's over its dense bytes, by CRC-combine of
// runs of the clear pixel, for odd sizes, every tile size, before and after a clear.
TEST(SparseFramebuffer, CrcOfUntouchedAndClearedBuffersIsZlibs) {
  struct Size { int w, h; };
  for (const Size sz : {Size{1, 1}, Size{7, 3}, Size{1000, 1}, Size{4097, 3}, Size{1, 999}, Size{33, 65}}) {
    for (int tile_log2 : {0, 2, 5, 8}) {
      for (int S : {1, 4}) {
        if (S > 1 && tile_log2 == 0 && sz.w * sz.h > 10000) continue;
        Framebuffer fb(sz.w, sz.h, S, tile_log2);
        DenseFb d(sz.w, sz.h, S);
        const std::string what = std::to_string(sz.w) + "x" + std::to_string(sz.h) + " tile 2^" +
                                 std::to_string(tile_log2) + " S=" + std::to_string(S);
        EXPECT_EQ(fb.color_crc32(), d.crc()) << what << " fresh";
        fb.clear_color(12, 200, 7);
        d.clear_color(12, 200, 7);
        EXPECT_EQ(fb.color_crc32(), d.crc()) << what << " cleared";
        fb.pixel(sz.w / 2, sz.h / 2)[0] = 99;  // one tile written ...
        d.rgba[d.at(sz.w / 2, sz.h / 2, 0) * 4] = 99;
        EXPECT_EQ(fb.color_crc32(), d.crc()) << what << " one pixel";
        fb.clear_color(255, 255, 255);  // ... and cleared away
        d.clear_color(255, 255, 255);
        EXPECT_EQ(fb.color_tiles_allocated(), 0u);
        EXPECT_EQ(fb.color_crc32(), d.crc()) << what << " cleared again";
      }
    }
  }
}

// A large buffer, one pixel drawn: the CRC (runs of 2^26 clear pixels combined) against
// zlib fed row by row.
TEST(SparseFramebuffer, CrcOfALargeMostlyClearBuffer) {
  const int w = 8191, h = 8193;
  Framebuffer fb(w, h);
  fb.clear_color(1, 2, 3);
  fb.pixel(4000, 5000)[1] = 77;
  std::vector<uint8_t> row(size_t(w) * 4);
  uLong crc = crc32(0L, Z_NULL, 0);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) row[size_t(x) * 4] = 1, row[size_t(x) * 4 + 1] = 2, row[size_t(x) * 4 + 2] = 3, row[size_t(x) * 4 + 3] = 255;
    if (y == 5000) row[4000 * 4 + 1] = 77;
    crc = crc32(crc, row.data(), uInt(row.size()));
  }
  EXPECT_EQ(fb.color_crc32(), uint32_t(crc));
  EXPECT_EQ(fb.color_tiles_allocated(), 1u);
}

// An image written from the tiles reads back as the same pixels.
TEST(SparseFramebuffer, ImageFilesStreamRowsFromTheTiles) {
  Framebuffer fb(77, 41, 1, 3);
  fb.clear_color(5, 6, 7);
  for (int i = 0; i < 40; ++i) {
    uint8_t* p = fb.pixel((i * 13) % 77, (i * 7) % 41);
    p[0] = uint8_t(i * 5), p[1] = uint8_t(i), p[2] = 250;
  }
  for (const char* ext : {".png", ".ppm"}) {
    const std::string path = ::testing::TempDir() + "sparse_fb_image" + ext;
    write_image(fb, path);
    const Framebuffer back = read_image(path);
    EXPECT_TRUE(back.same_color(fb)) << ext;
    EXPECT_EQ(back.color_crc32(), fb.color_crc32()) << ext;
    std::remove(path.c_str());
  }
}

}  // namespace
}  // namespace rastsim
