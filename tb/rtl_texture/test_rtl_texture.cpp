// SPDX-License-Identifier: Apache-2.0
// The texture unit's datapath units (rtl/rast_texture_{lod,address,filter,combine}.sv)
// against the reference's sampler functions (ref/texture/texture.h: texture_lod and
// choose_levels, texel_quad, texture_unit.h's texel_offset, filter_texels and
// blend_levels, texenv_combine), sample by sample, and their cycles against the hand
// count (docs/texture.md, "RTL").
//
// Each unit gets a stream of random samples: half the runs offer one every cycle and take
// every output (then the run's cycles are N + the latency: one sample a cycle), the other
// half leave random gaps and stall the output at random. The inputs mix the whole range
// with the cases where a rounding or a wrap turns: exact texel edges and bilinear weight
// ties (power-of-two sides, so s W hits them exactly), coordinates in a few repeats
// either side, every wrap, layout and format, derivatives at and around powers of two
// (the log2's steps) and biases that put lambda on a level's rounding tie.
// The seed is printed; RASTSIM_TEXTURE_SEED=<n> replays a run, =random draws a new one.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <deque>
#include <functional>
#include <random>
#include <vector>

#include "common/rtl_unit_test.h"
#include "ref/texture/texture.h"
#include "ref/texture/texture_unit.h"
#include "rtlsim/port_bits.h"
#include "texture_models.h"

namespace {

using rastsim::rtlsim::port_bits;
using rastsim::rtlsim::set_port_bits;

uint64_t seed() {
  static const uint64_t s = rastsim::test::seed_from_env("RASTSIM_TEXTURE_SEED", 28);
  return s;
}

// One unit's stream: `n` samples offered in order (set(m, k) drives sample k's inputs),
// each output taken checked by check(m, k) (false: a mismatch, reported). Returns the
// cycles from the first offer to the last output taken. With `stalls`, random gaps
// between offers and random cycles with out_ready low.
template <class Model>
uint64_t run_stream(Model& m, size_t n, const std::function<void(Model&, size_t)>& set,
                    const std::function<bool(Model&, size_t)>& check, std::mt19937_64& rng, bool stalls) {
  rastsim::test::reset_stream(m);
  size_t offered = 0, taken = 0, mismatches = 0;
  uint64_t cycles = 0;
  while (taken < n && cycles < 20 * n + 100) {
    const bool offer = offered < n && (!stalls || rng() % 4 != 0);
    m.in_valid_i = offer;
    if (offer) set(m, offered);
    m.out_ready_i = !stalls || rng() % 3 != 0;
    m.clk_i = 0, m.eval();
    if (m.out_valid_o && m.out_ready_i) {
      if (!check(m, taken) && ++mismatches <= 10) ADD_FAILURE() << "sample " << taken << " differs";
      ++taken;
    }
    if (offer && m.in_ready_o) ++offered;
    m.clk_i = 1, m.eval();
    ++cycles;
  }
  EXPECT_EQ(taken, n) << "outputs missing after " << cycles << " cycles";
  EXPECT_EQ(mismatches, 0u);
  return cycles;
}

// Both kinds of run of one unit: unstalled (cycles = n + latency) and (stalled_too) stalled.
template <class Model>
void run_both(size_t n, int latency, bool stalled_too, const std::function<void(Model&, size_t)>& set,
              const std::function<bool(Model&, size_t)>& check, std::mt19937_64& rng) {
  for (const bool stalls : {false, true}) {
    if (stalls && !stalled_too) break;
    Model m;
    const uint64_t cycles = run_stream<Model>(m, n, set, check, rng, stalls);
    if (!stalls) EXPECT_EQ(cycles, n + uint64_t(latency)) << "one sample a cycle, latency " << latency;
  }
}

int64_t uniform(std::mt19937_64& rng, int64_t lo, int64_t hi) {
  return std::uniform_int_distribution<int64_t>(lo, hi)(rng);
}

// A texture side: small ones often (odd included), powers of two (exact ties), any up to 16384.
int random_side(std::mt19937_64& rng) {
  switch (rng() % 4) {
    case 0: return int(uniform(rng, 1, 8));
    case 1: return 1 << uniform(rng, 0, 14);
    case 2: return int(uniform(rng, 1, 64));
    default: return int(uniform(rng, 1, 16384));
  }
}

}  // namespace

