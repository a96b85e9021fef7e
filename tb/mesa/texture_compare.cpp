// SPDX-License-Identifier: Apache-2.0
// Textured triangles, reference model against llvmpipe (texture_compare.h).
#include "texture_compare.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <random>

#include "mesa_scenes.h"
#include "ref/pipeline.h"

namespace rastsim::mesa {
namespace {

constexpr int kTexcoordGrid = 1024;  // texture coordinates are multiples of 1/1024 repeat

TexWrap ref_wrap(GlWrap w) {
  switch (w) {
    case GlWrap::Repeat: return TexWrap::Repeat;
    case GlWrap::Clamp: return TexWrap::Clamp;
    case GlWrap::Mirror: return TexWrap::Mirror;
  }
  return TexWrap::Repeat;
}

// A triangle of at least 40 px^2 (so that it has interior pixels) inside the framebuffer.
GridTri random_tri(std::mt19937_64& rng, int width, int height) {
  std::uniform_int_distribution<int64_t> ux(0, int64_t(width) * 256 - 1), uy(0, int64_t(height) * 256 - 1);
  for (;;) {
    GridTri t;
    for (size_t v = 0; v < 3; ++v) t.x[v] = ux(rng), t.y[v] = uy(rng);
    const int64_t area2 = (t.x[1] - t.x[0]) * (t.y[2] - t.y[0]) - (t.y[1] - t.y[0]) * (t.x[2] - t.x[0]);
    if (std::llabs(area2) >= int64_t{80} * 256 * 256) return t;
  }
}

// The scene of one case: the triangle drawn textured, texenv replace, over black.
Scene reference_scene(const TexCase& c) {
  auto image = std::make_shared<TextureImage>();
  image->name = "random";
  image->width = c.tex.base.width, image->height = c.tex.base.height;
  image->rgba = c.tex.base.rgba;
  CmdPrimitives prims;
  prims.texture.image = image;
  prims.texture.filter = c.filter == GlFilter::Nearest    ? TexFilter::Nearest
                         : c.filter == GlFilter::Bilinear ? TexFilter::Bilinear
                                                          : TexFilter::Trilinear;
  prims.texture.wrap_s = ref_wrap(c.wrap_s), prims.texture.wrap_t = ref_wrap(c.wrap_t);
  prims.texture.env = TexEnv::Replace;
  prims.texture.mipmap = !c.tex.below.empty();
  for (size_t v = 0; v < 3; ++v) {
    SceneVertex sv;
    sv.x = Q64{i128(c.tri.tri.x[v]) << (Q64::kFracBits - c.tri.tri.frac_bits)};
    sv.y = Q64{i128(c.tri.tri.y[v]) << (Q64::kFracBits - c.tri.tri.frac_bits)};
    sv.z = 0.5;
    sv.s = c.tri.s[v], sv.t = c.tri.t[v];
    prims.vertices.push_back(sv);
  }
  Scene scene;
  scene.source = "mesa-texture";
  scene.commands.push_back({CmdClear{0, 0, 0}, {"mesa-texture", 1}});
  scene.commands.push_back({std::move(prims), {"mesa-texture", 2}});
  return scene;
}

// The exact barycentric weights of point (px, py) (pixels) in the triangle, and whether
// it lies farther than one 1/256 px LSB from every edge, inside.
struct Bary {
  double w[3] = {};
  bool interior = false;
};
Bary barycentric(const GridTri& t, double px, double py) {
  const double k = 1.0 / double(int64_t{1} << t.frac_bits);
  double x[3], y[3];
  for (size_t v = 0; v < 3; ++v) x[v] = double(t.x[v]) * k, y[v] = double(t.y[v]) * k;
  const double area2 = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
  Bary b;
  b.interior = true;
  for (size_t v = 0; v < 3; ++v) {
    const size_t i = (v + 1) % 3, j = (v + 2) % 3;  // the edge opposite vertex v
    const double e = ((x[j] - x[i]) * (py - y[i]) - (y[j] - y[i]) * (px - x[i])) / area2;
    b.w[v] = e;
    const double dist = e * std::fabs(area2) / std::hypot(x[j] - x[i], y[j] - y[i]);  // px, > 0 inside
    b.interior = b.interior && dist > k;
  }
  return b;
}

// Distance (texels) of texel coordinate u from the nearest edge that decides the filter's
// result: texel edges (integers) for nearest; for bilinear the 1/256 steps of u - 1/2.
double edge_distance(double u, GlFilter f) {
  const double q = f == GlFilter::Nearest ? u : (u - 0.5) * 256.0;
  const double d = std::fabs(q - std::nearbyint(q));
  return f == GlFilter::Nearest ? d : d / 256.0;
}

// Vulkan's wrap of texel index i on an axis of n texels (written here, not the model's).
int64_t wrap_index(int64_t i, int64_t n, GlWrap w) {
  const auto mod = [](int64_t a, int64_t b) { return ((a % b) + b) % b; };
  if (w == GlWrap::Repeat) return mod(i, n);
  if (w == GlWrap::Clamp) return std::clamp<int64_t>(i, 0, n - 1);
  const int64_t a = mod(i, 2 * n) - n;  // mirrored repeat: (n - 1) - mirror((i mod 2n) - n)
  return (n - 1) - (a >= 0 ? a : -(1 + a));
}

// The exact bilinear filter (double weights, nothing rounded) of level `t` at its texel
// coordinates (u, v).
std::array<double, 3> exact_bilinear_level(const TexImage& t, GlWrap ws, GlWrap wt, double u, double v) {
  const double x = u - 0.5, y = v - 0.5, i0 = std::floor(x), j0 = std::floor(y), a = x - i0, b = y - j0;
  std::array<double, 3> out{};
  for (int dj = 0; dj < 2; ++dj)
    for (int di = 0; di < 2; ++di) {
      const int64_t i = wrap_index(int64_t(i0) + di, t.width, ws);
      const int64_t j = wrap_index(int64_t(j0) + dj, t.height, wt);
      for (size_t ch = 0; ch < 3; ++ch) out[ch] += (di ? a : 1 - a) * (dj ? b : 1 - b) * t.rgba[size_t(j * t.width + i) * 4 + ch];
    }
  return out;
}

std::array<double, 3> exact_bilinear(const TexCase& c, double u, double v) {
  return exact_bilinear_level(c.tex.base, c.wrap_s, c.wrap_t, u, v);
}

// The exact trilinear filter at (s, t) (repeats) and level of detail `lambda` (double,
// unrounded): clamped to the chain, levels floor and floor + 1 blended by the fraction.
std::array<double, 3> exact_trilinear(const TexCase& c, double s, double t, double lambda) {
  const int levels = int(c.tex.below.size()) + 1;
  const double l = std::clamp(lambda, 0.0, double(levels - 1));
  const int k = std::min(int(std::floor(l)), levels - 1);
  const double f = l - k;
  const auto level = [&](int n) -> const TexImage& { return n == 0 ? c.tex.base : c.tex.below[size_t(n - 1)]; };
  const auto at = [&](int n) {
    const TexImage& im = level(n);
    return exact_bilinear_level(im, c.wrap_s, c.wrap_t, s * im.width, t * im.height);
  };
  std::array<double, 3> out = at(k);
  if (f > 0 && k + 1 < levels) {
    const std::array<double, 3> next = at(k + 1);
    for (size_t ch = 0; ch < 3; ++ch) out[ch] = out[ch] * (1 - f) + next[ch] * f;
  }
  return out;
}

// The range per channel of the exact trilinear filter over lambda in [lo, hi]: linear
// between whole levels, so its extremes are at the ends and the whole levels between.
struct Band {
  std::array<double, 3> lo{}, hi{};
};
Band trilinear_band(const TexCase& c, double s, double t, double lo, double hi) {
  Band b;
  b.lo.fill(1e9), b.hi.fill(-1e9);
  const auto take = [&](double l) {
    const std::array<double, 3> v = exact_trilinear(c, s, t, l);
    for (size_t ch = 0; ch < 3; ++ch) b.lo[ch] = std::min(b.lo[ch], v[ch]), b.hi[ch] = std::max(b.hi[ch], v[ch]);
  };
  take(lo);
  take(hi);
  for (double k = std::ceil(lo); k < hi; k += 1) take(k);
  return b;
}

// How far (LSB) the colour `rgb` lies outside the band's range on its worst channel (0 inside).
double outside(const Band& b, const std::array<int, 3>& rgb) {
  double d = 0;
  for (size_t ch = 0; ch < 3; ++ch) d = std::max({d, b.lo[ch] - rgb[ch], rgb[ch] - b.hi[ch]});
  return d;
}

// The reference's mip chain below level 0 (ref/texture's box filter, RGBA8888: the
// chain is the input both samplers read, not what is compared).
std::vector<TexImage> chain_below(const TexImage& base) {
  TextureImage img;
  img.width = base.width, img.height = base.height, img.rgba = base.rgba;
  std::vector<TexImage> out;
  const std::vector<MipLevel> chain = build_mip_chain(img, TexelFormat::Rgba8888, true);
  for (size_t k = 1; k < chain.size(); ++k) out.push_back({chain[k].width, chain[k].height, chain[k].rgba});
  return out;
}

// The exact level of detail of an affine triangle: log2 of the longer Euclidean length of
// (du/dx, dv/dx) and (du/dy, dv/dy), texels a pixel (u = s W, v = t H).
double exact_lambda(const TexCase& c) {
  const GridTri& g = c.tri.tri;
  const double k = 1.0 / double(int64_t{1} << g.frac_bits);
  const double x1 = double(g.x[1] - g.x[0]) * k, y1 = double(g.y[1] - g.y[0]) * k;
  const double x2 = double(g.x[2] - g.x[0]) * k, y2 = double(g.y[2] - g.y[0]) * k, det = x1 * y2 - x2 * y1;
  const auto grad = [&](const std::array<float, 3>& a, double n, double& dx, double& dy) {
    const double a1 = (a[1] - a[0]) * n, a2 = (a[2] - a[0]) * n;
    dx = (a1 * y2 - a2 * y1) / det, dy = (a2 * x1 - a1 * x2) / det;
  };
  double udx, udy, vdx, vdy;
  grad(c.tri.s, c.tex.base.width, udx, udy);
  grad(c.tri.t, c.tex.base.height, vdx, vdy);
  return std::log2(std::max(std::hypot(udx, vdx), std::hypot(udy, vdy)));
}

// Trilinear: where the pixel's two colours lie against the exact filter's range over
// the level-of-detail band (texture_compare.h), counted into `s`.
void check_trilinear(const TexCase& c, double lambda, double s_at, double t_at, const uint8_t* ref, uint32_t lp,
                     int diff, TexCompareStats& s) {
  const Band b = trilinear_band(c, s_at, t_at, lambda - kTrilinearBandLow, lambda + kTrilinearBandHigh);
  double spread = 0;
  for (size_t ch = 0; ch < 3; ++ch) spread = std::max(spread, b.hi[ch] - b.lo[ch]);
  s.max_band_spread = std::max(s.max_band_spread, spread);
  const double out_ref = outside(b, {ref[0], ref[1], ref[2]});
  const double out_lp = outside(b, {int(lp & 255), int((lp >> 8) & 255), int((lp >> 16) & 255)});
  s.max_outside_ref = std::max(s.max_outside_ref, out_ref);
  s.max_outside_llvmpipe = std::max(s.max_outside_llvmpipe, out_lp);
  s.outside_band_ref += out_ref > kTrilinearSlack;
  s.outside_band_llvmpipe += out_lp > kTrilinearSlack;
  s.beyond_range_plus_one += diff > spread + 1;
  s.max_diff_beyond_spread = std::max(s.max_diff_beyond_spread, diff - spread);
  const Band finer = trilinear_band(c, s_at, t_at, lambda - 0.5 - kTrilinearBandLow, lambda - 0.5 + kTrilinearBandHigh);
  s.outside_shifted_band_ref += outside(finer, {ref[0], ref[1], ref[2]}) > kTrilinearSlack;
}

std::string rgb_text(double r, double g, double b) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "(%.2f %.2f %.2f)", r, g, b);
  return buf;
}

}  // namespace

