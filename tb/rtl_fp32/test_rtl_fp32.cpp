// SPDX-License-Identifier: Apache-2.0
// The front end's binary32 units (rtl/rast_fp32_mul.sv, rast_fp32_add.sv,
// rast_fp32_recip.sv) against the host's float arithmetic (x86-64 SSE, round to nearest
// even, no flush-to-zero or denormals-are-zero: checked below; this file is compiled
// with -ffp-contract=off), and rtl/rast_front_end_xform.sv against a C++ transform in the
// operation order of docs/clip-space.md. Results must be equal bit for bit; every NaN
// equals every NaN (the units return one quiet NaN, the host another).
//
// Operands: every pair of hand-picked edge cases (zeros, subnormals, powers of two,
// the largest finite, infinities, NaNs, halfway cases), then kRandom random bit patterns
// a unit, biased to the exponents where rounding, underflow, overflow and cancellation
// happen. The seed is printed; RASTSIM_FP32_SEED=<n> replays a run.
#include <gtest/gtest.h>

#include <xmmintrin.h>

#include <array>
#include <bit>
#include <cmath>
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <random>
#include <string>
#include <vector>

#include "Vrast_front_end_xform.h"
#include "Vrast_fp32_add.h"
#include "Vrast_fp32_mul.h"
#include "Vrast_fp32_recip.h"
#include "common/rtl_unit_test.h"

namespace {

constexpr int kRandom = 1'000'000;  // random operand sets a unit

uint32_t bits(float f) { return std::bit_cast<uint32_t>(f); }
float value(uint32_t b) { return std::bit_cast<float>(b); }

std::string show(uint32_t b) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "0x%08x (%.9g)", b, static_cast<double>(value(b)));
  return buf;
}

// Equal bits, or both NaN.
bool same(uint32_t got, uint32_t want) { return got == want || (std::isnan(value(got)) && std::isnan(value(want))); }

// A fixed seed by default (ctest runs the same operands every time);
// RASTSIM_FP32_SEED=<n> replays run n, RASTSIM_FP32_SEED=random draws a new one.
uint64_t seed() {
  static const uint64_t s = rastsim::test::seed_from_env("RASTSIM_FP32_SEED", 26);
  return s;
}

// The golden's rounding: SSE's MXCSR must round to nearest with FTZ and DAZ off.
TEST(RtlFp32, HostIsIeee) {
  const unsigned csr = _mm_getcsr();
  EXPECT_EQ(csr & _MM_ROUND_MASK, unsigned(_MM_ROUND_NEAREST));
  EXPECT_EQ(csr & (_MM_FLUSH_ZERO_MASK | 0x40u), 0u) << "FTZ or DAZ set";
  volatile float tiny = value(0x00000001);  // 2^-149
  EXPECT_EQ(bits(tiny * 2.0f), 0x00000002u);
}

// Hand-picked operands: each with both signs.
std::vector<uint32_t> edge_cases() {
  std::vector<uint32_t> v = {
      0x00000000, 0x00000001, 0x00000002, 0x00000003, 0x007FFFFF, 0x007FFFFE, 0x00400000, 0x00400001,
      0x00800000, 0x00800001, 0x00FFFFFF, 0x01000000, 0x3F800000, 0x3F800001, 0x3F7FFFFF, 0x3FC00000,
      0x3F000000, 0x40000000, 0x40400000, 0x3EAAAAAB, 0x33800000, 0x33800001, 0x34000000, 0x4B000000,
      0x4B000001, 0x4B7FFFFF, 0x7F7FFFFF, 0x7F7FFFFE, 0x7F000000, 0x7E800000, 0x7E7FFFFF, 0x7F800000,
      0x7FC00000, 0x7F800001, 0x7FFFFFFF, 0x1F800000, 0x5F800000, 0x20000000, 0x1F7FFFFF, 0x3F801000,
      0x45800000, 0x461C4000, 0x3A83126F, 0x00000100, 0x00200000, 0x0C000000, 0x72800000, 0x3F800003};
  for (uint32_t p = 0; p < 254; p += 11) v.push_back((p + 1) << 23);  // powers of two
  const size_t n = v.size();
  for (size_t i = 0; i < n; ++i) v.push_back(v[i] | 0x80000000u);
  return v;
}