namespace {

// ---- rast_texture_lod ----
namespace lp = rast_texture_lod_params;

struct LodSample {
  rastsim::QuadDerivatives d;
  int width = 1, height = 1, levels = 1;
  int32_t bias = 0;
  bool trilinear = false;
  rastsim::LevelChoice want;  // the reference's
};

// A derivative: zero, anywhere in the range of a difference of two TexW-bit coordinates,
// or at and around a power of two (the log2's steps).
int64_t random_derivative(std::mt19937_64& rng) {
  const int64_t max = (int64_t{1} << lp::TexW) - 1;
  int64_t v = 0;
  switch (rng() % 4) {
    case 0: v = rng() % 3 == 0 ? 0 : uniform(rng, -4, 4); break;
    case 1: v = uniform(rng, -max, max); break;
    case 2: v = (int64_t{1} << uniform(rng, 0, lp::TexW - 1)) + uniform(rng, -2, 2); break;
    default: v = uniform(rng, 0, int64_t{1} << lp::TexFrac) >> uniform(rng, 0, lp::TexFrac); break;
  }
  v = std::clamp<int64_t>(v, -max, max);
  return rng() % 2 ? -v : v;
}

LodSample random_lod_sample(std::mt19937_64& rng) {
  LodSample s;
  s.d = {random_derivative(rng), random_derivative(rng), random_derivative(rng), random_derivative(rng)};
  if (rng() % 16 == 0) s.d = {};  // rho = 0: lambda -infinity
  s.width = random_side(rng), s.height = random_side(rng);
  const bool mipmap = rng() % 4 != 0;
  s.levels = mipmap ? int(std::bit_width(unsigned(std::max(s.width, s.height)))) : 1;
  s.trilinear = rng() % 2;
  const int32_t max_bias = rastsim::kMaxLodBias * 256;
  s.bias = int32_t(uniform(rng, -max_bias, max_bias));
  const int32_t lambda = s.levels > 1 ? rastsim::texture_lod(s.d, s.width, s.height, lp::TexFrac) : 0;
  if (rng() % 3 == 0 && lambda > rastsim::kLodMinusInfinity) {
    // lambda + bias on a level's rounding tie (nearest: 127/128; trilinear: a whole level).
    const int32_t target = int32_t(uniform(rng, 0, s.levels)) * 256 + int32_t(uniform(rng, 126, 130)) % 256;
    s.bias = std::clamp(target - lambda, -max_bias, max_bias);
  }
  s.want = rastsim::choose_levels(lambda, s.bias, s.levels,
                                  s.trilinear ? rastsim::TexFilter::Trilinear : rastsim::TexFilter::Bilinear);
  return s;
}

TEST(RtlTexture, LodEqualsReference) {
  std::mt19937_64 rng(seed());
  std::vector<LodSample> v(20000);
  for (auto& s : v) s = random_lod_sample(rng);
  const uint64_t mask = (uint64_t{1} << (lp::TexW + 1)) - 1;
  int rho_zero = 0, whole_levels = 0;
  for (const auto& s : v) rho_zero += s.levels > 1 && rastsim::texture_lod(s.d, s.width, s.height, lp::TexFrac) ==
                                                           rastsim::kLodMinusInfinity;
  for (const auto& s : v) whole_levels += s.trilinear && s.levels > 1 && s.want.frac == 0;
  using M = Vrast_texture_lod;
  run_both<M>(v.size(), 3, true,
      [&](M& m, size_t k) {
        const LodSample& s = v[k];
        m.dsdx_i = uint32_t(uint64_t(s.d.dsdx) & mask), m.dtdx_i = uint32_t(uint64_t(s.d.dtdx) & mask);
        m.dsdy_i = uint32_t(uint64_t(s.d.dsdy) & mask), m.dtdy_i = uint32_t(uint64_t(s.d.dtdy) & mask);
        m.width_i = uint16_t(s.width), m.height_i = uint16_t(s.height), m.levels_i = uint8_t(s.levels);
        m.bias_i = uint16_t(uint32_t(s.bias) & ((1u << lp::BiasW) - 1)), m.trilinear_i = s.trilinear;
      },
      [&](M& m, size_t k) {
        const auto& w = v[k].want;
        return m.level0_o == w.level0 && m.level1_o == w.level1 && m.frac_o == w.frac;
      },
      rng);
  // The mix reached the corners it was drawn for.
  EXPECT_GT(rho_zero, 50);
  EXPECT_GT(whole_levels, 500);
}

}  // namespace