std::vector<TexCase> make_texture_cases(uint64_t seed, int count, GlFilter filter, int width, int height,
                                        bool mipmap) {
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int> side(1, mipmap ? 32 : 16), byte(0, 255), wrap(0, 2);
  std::uniform_int_distribution<int> coord(-2 * kTexcoordGrid, 3 * kTexcoordGrid);
  std::vector<TexCase> out;
  for (int n = 0; n < count; ++n) {
    TexCase c;
    c.filter = filter;
    TexImage& t = c.tex.base;
    t.width = side(rng), t.height = side(rng);
    for (int k = 0; k < t.width * t.height; ++k)
      t.rgba.insert(t.rgba.end(), {uint8_t(byte(rng)), uint8_t(byte(rng)), uint8_t(byte(rng)), 255});
    if (mipmap) c.tex.below = chain_below(t);
    c.wrap_s = GlWrap(wrap(rng)), c.wrap_t = GlWrap(wrap(rng));
    c.tri.tri = random_tri(rng, width, height);
    for (size_t v = 0; v < 3; ++v)
      c.tri.s[v] = float(coord(rng)) / kTexcoordGrid, c.tri.t[v] = float(coord(rng)) / kTexcoordGrid;
    out.push_back(std::move(c));
  }
  return out;
}

