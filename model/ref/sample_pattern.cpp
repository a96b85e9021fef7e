// SPDX-License-Identifier: Apache-2.0
#include "ref/sample_pattern.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "ref/fixed_point.h"

namespace rastsim {

namespace {

using Offsets = std::array<std::array<int, 2>, kMaxSamples>;

// D3D11 "standard multisample quality levels" (D3D11_STANDARD_MULTISAMPLE_PATTERN), the
// same as Vulkan's standard sample locations; 1/16 pixel from the centre, y down.
constexpr Offsets k1 = {{{0, 0}}};
constexpr Offsets k2 = {{{4, 4}, {-4, -4}}};
constexpr Offsets k4 = {{{-2, -6}, {6, -2}, {-6, 2}, {2, 6}}};
constexpr Offsets k8 = {{{1, -3}, {-1, 3}, {5, 1}, {-3, -5}, {-5, 5}, {-7, -1}, {3, 7}, {7, -7}}};
constexpr Offsets k16 = {{{1, 1}, {-1, -3}, {-3, 2}, {4, -1}, {-5, -2}, {2, 5}, {5, 3}, {3, -5},
                          {-2, 6}, {0, -7}, {-4, -6}, {-6, 4}, {-8, 0}, {7, -4}, {6, 7}, {-7, -8}}};

constexpr int kMaxFrac = 62;

int count_index(int n) {
  switch (n) {
    case 1: return 0;
    case 2: return 1;
    case 4: return 2;
    case 8: return 3;
    case 16: return 4;
  }
  throw std::invalid_argument("sample count " + std::to_string(n) + " is not 1, 2, 4, 8 or 16");
}

// off/16 pixel in raw units of F fraction bits.
int64_t snap_offset(int off16, int frac_bits) {
  if (frac_bits >= 4) return int64_t(off16) << (frac_bits - 4);
  return static_cast<int64_t>(div_round(i128(off16), i128(1) << (4 - frac_bits), Rounding::NearestEven));
}

std::vector<SamplePattern> build_table() {
  std::vector<SamplePattern> table(5 * (kMaxFrac + 1));
  for (int n : {1, 2, 4, 8, 16}) {
    const Offsets& o = standard_sample_offsets_16th(n);
    for (int f = 1; f <= kMaxFrac; ++f) {
      SamplePattern& p = table[size_t(count_index(n) * (kMaxFrac + 1) + f)];
      p.count = n;
      for (int s = 0; s < n; ++s) {
        p.dx[size_t(s)] = snap_offset(o[size_t(s)][0], f);
        p.dy[size_t(s)] = snap_offset(o[size_t(s)][1], f);
      }
      p.dx_min = *std::min_element(p.dx.begin(), p.dx.begin() + n);
      p.dx_max = *std::max_element(p.dx.begin(), p.dx.begin() + n);
      p.dy_min = *std::min_element(p.dy.begin(), p.dy.begin() + n);
      p.dy_max = *std::max_element(p.dy.begin(), p.dy.begin() + n);
    }
  }
  return table;
}

}  // namespace

const Offsets& standard_sample_offsets_16th(int n) {
  switch (count_index(n)) {
    case 0: return k1;
    case 1: return k2;
    case 2: return k4;
    case 3: return k8;
    default: return k16;
  }
}

const SamplePattern& sample_pattern(int samples, int frac_bits) {
  static const std::vector<SamplePattern> table = build_table();
  if (frac_bits < 1 || frac_bits > kMaxFrac)
    throw std::invalid_argument("sample pattern: fraction bits " + std::to_string(frac_bits) + " outside 1..62");
  return table[size_t(count_index(samples) * (kMaxFrac + 1) + frac_bits)];
}

}  // namespace rastsim