// A random operand: sign, exponent and fraction each from a mix of uniform and
// interesting choices; `near` is another operand's exponent field to stay close to
// (cancellation, alignment within the guard bits), or -1.
uint32_t pick(std::mt19937_64& rng, int near = -1) {
  const uint32_t sign = uint32_t(rng() & 1) << 31;
  int e;
  switch (rng() % 8) {
    case 0: e = int(rng() % 256); break;                     // any field, inf/NaN included
    case 1: e = int(rng() % 4); break;                       // subnormals and the smallest normals
    case 2: e = 251 + int(rng() % 5); break;                 // the largest binades, infinity
    case 3: case 4:
      if (near >= 0) {
        e = near + int(rng() % 61) - 30;                     // within the alignment range
        break;
      }
      [[fallthrough]];
    default: e = 1 + int(rng() % 254); break;                // any normal
  }
  e = e < 0 ? 0 : e > 255 ? 255 : e;
  uint32_t f;
  switch (rng() % 6) {
    case 0: f = 0; break;                                    // a power of two (or 0, inf)
    case 1: f = 0x7FFFFF; break;                             // all ones: carries
    case 2: f = (1u << (rng() % 23)) | ((rng() & 1) ? 1 : 0);  // one or two bits: ties
    case 3: f = 0x7FFFFF ^ (1u << (rng() % 23)); break;
    default: f = uint32_t(rng()) & 0x7FFFFF; break;
  }
  return sign | uint32_t(e) << 23 | f;
}

int field(uint32_t b) { return int((b >> 23) & 0xFF); }

struct Mul {
  Vrast_fp32_mul m;
  uint32_t rtl(uint32_t a, uint32_t b) { m.a_i = a, m.b_i = b, m.eval(); return m.f_o; }
  static uint32_t host(uint32_t a, uint32_t b) { return bits(value(a) * value(b)); }
  static const char* op() { return "*"; }
  // The second operand's exponent so that the product lands near the subnormal or
  // overflow range, half the time.
  static uint32_t second(std::mt19937_64& rng, uint32_t a) {
    if (rng() % 2) return pick(rng);
    const int target = (rng() % 2) ? int(rng() % 30) - 24 : 230 + int(rng() % 30);  // product's field
    return pick(rng, std::max(0, target - field(a) + 127));
  }
};

struct Add {
  Vrast_fp32_add m;
  uint32_t rtl(uint32_t a, uint32_t b) { m.a_i = a, m.b_i = b, m.eval(); return m.f_o; }
  static uint32_t host(uint32_t a, uint32_t b) { return bits(value(a) + value(b)); }
  static const char* op() { return "+"; }
  static uint32_t second(std::mt19937_64& rng, uint32_t a) {
    switch (rng() % 4) {
      case 0: return pick(rng);
      case 1: return (a ^ 0x80000000u) ^ uint32_t(rng() % 8);  // near cancellation
      default: return pick(rng, field(a));
    }
  }
};

template <class Unit>
void check_pair(Unit& u, uint32_t a, uint32_t b, int& mismatches) {
  const uint32_t got = u.rtl(a, b), want = Unit::host(a, b);
  if (same(got, want)) return;
  if (++mismatches <= 10)
    ADD_FAILURE() << show(a) << " " << Unit::op() << " " << show(b) << ": RTL " << show(got) << ", host " << show(want);
}

template <class Unit>
void check_binary(uint64_t salt) {
  Unit u;
  int mismatches = 0;
  const std::vector<uint32_t> edges = edge_cases();
  for (uint32_t a : edges)
    for (uint32_t b : edges) check_pair(u, a, b, mismatches);
  std::mt19937_64 rng(seed() ^ salt);
  for (int i = 0; i < kRandom; ++i) {
    const uint32_t a = pick(rng);
    check_pair(u, a, Unit::second(rng, a), mismatches);
  }
  EXPECT_EQ(mismatches, 0) << "of " << edges.size() * edges.size() + kRandom;
}

TEST(RtlFp32, Mul) { check_binary<Mul>(1); }
TEST(RtlFp32, Add) { check_binary<Add>(2); }

