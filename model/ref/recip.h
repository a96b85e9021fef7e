// SPDX-License-Identifier: Apache-2.0
// The reciprocal unit of perspective-correct interpolation (interp.recip = "newton").
//
// - Input: a normalised divisor d in [2^39, 2^40), the fixed-point value x = d / 2^40 in
//   [1/2, 1) (interpolation takes the top 40 bits of sum_k e_k Q_k after a leading-zero
//   count; docs/clip-space.md, "Perspective-correct interpolation").
// - Seed: a table of 2^b entries (b = interp.recip_seed_bits) indexed by the b bits of d
//   below its leading one; entry i is 1 / (midpoint of its interval of x), rounded to
//   nearest even to b + 1 fraction bits: b + 2 bits wide (recip_seed_entry).
// - Newton-Raphson steps (interp.recip_iterations), all unsigned with 40 fraction bits
//   (kRecipFracBits), each product truncated (floor):
//     p = (d * y) >> 40           x y, 81-bit product, 41-bit result
//     c = 2^41 - p                2 - x y, in (0, 2^41)
//     y = (y * c) >> 40           y (2 - x y), 82-bit product, 41-bit result
// - Output: y in units of 2^-40, about 2^80 / d: 1 / x in (1, 2], 42 bits unsigned.
// The relative error of the seed is below about 2^-(b+1); a step squares it, and the
// truncations add at most a few units of 2^-40. The one definition the SystemC stage
// and the RTL mirror; the exact method (a divider) is the golden it is measured against.
#pragma once

#include <cstdint>

#include "ref/fixed_point.h"

namespace rastsim {

inline constexpr int kRecipFracBits = 40;  // width of the normalised divisor and of y's fraction

// Seed table entry `index` (0 <= index < 2^seed_bits) in units of 2^-(seed_bits + 1):
// round_nearest_even(2^(2b+3) / (2^(b+1) + 2 index + 1)), the reciprocal of the
// interval's midpoint x = 1/2 + (index + 1/2) / 2^(b+1).
uint64_t recip_seed_entry(uint64_t index, int seed_bits);

// y ~ 2^80 / d for d in [2^39, 2^40): the seed (1 <= seed_bits <= 16) and `iterations`
// Newton-Raphson steps, as above.
uint64_t recip_newton(uint64_t d, int seed_bits, int iterations);

// round_half_up(num / D) by the reciprocal unit, D > 0 of bit length L (below 2^91): the
// divisor's top kRecipFracBits bits d = floor(D 2^(40 - L)) and the numerator shifted
// alike, num' = floor(num 2^(40 - L)), then (num' y + 2^79) >> 80 with y ~ 2^80 / d.
// A |num'| >= 2^84 means a quotient beyond 2^43 (extrapolated far outside the triangle):
// returned as +-2^43, which the caller clamps to the attribute's range. num' y < 2^126.
// The divider of both perspective-correct interpolators (interpolate.cpp, homogeneous.cpp).
struct NewtonDivider {
  int shift = 0;  // L - 40
  uint64_t y = 0;
  NewtonDivider() = default;
  NewtonDivider(i128 den, int seed_bits, int iterations) {
    // Leading-zero count of den > 0 (below 2^91): its bit length L.
    const auto hi = static_cast<uint64_t>(den >> 64), lo = static_cast<uint64_t>(den);
    const int len = hi ? 128 - __builtin_clzll(hi) : 64 - __builtin_clzll(lo);
    shift = len - kRecipFracBits;
    const i128 d = shift >= 0 ? den >> shift : den << -shift;
    y = recip_newton(static_cast<uint64_t>(d), seed_bits, iterations);
  }
  // quotient(num, frac): round_half_up(num / (D 2^frac)), the same product rounded
  // frac bits higher, (num' y + 2^(79 + frac)) >> (80 + frac) (a colour of 8.F vertex values).
  i128 quotient(i128 num, int frac = 0) const {
    constexpr int kNumBits = 85;  // |num'| < 2^84
    const i128 sat = i128(1) << 43;
    if (shift < 0 && !fits_signed(num, kNumBits + shift)) return num < 0 ? -sat : sat;
    const i128 n = shift >= 0 ? num >> shift : num << -shift;  // >>: floor
    if (!fits_signed(n, kNumBits)) return n < 0 ? -sat : sat;
    const int F2 = 2 * kRecipFracBits + frac;
    return (n * i128(y) + (i128(1) << (F2 - 1))) >> F2;
  }
};

}  // namespace rastsim