TexCompareStats& TexCompareStats::operator+=(const TexCompareStats& o) {
  triangles += o.triangles;
  interior += o.interior;
  identical += o.identical;
  within_one += o.within_one;
  beyond_one += o.beyond_one;
  near_texel_edge += o.near_texel_edge;
  near_lod_tie += o.near_lod_tie;
  unexplained += o.unexplained;
  max_diff_off_tie = std::max(max_diff_off_tie, o.max_diff_off_tie);
  beyond_one_off_tie += o.beyond_one_off_tie;
  ref_max_error = std::max(ref_max_error, o.ref_max_error);
  outside_band_ref += o.outside_band_ref;
  outside_band_llvmpipe += o.outside_band_llvmpipe;
  beyond_range_plus_one += o.beyond_range_plus_one;
  max_band_spread = std::max(max_band_spread, o.max_band_spread);
  max_outside_ref = std::max(max_outside_ref, o.max_outside_ref);
  max_outside_llvmpipe = std::max(max_outside_llvmpipe, o.max_outside_llvmpipe);
  max_diff_beyond_spread = std::max(max_diff_beyond_spread, o.max_diff_beyond_spread);
  outside_shifted_band_ref += o.outside_shifted_band_ref;
  llvmpipe_max_error = std::max(llvmpipe_max_error, o.llvmpipe_max_error);
  max_channel_diff = std::max(max_channel_diff, o.max_channel_diff);
  return *this;
}

