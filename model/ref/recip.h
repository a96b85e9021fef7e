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

namespace rastsim {

inline constexpr int kRecipFracBits = 40;  // width of the normalised divisor and of y's fraction

// Seed table entry `index` (0 <= index < 2^seed_bits) in units of 2^-(seed_bits + 1):
// round_nearest_even(2^(2b+3) / (2^(b+1) + 2 index + 1)), the reciprocal of the
// interval's midpoint x = 1/2 + (index + 1/2) / 2^(b+1).
uint64_t recip_seed_entry(uint64_t index, int seed_bits);

// y ~ 2^80 / d for d in [2^39, 2^40): the seed (1 <= seed_bits <= 16) and `iterations`
// Newton-Raphson steps, as above.
uint64_t recip_newton(uint64_t d, int seed_bits, int iterations);

}  // namespace rastsim
