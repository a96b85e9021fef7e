// SPDX-License-Identifier: Apache-2.0
// The texture cache (rtl/rast_texture_cache.sv) against the reference: its hits, misses
// and fills against SetAssocCache (model/ref/memory/cache.h, the reference texture unit's
// cache: one access a texel, in texel order) and its texels against decode_texel
// (model/ref/texture/texture.h) of a memory image, at each verilated parameter set
// (texture_cache_sets.h). The memory image is a hash of the byte address, so any address
// of AddrW bits has a byte.
//
// Streams (each from reset):
// - random: 1..4 texels a request (mostly 1 and 4), any format, addresses in a window a few
//   times the cache (neighbours of texel 0 mostly, as a bilinear footprint) and one in 16
//   anywhere in the address space (tags' high bits);
// - real: bilinear samples of a rotated, minified 256 x 256 texture over a 40 x 40 pixel
//   patch, every layout, the texels and their addresses by the reference's texel_quad and
//   texel_offset (the reference texture unit's fetch sequence for such a draw);
// each twice: with random gaps, response stalls, fill request stalls, 0..6 cycles of fill
// latency and gaps between beats; and with nothing stalled and a memory that takes a
// request at once and sends a beat every cycle. Checked: every response's texels, the
// fills' line addresses in order, the hit and miss counts (evt_hits_o, evt_miss_o) and,
// unstalled, the cycles against the hand count of docs/texture.md.
// The seed is printed; RASTSIM_TEXTURE_CACHE_SEED=<n> replays a run, =random draws a new one.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <random>
#include <vector>

#include "common/rtl_unit_test.h"
#include "ref/memory/cache.h"
#include "ref/texture/texture.h"
#include "ref/texture/texture_unit.h"
#include "rtlsim/port_bits.h"
#include "texture_cache_sets.h"