// Hand-worked roundings, independent of the host: ties to even, carries, underflow and
// overflow, where the exact result is known on paper.
TEST(RtlFp32, HandWorked) {
  struct Case {
    char op;  // '+' or '*'
    uint32_t a, b, want;
    const char* why;
  };
  const Case cases[] = {
      {'+', 0x3F800000, 0x33800000, 0x3F800000, "1 + 2^-24: halfway to 1 + 2^-23, ties to the even 1"},
      {'+', 0x3F800001, 0x33800000, 0x3F800002, "(1 + 2^-23) + 2^-24: halfway, ties to the even 1 + 2^-22"},
      {'+', 0x3F800000, 0xB3000000, 0x3F800000, "1 - 2^-25: halfway between 1 - 2^-24 and 1, to the even 1"},
      {'+', 0x3FC00000, 0xBFC00000, 0x00000000, "x + (-x) = +0"},
      {'+', 0x80000000, 0x80000000, 0x80000000, "-0 + -0 = -0"},
      {'+', 0x00800000, 0x807FFFFF, 0x00000001, "2^-126 - (2^-126 - 2^-149) = 2^-149, the smallest subnormal"},
      {'+', 0x7F7FFFFF, 0x73000000, 0x7F800000, "largest finite + half its ulp (2^103): a tie to the even 2^128, inf"},
      {'*', 0x3F800800, 0x3F800800, 0x3F801000, "(1 + 2^-12)^2 = 1 + 2^-11 + 2^-24: a tie, to the even 1 + 2^-11"},
      {'*', 0x1A000000, 0x1A000000, 0x00000000, "2^-75 * 2^-75 = 2^-150: halfway between 0 and 2^-149, to 0"},
      {'*', 0x1A400000, 0x1A000000, 0x00000001, "1.5 * 2^-75 * 2^-75 = 0.75 * 2^-149: above halfway, 2^-149"},
      {'*', 0x5F800000, 0x5F800000, 0x7F800000, "2^64 * 2^64 = 2^128: overflow to inf"},
      {'*', 0xDF800000, 0x5F800000, 0xFF800000, "-2^64 * 2^64: -inf"},
      {'*', 0x7F800000, 0x00000000, 0x7FC00000, "inf * 0: NaN"},
      {'*', 0x80000000, 0x40400000, 0x80000000, "-0 * 3 = -0"},
  };
  Mul mul;
  Add add;
  for (const Case& c : cases) {
    const uint32_t got = c.op == '+' ? add.rtl(c.a, c.b) : mul.rtl(c.a, c.b);
    EXPECT_TRUE(same(got, c.want)) << c.why << ": RTL " << show(got) << ", expected " << show(c.want);
  }
}

struct Recip {
  Vrast_fp32_recip m;
  uint32_t rtl(uint32_t w) { m.w_i = w, m.eval(); return m.f_o; }
  static uint32_t host(uint32_t w) { return bits(1.0f / value(w)); }
};

TEST(RtlFp32, Recip) {
  Recip u;
  int mismatches = 0;
  auto check = [&](uint32_t w) {
    const uint32_t got = u.rtl(w), want = Recip::host(w);
    if (same(got, want)) return;
    if (++mismatches <= 10) ADD_FAILURE() << "1 / " << show(w) << ": RTL " << show(got) << ", host " << show(want);
  };
  for (uint32_t w : edge_cases()) check(w);
  // Every significand of three binades: the normal 1 / w, the one whose reciprocal is
  // subnormal, and a subnormal w (1 / w overflows or is huge).
  for (uint32_t f = 0; f < (1u << 23); f += 7) {
    check(0x3F800000 | f);
    check(0x7E800000 | f);
    check(f);
  }
  std::mt19937_64 rng(seed() ^ 3);
  for (int i = 0; i < kRandom; ++i) check(pick(rng));
  EXPECT_EQ(mismatches, 0);
  // Hand-worked: 1 / 3 = 0x3EAAAAAB (0.0101... rounds up), 1 / 2^-149 overflows,
  // 1 / 2^127 = 2^-127 = 2^22 * 2^-149, a subnormal; 1 / -0 = -inf.
  EXPECT_EQ(u.rtl(0x40400000), 0x3EAAAAABu);
  EXPECT_EQ(u.rtl(0x00000001), 0x7F800000u);
  EXPECT_EQ(u.rtl(0x7F000000), 0x00400000u);
  EXPECT_EQ(u.rtl(0x80000000), 0xFF800000u);
}

// ---- rast_front_end_xform against docs/clip-space.md's operation order ----

struct State {
  float vx, vy, vw, vh, near, far;  // viewport_xform X Y W H, depth_range N F
};
struct Window {
  float x, y, z, inv_w;
};

// The doc's order, each operation one binary32 rounding (-ffp-contract=off).
Window xform_ref(const State& s, float x, float y, float z, float w) {
  const float q = 1.0f / w;
  const float half_w = s.vw / 2, half_h = s.vh / 2;
  const float center_x = s.vx + half_w, center_y = s.vy + half_h, depth_scale = s.far - s.near;
  return {(x * q) * half_w + center_x, (y * q) * half_h + center_y, (z * q) * depth_scale + s.near, q};
}

