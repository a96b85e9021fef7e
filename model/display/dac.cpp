// SPDX-License-Identifier: Apache-2.0
// Video DAC: palette lookup and the seeded INL/DNL mismatch model (equations in dac.h).
#include "display/dac.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

namespace rastsim {

namespace {

// INL curve of one channel: a walk from 0 back to 0 over max_code steps with every step
// in [-dnl, dnl] and every point within [-B_k, B_k], B_k = min(inl, (max_code - k) * dnl),
// so the walk can always return to 0 at the top code. Each step moves halfway toward
// a bow of amplitude inl (sign drawn) plus a uniform draw, then is clamped to the bounds.
std::vector<double> draw_inl(int max_code, double inl, double dnl, uint64_t seed) {
  std::vector<double> v(max_code + 1, 0.0);
  if (inl <= 0 || dnl <= 0) return v;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double sign = u(rng) < 0 ? -1.0 : 1.0;
  for (int k = 1; k <= max_code; ++k) {
    const double prev = v[k - 1];
    const double bound = std::min(inl, (max_code - k) * dnl);
    const double bow = sign * inl * std::sin(std::numbers::pi * k / max_code);
    const double pull = std::clamp(bow - prev, -dnl, dnl);
    const double step = 0.5 * pull + 0.5 * dnl * u(rng);
    const double lo = std::max(prev - dnl, -bound), hi = std::min(prev + dnl, bound);
    v[k] = std::clamp(prev + step, lo, hi);
  }
  return v;
}

}  // namespace

Dac::Dac(const DacConfig& c) : cfg_(c) {
  const int m = max_code();
  for (int v = 0; v < 256; ++v) {
    if (cfg_.lut == DacLut::Gamma)
      lut_[v] = static_cast<uint16_t>(std::lround(std::pow(v / 255.0, 1.0 / cfg_.gamma) * m));
    else
      lut_[v] = static_cast<uint16_t>((v * m + 127) / 255);  // round half up, exact integers
  }
  // Inverse: for every code the byte whose code is nearest (first on ties).
  inverse_.assign(m + 1, 0);
  for (int code = 0; code <= m; ++code) {
    int best = 0;
    for (int v = 1; v < 256; ++v)
      if (std::abs(lut_[v] - code) < std::abs(lut_[best] - code)) best = v;
    inverse_[code] = static_cast<uint8_t>(best);
  }
  for (int ch = 0; ch < 3; ++ch) {
    // One independent stream per channel, derived from the seed (splitmix-style spread).
    const uint64_t s = cfg_.seed * 0x9E3779B97F4A7C15ull + static_cast<uint64_t>(ch + 1) * 0xBF58476D1CE4E5B9ull;
    inl_[ch] = draw_inl(m, cfg_.inl_lsb, cfg_.dnl_lsb, s);
    levels_[ch].resize(m + 1);
    for (int code = 0; code <= m; ++code) levels_[ch][code] = (code + inl_[ch][code]) * lsb_volts();
  }
}

uint16_t level_to_code(double volts, int bits, double full_scale_volts) {
  const int m = (1 << bits) - 1;
  const long c = std::lround(volts / full_scale_volts * m);
  return static_cast<uint16_t>(std::clamp<long>(c, 0, m));
}

}  // namespace rastsim
