// SPDX-License-Identifier: Apache-2.0
// Fixed-point formats and the exact integer arithmetic every rastsim datapath uses.
//
// - FixedFormat: a signed s.I.F format (1 sign bit, I integer bits, F fraction bits),
//   parsed from config strings like "s7.16"; raw values are two's-complement integers
//   in units of 2^-F.
// - Q64: the scene's exact coordinate type (64 fraction bits, rounded *to odd* from
//   its source) so that one later round-to-nearest-even into any s.I.F with F <= 62
//   equals rounding the source value directly (no double rounding).
// - Narrowing helpers that name their rounding and report overflow instead of wrapping.
//
// Every product and sum in the model is kept at full precision in i128 (a 128-bit
// integer is wider than any datapath quantity for I + F <= 31, see docs/fixed-point.md);
// only explicit calls here narrow.
#pragma once

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace rastsim {

__extension__ typedef __int128 i128;
__extension__ typedef unsigned __int128 u128;

// A signed fixed-point format s.I.F. Total width 1 + I + F bits.
struct FixedFormat {
  int int_bits = 0;   // I (raster.coord_format gives both; no default here)
  int frac_bits = 0;  // F

  // Accepts "s7.16" and "s.7.16". Throws std::invalid_argument with a message
  // naming what is wrong (I >= 0, F >= 1, I + F <= 31).
  static FixedFormat parse(std::string_view text);
  std::string name() const;  // canonical "s7.16"

  int total_bits() const { return 1 + int_bits + frac_bits; }
  int64_t raw_min() const { return -(int64_t{1} << (int_bits + frac_bits)); }
  int64_t raw_max() const { return (int64_t{1} << (int_bits + frac_bits)) - 1; }
  int64_t one() const { return int64_t{1} << frac_bits; }  // raw value of 1.0
  double to_double(int64_t raw) const { return double(raw) / double(one()); }
  bool operator==(const FixedFormat&) const = default;
};

// Largest viewport width or height (px) whose [0, n] range, taken relative to its centre
// floor(n/2), fits in the format: -2^I <= -floor(n/2) and n - floor(n/2) <= 2^I - 2^-F.
inline int64_t max_viewport_extent(const FixedFormat& f) { return (int64_t{2} << f.int_bits) - 2; }

// The datapath widths that follow from a coordinate format (docs/fixed-point.md,
// "Datapath widths"). The one place these equations are written: export-rtl
// (model/rtlsim/rtl_params.cpp), `rastsim fit` and the stability tests all call it.
// N = I + F; widths in bits, signed unless marked unsigned.
struct DatapathWidths {
  int coord = 0;      // snapped vertex x, y: N + 1
  int coef = 0;       // edge a, b: N + 2
  int edge = 0;       // edge c, E(x, y), E + bias: 2N + 3
  int area = 0;       // area2 and barycentric weights, unsigned: 2N + 2
  int color_num = 0;  // colour numerator sum w_k c_k (8-bit c_k), unsigned: 2N + 10
  int depth_num = 0;  // depth numerator sum w_k z_k (D-bit z_k), unsigned: 2N + 2 + D
  bool operator==(const DatapathWidths&) const = default;
};
DatapathWidths datapath_widths(const FixedFormat& f, int depth_bits);

// True when every edge value E(x, y) = a x + b y + c at a point of the format's range,
// and each partial sum on the way, fits int64: |a x|, |b y| < 2^(2N+1) and |c| <= L^2 <
// 2^(2N+2) (docs/fixed-point.md), so every partial sum is below 2^(2N+3) in magnitude and
// needs datapath_widths().edge + 1 = 2N + 4 <= 64 bits: N <= 30, every format but the
// widest (I + F = 31). Chooses the 64-bit
// fine raster and interpolation (fine_raster.h, interpolate.cpp); the i128 path stays
// the exact one for the rest.
inline bool edges_fit_int64(const FixedFormat& f) { return datapath_widths(f, 1).edge + 1 <= 64; }

// Largest I + F the model supports: raw coordinates then fit in 32 bits and every
// intermediate (edge values, interpolation numerators) fits in i128.
inline constexpr int kMaxFormatBits = 31;

// Rounding modes used anywhere a value is narrowed.
enum class Rounding {
  NearestEven,  // ties to even: vertex snapping, depth quantisation
  HalfUp,       // ties toward +inf: attribute interpolation (non-negative operands)
  Floor,        // toward -inf: pixel index of a coordinate
};

// Exact scene coordinate: value = q / 2^64, q rounded to odd from the source.
struct Q64 {
  i128 q = 0;
  static constexpr int kFracBits = 64;
  // Parses a plain decimal "[-+]digits[.digits]" exactly (".5" and "5." are accepted) (up to 18 integer and 36
  // fraction digits). Throws std::invalid_argument naming the problem.
  static Q64 parse_decimal(std::string_view text);
  // Exact for finite doubles with |v| < 2^62; larger or non-finite values saturate to
  // a sentinel that every format reports as out of range.
  static Q64 from_double(double v);
  static Q64 from_int(int64_t v) { return Q64{i128(v) << kFracBits}; }
  double to_double() const;
  bool saturated() const;
};

// Signed shift right with the named rounding (shift >= 0).
i128 shift_right_round(i128 v, int shift, Rounding mode);

// round(num / den) for den > 0 with the named rounding. Exact.
i128 div_round(i128 num, i128 den, Rounding mode);

// The same in the integer type T (int64_t or i128) for den > 0: the one definition of
// the rounding, which div_round and the 64-bit interpolation path (interpolate.cpp) use.
template <class T>
inline T div_round_in(T num, T den, Rounding mode) {
  T q = num / den, r = num % den;
  if (r < 0) { q -= 1; r += den; }  // floor division, r in [0, den)
  switch (mode) {
    case Rounding::Floor: return q;
    // Compare r with den - r rather than 2r with den: 2r overflows for den > 2^(w-2).
    case Rounding::HalfUp: return r >= den - r ? q + 1 : q;
    case Rounding::NearestEven:
      if (r > den - r) return q + 1;
      if (r < den - r) return q;
      return (q & 1) ? q + 1 : q;
  }
  return q;
}

// True when v fits in a two's-complement field of `bits` bits.
inline bool fits_signed(i128 v, int bits) {
  if (bits >= 128) return true;
  const i128 lim = i128(1) << (bits - 1);
  return v >= -lim && v < lim;
}
// Minimum two's-complement width that holds v.
int signed_width(i128 v);

// Snap a scene coordinate to raw s.I.F units with round-to-nearest-even, relative to
// `origin` (an integer pixel position, e.g. the viewport centre). Returns nullopt when
// the result is outside the format's range: callers report or cull, never wrap.
std::optional<int64_t> snap_coord(Q64 v, int64_t origin_px, const FixedFormat& fmt);

// Unsigned normalised quantisation of v in [0, 1] to `bits` bits: round-to-nearest-
// even of v * (2^bits - 1). nullopt when v is outside [0, 1] or not finite.
std::optional<uint32_t> quantize_unorm(double v, int bits);

std::string to_string(i128 v);

}  // namespace rastsim