namespace {

using rastsim::CacheParams;
using rastsim::decode_texel;
using rastsim::Rgba8;
using rastsim::SetAssocCache;
using rastsim::TexelFormat;
using rastsim::TexLayout;
using rastsim::rtlsim::port_bits;
using rastsim::rtlsim::set_port_bits;

uint64_t seed() {
  static const uint64_t s = rastsim::test::seed_from_env("RASTSIM_TEXTURE_CACHE_SEED", 28);
  return s;
}

struct CacheSet {
  int addr_w, cache_bytes, ways, line_bytes, ports, beat_bytes;
  int beats() const { return line_bytes / beat_bytes; }
  uint64_t addr_mask() const { return addr_w >= 64 ? ~uint64_t{0} : (uint64_t{1} << addr_w) - 1; }
};

// The memory image: byte a's value, a hash of a (splitmix64's finaliser).
uint8_t mem_byte(uint64_t a) {
  uint64_t z = a + 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return uint8_t(z ^ (z >> 31));
}

struct Request {
  int count = 1;
  int format = 0;  // TexelFormat's order: 0 rgba8888, 1 rgb565, 2 l8
  uint64_t addr[4] = {};
};

// What the reference expects of a stream: each request's 4 texels (0 past its count),
// the fills' line addresses, hits and misses; and the lookup groups of the hand count
// (docs/texture.md): a texel starts a group when it is its request's first, misses, or
// follows a full group of Ports.
struct Expected {
  std::vector<std::array<uint32_t, 4>> texels;
  std::vector<uint64_t> fills;
  uint64_t hits = 0, misses = 0, groups = 0;
};

Expected expect(const CacheSet& c, const std::vector<Request>& reqs) {
  SetAssocCache cache(CacheParams{uint64_t(c.cache_bytes), c.ways, c.line_bytes});
  Expected e;
  for (const Request& r : reqs) {
    std::array<uint32_t, 4> t{};
    const auto f = TexelFormat(r.format);
    const int count = std::min(r.count, 4);  // 0: nothing looked up, a response of zeros; 5..7 as 4
    int in_group = 0;
    if (count == 0) ++e.groups;  // a lookup cycle that takes nothing
    for (int k = 0; k < count; ++k) {
      SetAssocCache::Victim v;
      const bool hit = cache.access(r.addr[k] / uint64_t(c.line_bytes), false, v);
      if (k == 0 || !hit || in_group == c.ports) {
        ++e.groups;
        in_group = 0;
      }
      ++in_group;
      if (hit) {
        ++e.hits;
      } else {
        ++e.misses;
        e.fills.push_back(r.addr[k] / uint64_t(c.line_bytes) * uint64_t(c.line_bytes));
      }
      uint32_t stored = 0;
      for (int b = 0; b < rastsim::texel_bytes(f); ++b)
        stored |= uint32_t(mem_byte(r.addr[k] + uint64_t(b))) << (8 * b);
      const Rgba8 x = decode_texel(stored, f);
      t[size_t(k)] = uint32_t(x[0]) | uint32_t(x[1]) << 8 | uint32_t(x[2]) << 16 | uint32_t(x[3]) << 24;
    }
    e.texels.push_back(t);
  }
  return e;
}

// Handshake stalls: each a probability in 1/16 (0: never stalled).
struct Stalls {
  int req_gap = 0, rsp_stall = 0, mem_req_stall = 0, beat_gap = 0, max_latency = 0;
};

struct Result {
  std::vector<std::array<uint32_t, 4>> texels;
  std::vector<uint64_t> fills;
  uint64_t hits = 0, misses = 0;
  uint64_t cycles = 0;  // from the first request offered to the last response taken, inclusive
  int fill_protocol_errors = 0;  // a beat taken with no fill open
};

template <class M>
Result run(M& m, const CacheSet& c, const std::vector<Request>& reqs, const Stalls& st, std::mt19937_64& rng,
           bool do_reset = true) {
  auto chance = [&](int p16) { return p16 > 0 && int(rng() % 16) < p16; };
  if (do_reset) {
    m.rst_ni = 1, m.clk_i = 0, m.req_valid_i = 0, m.rsp_ready_i = 0, m.mem_req_ready_i = 0, m.mem_rsp_valid_i = 0;
    m.eval();
    m.rst_ni = 0, m.eval();
    m.rst_ni = 1, m.eval();
  }
  Result r;
  size_t next = 0;
  bool offering = false;
  struct Fill {
    uint64_t addr;
    int beat, wait;
  };
  std::deque<Fill> fills;
  for (uint64_t cycle = 0; r.texels.size() < reqs.size(); ++cycle) {
    if (cycle > 200000 + 200 * reqs.size()) {
      ADD_FAILURE() << "no progress: " << r.texels.size() << " of " << reqs.size() << " responses";
      return r;
    }
    if (!offering && next < reqs.size() && !chance(st.req_gap)) {
      offering = true;
      const Request& q = reqs[next];
      for (int k = 0; k < 4; ++k) set_port_bits(m.req_addr_i, k * c.addr_w, c.addr_w, q.addr[k] & c.addr_mask());
      m.req_count_i = uint8_t(q.count);
      m.req_format_i = uint8_t(q.format);
    }
    m.req_valid_i = offering;
    m.rsp_ready_i = !chance(st.rsp_stall);
    m.mem_req_ready_i = !chance(st.mem_req_stall);
    const bool beat = !fills.empty() && fills.front().wait == 0 && !chance(st.beat_gap);
    m.mem_rsp_valid_i = beat;
    if (beat)
      for (int b = 0; b < c.beat_bytes; ++b)
        set_port_bits(m.mem_rsp_data_i, 8 * b, 8,
                      mem_byte(fills.front().addr + uint64_t(fills.front().beat * c.beat_bytes + b)));
    m.clk_i = 0, m.eval();
    const bool req_hs = m.req_valid_i && m.req_ready_o, rsp_hs = m.rsp_valid_o && m.rsp_ready_i;
    const bool mreq_hs = m.mem_req_valid_o && m.mem_req_ready_i, beat_hs = beat && m.mem_rsp_ready_o;
    r.hits += m.evt_hits_o;
    r.misses += m.evt_miss_o;
    if (rsp_hs) {
      std::array<uint32_t, 4> t{};
      for (int k = 0; k < 4; ++k) t[size_t(k)] = uint32_t(port_bits(m.rsp_texels_o, 32 * k, 32));
      r.texels.push_back(t);
      r.cycles = cycle + 1;
    }
    if (!fills.empty() && fills.front().wait > 0) --fills.front().wait;
    if (beat_hs && ++fills.front().beat == c.beats()) fills.pop_front();
    if (mreq_hs) {
      const uint64_t a = port_bits(m.mem_req_addr_o, 0, c.addr_w);
      r.fills.push_back(a);
      fills.push_back({a, 0, st.max_latency > 0 ? int(rng() % uint64_t(st.max_latency + 1)) : 0});
    }
    if (req_hs) offering = false, ++next;
    m.clk_i = 1, m.eval();
  }
  return r;
}

// Random requests: texel 0 in a window of 4 caches at a random base, the others its
// neighbours (+1 texel, + a row of 64 texels) or anywhere in the window; 1 in 16 texels
// anywhere in the address space.
std::vector<Request> random_stream(const CacheSet& c, int n, std::mt19937_64& rng) {
  const uint64_t window = uint64_t(4 * c.cache_bytes);
  const uint64_t base = (rng() & c.addr_mask()) & ~(window - 1);
  std::vector<Request> out;
  static const int kCounts[] = {1, 4, 4, 1, 2, 3, 4, 1};
  for (int i = 0; i < n; ++i) {
    Request q;
    q.count = kCounts[rng() % 8];
    if (rng() % 64 == 0) q.count = int(rng() % 2) * 7;  // outside 1..4: 0 or 7
    q.format = int(rng() % 3);
    const uint64_t bytes = uint64_t(rastsim::texel_bytes(TexelFormat(q.format)));
    const uint64_t a0 = (rng() % window) / bytes * bytes;
    for (int k = 0; k < 4; ++k) {
      uint64_t off = a0 + uint64_t(k & 1) * bytes + uint64_t(k >> 1) * 64 * bytes;
      if (rng() % 4 == 0) off = rng() % window;
      uint64_t a = (base + off % window) & c.addr_mask();
      if (rng() % 16 == 0) a = rng() & c.addr_mask();
      q.addr[k] = a / bytes * bytes;
    }
    out.push_back(q);
  }
  return out;
}

// A textured patch's fetches: w x w pixels sampling a 256 x 256 texture with `layout`,
// rotated by 0.5 radians and minified 1.7 times, bilinear, repeat, by the reference's
// texel_quad and texel_offset (texel 0's base 0x10000 within the address space).
std::vector<Request> patch_stream(const CacheSet& c, TexLayout layout, int format, int w) {
  constexpr int kSide = 256, kFrac = 16;
  const int bytes = rastsim::texel_bytes(TexelFormat(format));
  const uint64_t base = 0x10000 & c.addr_mask() & ~uint64_t(c.line_bytes - 1);
  std::vector<Request> out;
  for (int y = 0; y < w; ++y)
    for (int x = 0; x < w; ++x) {
      const double u = 1.7 * (std::cos(0.5) * x - std::sin(0.5) * y) + 100.0;
      const double v = 1.7 * (std::sin(0.5) * x + std::cos(0.5) * y) + 20.0;
      const auto s = int32_t(std::lround(u / kSide * (1 << kFrac))), t = int32_t(std::lround(v / kSide * (1 << kFrac)));
      const rastsim::TexelQuad q = rastsim::texel_quad(s, t, kSide, kSide, kFrac, true, rastsim::TexWrap::Repeat,
                                                       rastsim::TexWrap::Repeat);
      Request r;
      r.count = q.count;
      r.format = format;
      for (int k = 0; k < q.count; ++k)
        r.addr[k] = (base + rastsim::texel_offset(layout, kSide, kSide, bytes, q.i[size_t(k)], q.j[size_t(k)])) &
                    c.addr_mask();
      out.push_back(r);
    }
  return out;
}

// Checks a run against the reference: every texel, the fills in order, the counts; on a
// difference one line of figures (texels mismatched, the first fill that differs).
void check(const Result& r, const Expected& e, const char* what) {
  size_t bad = 0, texels = 0;
  for (size_t i = 0; i < e.texels.size() && i < r.texels.size(); ++i)
    for (size_t k = 0; k < 4; ++k, ++texels)
      if (r.texels[i][k] != e.texels[i][k]) ++bad;
  size_t fill = 0;
  while (fill < r.fills.size() && fill < e.fills.size() && r.fills[fill] == e.fills[fill]) ++fill;
  const bool same = bad == 0 && r.texels.size() == e.texels.size() && r.fills == e.fills && r.hits == e.hits &&
                    r.misses == e.misses;
  EXPECT_TRUE(same) << what << ": " << bad << " of " << texels << " texel slots mismatched; " << r.texels.size()
                    << " responses of " << e.texels.size() << "; fills equal up to " << fill << " (RTL "
                    << r.fills.size() << ", reference " << e.fills.size() << "); hits " << r.hits << " (reference "
                    << e.hits << "), misses " << r.misses << " (reference " << e.misses << ")";
}

// The hand count of an unstalled run (immediate memory, every request offered back to
// back, every response taken): a cycle a lookup group, 2 + Beats more a miss (its lookup,
// the fill request, the beats), and 3 (the offer's cycle, data read and decode).
uint64_t hand_cycles(const CacheSet& c, const Expected& e) {
  return e.groups + e.misses * uint64_t(2 + c.beats()) + 3;
}

const Stalls kStalled{4, 5, 6, 4, 6};
const Stalls kFree{};

template <class M>
void random_streams(const CacheSet& c) {
  std::mt19937_64 rng(seed() ^ uint64_t(c.cache_bytes * 131 + c.ports));
  M m;
  uint64_t texels = 0, hits = 0, misses = 0;
  for (int s = 0; s < 8; ++s) {
    const std::vector<Request> reqs = random_stream(c, 1500, rng);
    const Expected e = expect(c, reqs);
    const Result r = run(m, c, reqs, s % 2 ? kFree : kStalled, rng);
    check(r, e, s % 2 ? "random, unstalled" : "random, stalled");
    if (s % 2) EXPECT_EQ(r.cycles, hand_cycles(c, e)) << "groups + misses (2 + Beats) + 3";
    for (const auto& r : reqs) texels += uint64_t(std::min(r.count, 4));
    hits += e.hits, misses += e.misses;
  }
  std::printf("random: %llu texels, %llu hits, %llu misses\n", (unsigned long long)texels, (unsigned long long)hits,
              (unsigned long long)misses);
  EXPECT_GT(hits, texels / 8);  // the streams reach both outcomes
  EXPECT_GT(misses, texels / 50);
}

template <class M>
void patch_streams(const CacheSet& c) {
  std::mt19937_64 rng(seed() + 7);
  M m;
  const TexLayout layouts[] = {TexLayout::Linear, TexLayout::Tiled, TexLayout::Morton};
  for (int li = 0; li < 3; ++li) {
    const std::vector<Request> reqs = patch_stream(c, layouts[li], li, 40);
    const Expected e = expect(c, reqs);
    std::printf("patch layout %d: %zu samples, %llu hits, %llu misses\n", li, reqs.size(),
                (unsigned long long)e.hits, (unsigned long long)e.misses);
    check(run(m, c, reqs, kStalled, rng), e, "patch, stalled");
    const Result r = run(m, c, reqs, kFree, rng);
    check(r, e, "patch, unstalled");
    EXPECT_EQ(r.cycles, hand_cycles(c, e)) << "groups + misses (2 + Beats) + 3";
  }
}

// Cycles (docs/texture.md): requests whose texels all hit, offered back to back with every
// response taken, take sum ceil(count / Ports) + 3 cycles from the first offer to the last
// response, inclusive; nearest requests with M misses and an immediate memory (a request
// taken at once, a beat every cycle from the next) N + M (2 + Beats) + 3.
template <class M>
void cycles(const CacheSet& c) {
  std::mt19937_64 rng(seed() + 11);
  M m;
  // A contiguous cache's worth of bytes fills every way of every set once: after a warm-up
  // over it, every access there hits.
  std::vector<Request> warm;
  for (int a = 0; a < c.cache_bytes; a += c.line_bytes) warm.push_back(Request{1, 0, {uint64_t(a), 0, 0, 0}});
  run(m, c, warm, kFree, rng);
  std::vector<Request> hot;
  uint64_t hand = 3;
  for (int i = 0; i < 500; ++i) {
    Request q;
    q.count = 1 + int(rng() % 4);
    q.format = int(rng() % 3);
    for (int k = 0; k < 4; ++k) q.addr[k] = rng() % uint64_t(c.cache_bytes) / 4 * 4;
    hand += uint64_t((q.count + c.ports - 1) / c.ports);
    hot.push_back(q);
  }
  const Result h = run(m, c, hot, kFree, rng, false);
  EXPECT_EQ(h.misses, 0u);
  EXPECT_EQ(h.cycles, hand) << "hits: sum ceil(count / Ports) + 3";
  // Nearest from reset over 4 caches' worth of bytes.
  std::vector<Request> near;
  for (int i = 0; i < 1000; ++i) near.push_back(Request{1, 0, {rng() % uint64_t(4 * c.cache_bytes) / 4 * 4, 0, 0, 0}});
  const Expected e = expect(c, near);
  const Result n = run(m, c, near, kFree, rng);
  check(n, e, "nearest, unstalled");
  EXPECT_EQ(e.groups, near.size());
  EXPECT_EQ(n.cycles, near.size() + e.misses * uint64_t(2 + c.beats()) + 3) << "N + M (2 + Beats) + 3";
  std::printf("cycles: %zu hot requests %llu cycles; %zu nearest, %llu misses, %llu cycles\n", hot.size(),
              (unsigned long long)h.cycles, near.size(), (unsigned long long)e.misses, (unsigned long long)n.cycles);
}

#define RAST_TEXTURE_CACHE_TESTS(name, aw, bytes, ways, line, ports, beat)                  \
  TEST(RtlTextureCache, Random_##name) {                                                     \
    random_streams<Vrast_texture_cache_##name>({aw, bytes, ways, line, ports, beat});        \
  }                                                                                          \
  TEST(RtlTextureCache, Patch_##name) {                                                      \
    patch_streams<Vrast_texture_cache_##name>({aw, bytes, ways, line, ports, beat});         \
  }                                                                                          \
  TEST(RtlTextureCache, Cycles_##name) { cycles<Vrast_texture_cache_##name>({aw, bytes, ways, line, ports, beat}); }
RAST_TEXTURE_CACHE_SETS(RAST_TEXTURE_CACHE_TESTS)

// decode_texel (the RTL's reference) by hand: each channel's extremes and a mid value.
TEST(RtlTextureCache, DecodeTexelByHand) {
  EXPECT_EQ(decode_texel(0x11223344u, TexelFormat::Rgba8888), (Rgba8{0x44, 0x33, 0x22, 0x11}));
  EXPECT_EQ(decode_texel(0xf800u, TexelFormat::Rgb565), (Rgba8{255, 0, 0, 255}));
  EXPECT_EQ(decode_texel(0x07e0u, TexelFormat::Rgb565), (Rgba8{0, 255, 0, 255}));
  EXPECT_EQ(decode_texel(0x001fu, TexelFormat::Rgb565), (Rgba8{0, 0, 255, 255}));
  // R5 16 -> 128 + 4, G6 32 -> 128 + 2, B5 16 -> 132; the bits above 16 ignored.
  EXPECT_EQ(decode_texel(0xabcd8410u, TexelFormat::Rgb565), (Rgba8{132, 130, 132, 255}));
  EXPECT_EQ(decode_texel(0x1234u, TexelFormat::L8), (Rgba8{0x34, 0x34, 0x34, 255}));
  // encode_texel: 200 in 5 bits (200 x 31 + 127) / 255 = 24, in 6 bits (200 x 63 + 127) / 255 = 49.
  EXPECT_EQ(rastsim::encode_texel({200, 200, 200, 7}, TexelFormat::Rgb565), (24u << 11) | (49u << 5) | 24u);
}

}  // namespace