State pick_state(std::mt19937_64& rng) {
  if (rng() % 8 == 0)  // anything at all, to reach every path of the constants' units
    return {value(pick(rng)), value(pick(rng)), value(pick(rng)), value(pick(rng)), value(pick(rng)), value(pick(rng))};
  auto range = [&](int lo, int hi) { return float(lo + int(rng() % uint64_t(hi - lo + 1))); };
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  return {range(-4096, 4096), range(-4096, 4096), range(1, 16384), range(1, 16384), unit(rng), unit(rng)};
}

// A clip-space vertex: mostly inside or near the view volume with w from tiny to huge,
// some raw bit patterns.
std::array<float, 4> pick_vertex(std::mt19937_64& rng) {
  if (rng() % 8 == 0) return {value(pick(rng)), value(pick(rng)), value(pick(rng)), value(pick(rng))};
  const float w = value(pick(rng) & 0x7FFFFFFFu);
  std::uniform_real_distribution<float> ndc(-1.5f, 1.5f), depth(-0.25f, 1.25f);
  return {ndc(rng) * w, ndc(rng) * w, depth(rng) * w, w};
}

// Random stalls on both sides; the state changes only while the pipeline is empty (the
// module's contract). Every vertex out is the next one in, transformed, and with the
// output always ready a vertex leaves exactly 4 cycles after it entered.
TEST(RtlFp32, FrontEndXform) {
  Vrast_front_end_xform m;
  std::mt19937_64 rng(seed() ^ 4);
  auto tick = [&] { rastsim::test::clock_cycle(m); };
  rastsim::test::reset_stream(m);
  struct InFlight {
    std::array<float, 4> v;
    long entered;
  };
  std::deque<InFlight> queue;
  State st{};
  int mismatches = 0, checked = 0, taken = 0, latency_errors = 0;
  bool stalls = false;
  long cycle = 0;
  // The vertex on the outputs this cycle: the oldest in flight, transformed.
  auto check_out = [&] {
    ASSERT_FALSE(queue.empty()) << "a vertex out that never went in, cycle " << cycle;
    const InFlight f = queue.front();
    queue.pop_front();
    const Window want = xform_ref(st, f.v[0], f.v[1], f.v[2], f.v[3]);
    const uint32_t got[4] = {m.x_w_o, m.y_w_o, m.z_w_o, m.inv_w_o};
    const float wants[4] = {want.x, want.y, want.z, want.inv_w};
    for (int c = 0; c < 4; ++c)
      if (!same(got[c], bits(wants[c])) && ++mismatches <= 10)
        ADD_FAILURE() << "vertex (" << f.v[0] << ", " << f.v[1] << ", " << f.v[2] << ", " << f.v[3] << ") output "
                      << "xyzq"[c] << ": RTL " << show(got[c]) << ", reference " << show(bits(wants[c]));
    latency_errors += !stalls && cycle - f.entered != 4;
    ++checked;
  };
  auto put = [](uint32_t& port, float f) { port = bits(f); };
  auto drain = [&] {
    while (!queue.empty()) {
      m.in_valid_i = 0, m.out_ready_i = 1;
      m.eval();
      if (m.out_valid_o) check_out();
      tick(), ++cycle;
    }
  };
  for (int batch = 0; batch < 2000; ++batch) {
    drain();  // before the state changes
    st = pick_state(rng);
    put(m.vp_x_i, st.vx), put(m.vp_y_i, st.vy), put(m.vp_w_i, st.vw), put(m.vp_h_i, st.vh);
    put(m.depth_near_i, st.near), put(m.depth_far_i, st.far);
    stalls = batch % 2 == 1;
    for (int k = 0; k < 100; ++k) {
      const std::array<float, 4> v = pick_vertex(rng);
      m.in_valid_i = !stalls || rng() % 4 != 0;
      m.out_ready_i = !stalls || rng() % 3 != 0;
      put(m.x_i, v[0]), put(m.y_i, v[1]), put(m.z_i, v[2]), put(m.w_i, v[3]);
      m.eval();
      const bool take = m.in_valid_i && m.in_ready_o;
      if (m.out_valid_o && m.out_ready_i) check_out();
      if (take) queue.push_back({v, cycle}), ++taken;
      tick(), ++cycle;
    }
  }
  drain();
  EXPECT_FALSE(m.out_valid_o);
  EXPECT_EQ(mismatches, 0) << "of " << checked << " vertices";
  EXPECT_EQ(latency_errors, 0);
  EXPECT_EQ(checked, taken);  // none lost
  EXPECT_GT(taken, 150000);
  std::printf("%d vertices in %ld cycles\n", checked, cycle);
}

}  // namespace
