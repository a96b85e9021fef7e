// SPDX-License-Identifier: Apache-2.0
// Clip-space scene generators for the llvmpipe comparison (see clip_scenes.h).
#include "clip_scenes.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

namespace rastsim::mesa {
namespace {

// Uniform values from a 64-bit engine, written out (not std::*_distribution, whose
// output differs between standard libraries) so a seed names the same scene everywhere.
// Magnitudes are (1 + u) * 2^e with an integer e: exact, no libm call.
struct ClipRng {
  std::mt19937_64 eng;
  explicit ClipRng(uint64_t seed) : eng(seed) {}
  double unit() { return double(eng() >> 11) * 0x1p-53; }  // [0, 1)
  double uniform(double lo, double hi) { return lo + (hi - lo) * unit(); }
  int integer(int lo, int hi) { return lo + int(eng() % uint64_t(hi - lo + 1)); }
  bool chance(int percent) { return integer(0, 99) < percent; }
  double magnitude(int e_lo, int e_hi) { return std::ldexp(1.0 + unit(), integer(e_lo, e_hi - 1)); }
  double sign() { return chance(50) ? 1.0 : -1.0; }
  uint8_t byte() { return uint8_t(eng() & 0xff); }
};

void random_colour(ClipRng& rng, ClipVertex& v) { v.r = rng.byte(), v.g = rng.byte(), v.b = rng.byte(); }

// A vertex inside the view volume at NDC (nx, ny) (clamped to [-1, 1]): |x|, |y| <= w and
// 0 <= z <= w hold after rounding, since rounding a product of w by a factor in [-1, 1]
// cannot pass the binary32 value w.
ClipVertex inside_vertex(ClipRng& rng, double nx, double ny) {
  ClipVertex v;
  const double w = rng.magnitude(-4, 7);  // 1/16 .. 128
  v.w = float(w);
  v.x = float(std::clamp(nx, -1.0, 1.0) * v.w);
  v.y = float(std::clamp(ny, -1.0, 1.0) * v.w);
  v.z = float(rng.unit() * v.w);
  random_colour(rng, v);
  return v;
}

// A triangle inside the view volume: centre anywhere, NDC extent 2^-8 .. 2 (half a pixel
// to the whole viewport on a 240-pixel one).
ClipTri inside_tri(ClipRng& rng) {
  const double cx = rng.uniform(-1, 1), cy = rng.uniform(-1, 1), ext = rng.magnitude(-8, 1);
  ClipTri t;
  for (ClipVertex& v : t.v) v = inside_vertex(rng, cx + ext * rng.uniform(-1, 1), cy + ext * rng.uniform(-1, 1));
  return t;
}

// One or two distinct vertex indices, to be moved out of the volume.
std::vector<int> some_vertices(ClipRng& rng) {
  const int first = rng.integer(0, 2);
  if (rng.chance(50)) return {first};
  return {first, (first + rng.integer(1, 2)) % 3};
}

ClipTri near_crossing(ClipRng& rng) {
  ClipTri t = inside_tri(rng);
  for (int i : some_vertices(rng)) t.v[i].z = float(-t.v[i].w * rng.magnitude(-10, 2));  // z < 0 < w
  return t;
}

ClipTri behind_eye(ClipRng& rng) {
  ClipTri t = inside_tri(rng);
  for (int i : some_vertices(rng)) {
    ClipVertex& v = t.v[i];
    const double w = -rng.magnitude(-6, 4);  // -1/64 .. -16
    v.w = float(w);
    v.x = float(-w * rng.uniform(-2, 2));
    v.y = float(-w * rng.uniform(-2, 2));
    // A perspective projection puts z near w behind the eye; any z is legal input.
    v.z = float(rng.chance(70) ? w * rng.unit() : -w * rng.uniform(-1, 1));
  }
  return t;
}

ClipTri sliver(ClipRng& rng) {
  ClipTri t;
  t.v[0] = inside_vertex(rng, rng.uniform(-1, 1), rng.uniform(-1, 1));
  t.v[1] = inside_vertex(rng, rng.uniform(-1, 1), rng.uniform(-1, 1));
  if (rng.chance(20)) t.v[0].z = float(-t.v[0].w * rng.magnitude(-6, 0));  // a near-clipped sliver
  // A homogeneous combination lies on the line through the other two on screen.
  const double a = rng.uniform(0.05, 0.95);
  const auto mix = [&](float p, float q) { return a * double(p) + (1 - a) * double(q); };
  const double w = mix(t.v[0].w, t.v[1].w);
  // Off the line by 2^-14 .. 2^-7 NDC (about 0.007 .. 1 px), or not at all.
  const double off = rng.chance(25) ? 0.0 : rng.sign() * rng.magnitude(-14, -7);
  ClipVertex& v = t.v[2];
  v.w = float(w);
  v.x = float(mix(t.v[0].x, t.v[1].x) + off * w * rng.unit());
  v.y = float(mix(t.v[0].y, t.v[1].y) + off * w * rng.unit());
  v.z = float(mix(t.v[0].z, t.v[1].z));
  random_colour(rng, v);
  return t;
}

ClipTri near_zero_w(ClipRng& rng) {
  ClipTri t = inside_tri(rng);
  for (int i : some_vertices(rng)) {
    ClipVertex& v = t.v[i];
    const double w = (rng.chance(75) ? 1.0 : -1.0) * rng.magnitude(-23, -7);  // |w| 1.2e-7 .. 7.8e-3
    v.w = float(w);
    if (rng.chance(50)) {  // on screen: x, y scale with w
      v.x = float(w * rng.uniform(-1, 1)), v.y = float(w * rng.uniform(-1, 1));
      v.z = float(w * rng.unit());
    } else {  // far off screen (|x/w| up to 10^7), in front of or behind the near plane
      v.x = float(rng.uniform(-1, 1)), v.y = float(rng.uniform(-1, 1));
      v.z = float(std::abs(w) * rng.uniform(-1, 1));
    }
  }
  return t;
}

ClipTri beyond_guard_band(ClipRng& rng) {
  ClipTri t = inside_tri(rng);
  const int moved = rng.integer(1, 3);
  for (int i = 0; i < moved; ++i) {
    ClipVertex& v = t.v[i];
    v.x = float(v.w * rng.sign() * rng.magnitude(0, 17));  // |x/w| 1 .. 2^17
    if (rng.chance(70)) v.y = float(v.w * rng.sign() * rng.magnitude(0, 17));
  }
  return t;
}

// Eye space (y up, looking down -z) through a binary32 perspective matrix: 60 degrees
// vertical field of view, aspect 3:2, near 0.1, far 50, depth 0..1 (Vulkan), y down.
ClipTri camera(ClipRng& rng) {
  constexpr float kFocal = 1.7320508f;  // 1 / tan(30 degrees)
  constexpr float kNear = 0.1f, kFar = 50.0f;
  const float sx = kFocal / 1.5f, sy = -kFocal;
  const float a = kFar / (kNear - kFar), b = kNear * kFar / (kNear - kFar);
  // Centres from 2 units behind to 12 in front of the eye, sizes 1/16 .. 8 units: many
  // triangles pass through the near plane or the eye.
  const double cx = rng.uniform(-4, 4), cy = rng.uniform(-3, 3), cz = rng.uniform(-12, 2);
  const double size = rng.magnitude(-4, 3);
  ClipTri t;
  for (ClipVertex& v : t.v) {
    const float xe = float(cx + size * rng.uniform(-1, 1)), ye = float(cy + size * rng.uniform(-1, 1));
    const float ze = float(cz + size * rng.uniform(-1, 1));
    v.x = sx * xe, v.y = sy * ye, v.z = a * ze + b, v.w = -ze;
    random_colour(rng, v);
  }
  return t;
}

}  // namespace

const char* to_string(ClipKind k) {
  switch (k) {
    case ClipKind::Inside: return "Inside";
    case ClipKind::NearCrossing: return "NearCrossing";
    case ClipKind::BehindEye: return "BehindEye";
    case ClipKind::Sliver: return "Sliver";
    case ClipKind::NearZeroW: return "NearZeroW";
    case ClipKind::BeyondGuardBand: return "BeyondGuardBand";
    case ClipKind::Camera: return "Camera";
  }
  return "?";
}

std::vector<ClipTri> make_clip_scene(ClipKind kind, uint64_t seed, int count) {
  ClipRng rng(seed);
  std::vector<ClipTri> out;
  for (int i = 0; i < count; ++i) switch (kind) {
      case ClipKind::Inside: out.push_back(inside_tri(rng)); break;
      case ClipKind::NearCrossing: out.push_back(near_crossing(rng)); break;
      case ClipKind::BehindEye: out.push_back(behind_eye(rng)); break;
      case ClipKind::Sliver: out.push_back(sliver(rng)); break;
      case ClipKind::NearZeroW: out.push_back(near_zero_w(rng)); break;
      case ClipKind::BeyondGuardBand: out.push_back(beyond_guard_band(rng)); break;
      case ClipKind::Camera: out.push_back(camera(rng)); break;
    }
  return out;
}

ViewRect make_view_rect(uint64_t seed, int fb_width, int fb_height) {
  ClipRng rng(seed ^ 0x5eed'0f'7e57ull);
  if (rng.chance(50)) return {0, 0, fb_width, fb_height};
  ViewRect r;
  r.x = rng.integer(0, fb_width / 4), r.y = rng.integer(0, fb_height / 4);
  r.width = rng.integer(fb_width / 3, fb_width - r.x), r.height = rng.integer(fb_height / 3, fb_height - r.y);
  return r;
}

std::string describe(const ClipTri& t, const ViewRect& vp) {
  char buf[400];
  int n = std::snprintf(buf, sizeof buf, "viewport_xform %d %d %d %d\ntri4", vp.x, vp.y, vp.width, vp.height);
  for (const ClipVertex& v : t.v)
    n += std::snprintf(buf + n, sizeof buf - size_t(n), " %.9g %.9g %.9g %.9g %d %d %d", double(v.x), double(v.y),
                       double(v.z), double(v.w), int(v.r), int(v.g), int(v.b));
  return buf;
}

}  // namespace rastsim::mesa
