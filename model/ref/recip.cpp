// SPDX-License-Identifier: Apache-2.0
#include "ref/recip.h"

#include "ref/fixed_point.h"

namespace rastsim {

uint64_t recip_seed_entry(uint64_t index, int seed_bits) {
  const i128 num = i128(1) << (2 * seed_bits + 3);
  const i128 den = (i128(1) << (seed_bits + 1)) + 2 * i128(index) + 1;
  return static_cast<uint64_t>(div_round(num, den, Rounding::NearestEven));
}

uint64_t recip_newton(uint64_t d, int seed_bits, int iterations) {
  constexpr int F = kRecipFracBits;
  // The b bits below d's leading one (bit F - 1) index the table.
  const uint64_t index = (d >> (F - 1 - seed_bits)) & ((uint64_t{1} << seed_bits) - 1);
  uint64_t y = recip_seed_entry(index, seed_bits) << (F - seed_bits - 1);
  for (int i = 0; i < iterations; ++i) {
    const uint64_t p = static_cast<uint64_t>((u128(d) * y) >> F);  // x y < 2: below 2^41
    const uint64_t c = (uint64_t{2} << F) - p;
    y = static_cast<uint64_t>((u128(y) * c) >> F);
  }
  return y;
}

}  // namespace rastsim