namespace {

// ---- rast_texture_address ----
struct AddressParams {
  int tex_w, tex_frac, weight_bits, size_w, addr_w;
};

struct AddressSample {
  int32_t s = 0, t = 0;
  int width = 1, height = 1;
  bool bilinear = false;
  rastsim::TexWrap wrap_s{}, wrap_t{};
  rastsim::TexLayout layout{};
  rastsim::TexelFormat format{};
  uint64_t base = 0;
  rastsim::TexelQuad want;            // the reference's texels and weights
  std::array<uint64_t, 4> addr{};     // their byte addresses
};

// A coordinate on an axis of n texels: anywhere, within a few repeats, on or next to a
// texel edge, or on or next to a bilinear weight tie (u - 1/2 halfway between two
// 2^-B steps): exact where n divides the raw value (powers of two).
int32_t random_coordinate(std::mt19937_64& rng, int n, const AddressParams& p) {
  const int64_t one = int64_t{1} << p.tex_frac, lo = -(int64_t{1} << (p.tex_w - 1)), hi = -lo - 1;
  int64_t s = 0;
  switch (rng() % 4) {
    case 0: s = uniform(rng, lo, hi); break;
    case 1: s = uniform(rng, -3 * one, 4 * one); break;
    case 2: s = uniform(rng, -3 * int64_t(n), 4 * int64_t(n)) * one / n + uniform(rng, -1, 1); break;
    default: {
      const int b = p.weight_bits;
      const int64_t i = uniform(rng, -3 * int64_t(n), 4 * int64_t(n)), k = uniform(rng, 0, (int64_t{1} << b) - 1);
      const int64_t u = (i * (int64_t{2} << b) + (int64_t{1} << b) + 2 * k + 1) << (p.tex_frac - b - 1);  // 2^-F texels
      s = u / n + (rng() % 2 ? 0 : uniform(rng, -1, 1));
    }
  }
  return int32_t(std::clamp(s, lo, hi));
}

AddressSample random_address_sample(std::mt19937_64& rng, const AddressParams& p) {
  AddressSample a;
  a.width = random_side(rng), a.height = random_side(rng);
  a.s = random_coordinate(rng, a.width, p), a.t = random_coordinate(rng, a.height, p);
  a.bilinear = rng() % 4 != 0;
  a.wrap_s = rastsim::TexWrap(rng() % 3), a.wrap_t = rastsim::TexWrap(rng() % 3);
  a.layout = rastsim::TexLayout(rng() % 3), a.format = rastsim::TexelFormat(rng() % 3);
  a.base = uint64_t(uniform(rng, 0, (int64_t{1} << 32) - 1)) << 8;  // 256-byte aligned, below 2^40
  a.want = rastsim::texel_quad(a.s, a.t, a.width, a.height, p.tex_frac, a.bilinear, a.wrap_s, a.wrap_t, p.weight_bits);
  const int bytes = rastsim::texel_bytes(a.format);
  for (size_t k = 0; k < size_t(a.want.count); ++k)
    a.addr[k] = a.base + rastsim::texel_offset(a.layout, a.width, a.height, bytes, a.want.i[k], a.want.j[k]);
  return a;
}

// An exact bilinear weight tie on s: s W 2^B - 2^(F+B-1) + 2^(F-1) a multiple of 2^F.
bool weight_tie(const AddressSample& a, const AddressParams& p) {
  const int64_t x = (int64_t(a.s) * a.width << p.weight_bits) - (int64_t{1} << (p.tex_frac + p.weight_bits - 1)) +
                    (int64_t{1} << (p.tex_frac - 1));
  return a.bilinear && (x & ((int64_t{1} << p.tex_frac) - 1)) == 0;
}

template <class M>
bool address_matches(M& m, const AddressSample& a, const AddressParams& p) {
  const int ix = p.size_w - 1;
  bool ok = m.alpha_o == (a.bilinear ? a.want.alpha : 0) && m.beta_o == (a.bilinear ? a.want.beta : 0);
  for (int k = 0; k < a.want.count; ++k) {
    ok = ok && int(port_bits(m.i_o, k * ix, ix)) == a.want.i[size_t(k)];
    ok = ok && int(port_bits(m.j_o, k * ix, ix)) == a.want.j[size_t(k)];
    ok = ok && port_bits(m.addr_o, k * p.addr_w, p.addr_w) == a.addr[size_t(k)];
  }
  return ok;
}

template <class M>
void address_test(const AddressParams& p, size_t n) {
  std::mt19937_64 rng(seed() + uint64_t(p.weight_bits));
  std::vector<AddressSample> v(n);
  for (auto& a : v) a = random_address_sample(rng, p);
  const uint64_t mask = (uint64_t{1} << p.tex_w) - 1;
  run_both<M>(v.size(), 4, true,
      [&](M& m, size_t k) {
        const AddressSample& a = v[k];
        m.s_i = uint32_t(uint64_t(int64_t(a.s)) & mask), m.t_i = uint32_t(uint64_t(int64_t(a.t)) & mask);
        m.width_i = uint16_t(a.width), m.height_i = uint16_t(a.height), m.bilinear_i = a.bilinear;
        m.wrap_s_i = uint8_t(a.wrap_s), m.wrap_t_i = uint8_t(a.wrap_t);
        m.layout_i = uint8_t(a.layout), m.format_i = uint8_t(a.format), m.base_i = a.base;
      },
      [&](M& m, size_t k) { return address_matches(m, v[k], p); }, rng);
  // The mix reached every wrap, layout and format with exact weight ties and edges among them.
  int ties = 0, wraps[3] = {}, layouts[3] = {}, formats[3] = {};
  for (const auto& a : v) {
    ties += weight_tie(a, p);
    ++wraps[int(a.wrap_s)], ++layouts[int(a.layout)], ++formats[int(a.format)];
  }
  EXPECT_GT(ties, int(n / 40));
  for (int k = 0; k < 3; ++k) EXPECT_GT(std::min({wraps[k], layouts[k], formats[k]}), int(n / 5));
}

TEST(RtlTexture, AddressEqualsReference) {
  namespace ap = rast_texture_address_params;
  address_test<Vrast_texture_address>({ap::TexW, ap::TexFrac, ap::WeightBits, ap::SizeW, ap::AddrW}, 30000);
}

TEST(RtlTexture, AddressEqualsReferenceAtThreeWeightBits) {
  namespace ap = rast_texture_address_w3_params;
  static_assert(ap::WeightBits == 3);
  address_test<Vrast_texture_address_w3>({ap::TexW, ap::TexFrac, ap::WeightBits, ap::SizeW, ap::AddrW}, 10000);
}

}  // namespace