TexCompareStats compare_textured(const TexCase& c, const RasterState& st, OsMesaTexture& gl,
                                 std::vector<std::string>& report, size_t max_report) {
  RenderStats rs;
  const Framebuffer fb = render_scene(reference_scene(c), st, rs);
  const std::vector<uint32_t> lp = gl.draw(c.tri, c.tex, c.filter, c.wrap_s, c.wrap_t);
  TexCompareStats s;
  s.triangles = 1;
  const bool mipmap = !c.tex.below.empty();
  const double lambda = mipmap ? exact_lambda(c) : 0.0;
  const bool lod_tie = mipmap && c.filter != GlFilter::Trilinear && lambda > 0.5 - kLodTieBand && std::fabs(lambda - std::floor(lambda) - 0.5) < kLodTieBand;
  for (int y = 0; y < st.fb_height; ++y)
    for (int x = 0; x < st.fb_width; ++x) {
      const Bary b = barycentric(c.tri.tri, x + 0.5, y + 0.5);
      if (!b.interior) continue;
      ++s.interior;
      const uint8_t* r = fb.pixel(x, y);
      const uint32_t l = lp[size_t(y) * size_t(st.fb_width) + size_t(x)];
      const double s_at = b.w[0] * c.tri.s[0] + b.w[1] * c.tri.s[1] + b.w[2] * c.tri.s[2];
      const double t_at = b.w[0] * c.tri.t[0] + b.w[1] * c.tri.t[1] + b.w[2] * c.tri.t[2];
      const double u = s_at * c.tex.base.width, v = t_at * c.tex.base.height;
      const std::array<double, 3> exact = exact_bilinear(c, u, v);
      int diff = 0;
      for (size_t ch = 0; ch < 3; ++ch) {
        const int lv = int((l >> (8 * ch)) & 255);
        diff = std::max(diff, std::abs(int(r[ch]) - lv));
        if (c.filter == GlFilter::Bilinear && !mipmap) {
          s.ref_max_error = std::max(s.ref_max_error, std::fabs(r[ch] - exact[ch]));
          s.llvmpipe_max_error = std::max(s.llvmpipe_max_error, std::fabs(lv - exact[ch]));
        }
      }
      s.max_channel_diff = std::max(s.max_channel_diff, diff);
      if (c.filter == GlFilter::Trilinear) check_trilinear(c, lambda, s_at, t_at, r, l, diff, s);
      if (diff == 0) {
        ++s.identical;
        continue;
      }
      ++(diff <= 1 ? s.within_one : s.beyond_one);
      double edge = std::min(edge_distance(u, c.filter), edge_distance(v, c.filter));
      for (const TexImage& l : c.tex.below)  // mipmapped: the edges of every level
        edge = std::min({edge, edge_distance(s_at * l.width, c.filter), edge_distance(t_at * l.height, c.filter)});
      if (edge < kTexelTieBand) ++s.near_texel_edge;
      if (lod_tie) ++s.near_lod_tie;
      if (!lod_tie && edge >= kTexelTieBand) ++s.unexplained;
      if (!lod_tie) {
        s.max_diff_off_tie = std::max(s.max_diff_off_tie, diff);
        s.beyond_one_off_tie += diff > 1;
      }
      if (report.size() < max_report && (diff > 1 || c.filter == GlFilter::Nearest) && !lod_tie)
        report.push_back(describe(c.tri.tri) + " texture " + std::to_string(c.tex.base.width) + "x" +
                         std::to_string(c.tex.base.height) + (mipmap ? " lambda " + std::to_string(lambda) : "") +
                         ": pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                         ") u " + std::to_string(u) + " v " + std::to_string(v) + ": RGB differs by " +
                         std::to_string(diff) + ", " + std::to_string(edge) + " texels from an edge: rastsim " +
                         rgb_text(r[0], r[1], r[2]) + ", llvmpipe " + rgb_text(l & 255, (l >> 8) & 255, (l >> 16) & 255) +
                         ", exact " + rgb_text(exact[0], exact[1], exact[2]));
    }
  return s;
}

}  // namespace rastsim::mesa