namespace {

// ---- rast_texture_filter ----
struct FilterSample {
  std::array<rastsim::Rgba8, 4> texels{};
  rastsim::TexelQuad q;  // count, alpha, beta
  bool blend = false;
  rastsim::Rgba8 prev{};
  int frac = 0;
  rastsim::Rgba8 want{};
};

// A weight: the ends, the midpoint, or any.
int random_weight(std::mt19937_64& rng) {
  const int ends[] = {0, 1, 128, 254, 255};
  return rng() % 3 == 0 ? ends[rng() % 5] : int(rng() % 256);
}

// A channel: 0 or 255 (the largest rounding steps) or any.
uint8_t random_channel(std::mt19937_64& rng) {
  return rng() % 3 == 0 ? (rng() % 2 ? 255 : 0) : uint8_t(rng());
}

TEST(RtlTexture, FilterEqualsReference) {
  std::mt19937_64 rng(seed() + 100);
  std::vector<FilterSample> v(30000);
  for (auto& f : v) {
    for (auto& t : f.texels)
      for (auto& c : t) c = random_channel(rng);
    f.q.count = rng() % 4 == 0 ? 1 : 4;
    f.q.alpha = random_weight(rng), f.q.beta = random_weight(rng);
    f.blend = rng() % 2;
    for (auto& c : f.prev) c = random_channel(rng);
    f.frac = random_weight(rng);
    f.want = rastsim::filter_texels(f.q, f.texels);
    if (f.blend) f.want = rastsim::blend_levels(f.prev, f.want, f.frac);
  }
  const auto word = [](const rastsim::Rgba8& c) { return uint32_t(c[0] | c[1] << 8 | c[2] << 16 | uint32_t(c[3]) << 24); };
  using M = Vrast_texture_filter;
  run_both<M>(v.size(), 3, true,
      [&](M& m, size_t k) {
        const FilterSample& f = v[k];
        for (size_t t = 0; t < 4; ++t) m.texels_i[t] = word(f.texels[t]);
        m.alpha_i = uint8_t(f.q.alpha), m.beta_i = uint8_t(f.q.beta), m.bilinear_i = f.q.count == 4;
        m.blend_i = f.blend, m.prev_i = word(f.prev), m.frac_i = uint8_t(f.frac);
      },
      [&](M& m, size_t k) { return m.color_o == word(v[k].want); }, rng);
}

// ---- rast_texture_combine ----
struct CombineSample {
  rastsim::Rgba8 tex{};
  std::array<uint8_t, 3> color{};
  rastsim::TexEnv env{};
  std::array<uint8_t, 3> want{};
};

void run_combine(std::vector<CombineSample>& v, std::mt19937_64& rng, bool stalled_too = true) {
  for (auto& c : v) c.want = rastsim::texenv_combine(c.env, c.tex, c.color);
  using M = Vrast_texture_combine;
  run_both<M>(v.size(), 2, stalled_too,
      [&](M& m, size_t k) {
        const CombineSample& c = v[k];
        m.tex_i = uint32_t(c.tex[0] | c.tex[1] << 8 | c.tex[2] << 16 | uint32_t(c.tex[3]) << 24);
        m.color_i = uint32_t(c.color[0] | c.color[1] << 8 | c.color[2] << 16);
        m.env_i = uint8_t(c.env);
      },
      [&](M& m, size_t k) {
        const auto& w = v[k].want;
        return m.color_o == uint32_t(w[0] | w[1] << 8 | w[2] << 16);
      },
      rng);
}

TEST(RtlTexture, CombineEqualsReference) {
  std::mt19937_64 rng(seed() + 200);
  std::vector<CombineSample> v(30000);
  for (auto& c : v) {
    for (auto& x : c.tex) x = random_channel(rng);
    for (auto& x : c.color) x = random_channel(rng);
    c.env = rastsim::TexEnv(rng() % 3);
  }
  run_combine(v, rng);
}

// Every (T, C) of modulate and every (C, T, T_a) of decal: the quotient by 255 of every
// numerator either forms, three channels a sample (5.6 M decal samples).
TEST(RtlTexture, CombineEveryOperand) {
  std::mt19937_64 rng(seed() + 300);
  std::vector<CombineSample> v;
  for (int env = 1; env <= 2; ++env)
    for (uint32_t a = 0; a < (env == 2 ? 256u : 1u); ++a)
      for (uint32_t x = 0; x < 65536; x += 3) {  // (t, c) = (x & 255, x >> 8), channels x, x + 1, x + 2
        CombineSample c;
        c.env = rastsim::TexEnv(env);
        c.tex[3] = uint8_t(a);
        for (uint32_t ch = 0; ch < 3; ++ch) {
          const uint32_t y = std::min(x + ch, 65535u);
          c.tex[ch] = uint8_t(y), c.color[ch] = uint8_t(y >> 8);
        }
        v.push_back(c);
      }
  run_combine(v, rng, false);
}

}  // namespace
