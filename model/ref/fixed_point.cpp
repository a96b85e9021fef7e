// SPDX-License-Identifier: Apache-2.0
#include "ref/fixed_point.h"

#include <cctype>
#include <charconv>
#include <cmath>

namespace rastsim {

namespace {
// Sentinel magnitude for coordinates too large for any format (2^120 pixels-ish).
constexpr int kSaturateShift = 126;
i128 saturate_q(bool negative) {
  const i128 s = i128(1) << kSaturateShift;
  return negative ? -s : s;
}
}  // namespace

FixedFormat FixedFormat::parse(std::string_view text) {
  const std::string orig(text);
  auto fail = [&](const std::string& why) -> FixedFormat {
    throw std::invalid_argument("bad fixed-point format '" + orig + "': " + why +
                                " (expected s<I>.<F>, e.g. \"s7.16\", with I >= 0, F >= 1, I + F <= " +
                                std::to_string(kMaxFormatBits) + ")");
  };
  if (text.empty() || (text[0] != 's' && text[0] != 'S')) return fail("must start with 's'");
  text.remove_prefix(1);
  if (!text.empty() && text[0] == '.') text.remove_prefix(1);
  const auto dot = text.find('.');
  if (dot == std::string_view::npos) return fail("missing '.' between I and F");
  auto parse_int = [&](std::string_view s, int& out) {
    if (s.empty() || s.size() > 3) return false;
    for (char c : s) if (!std::isdigit(static_cast<unsigned char>(c))) return false;
    auto r = std::from_chars(s.data(), s.data() + s.size(), out);
    return r.ec == std::errc() && r.ptr == s.data() + s.size();
  };
  FixedFormat f;
  if (!parse_int(text.substr(0, dot), f.int_bits)) return fail("I is not a number");
  if (!parse_int(text.substr(dot + 1), f.frac_bits)) return fail("F is not a number");
  if (f.frac_bits < 1) return fail("F must be at least 1 (pixel centres sit at +0.5)");
  if (f.int_bits + f.frac_bits > kMaxFormatBits) return fail("I + F is too large");
  return f;
}

DatapathWidths datapath_widths(const FixedFormat& f, int depth_bits) {
  const int n = f.int_bits + f.frac_bits;  // N = I + F
  DatapathWidths w;
  w.coord = n + 1;
  w.coef = n + 2;
  w.edge = 2 * n + 3;  // |E| <= L^2 < 2^(2N+2), L = 2^(N+1) - 1, plus a sign bit
  w.area = 2 * n + 2;
  w.color_num = 2 * n + 2 + 8;
  w.depth_num = 2 * n + 2 + depth_bits;
  return w;
}

std::string FixedFormat::name() const {
  // Appended, not `"s" + std::to_string(...)`: GCC 12 at -O3 reports a false
  // -Wrestrict on operator+(const char*, string&&) (GCC bug 105329), which -Werror stops.
  std::string s = "s";
  s += std::to_string(int_bits);
  s += '.';
  s += std::to_string(frac_bits);
  return s;
}

Q64 Q64::parse_decimal(std::string_view text) {
  const std::string_view orig = text;  // copied into the message only on failure
  auto fail = [&](const std::string& why) -> Q64 {
    throw std::invalid_argument("bad number '" + std::string(orig) + "': " + why);
  };
  bool neg = false;
  if (!text.empty() && (text[0] == '-' || text[0] == '+')) {
    neg = text[0] == '-';
    text.remove_prefix(1);
  }
  const auto dot = text.find('.');
  std::string_view ip = text.substr(0, dot);
  std::string_view fp = dot == std::string_view::npos ? std::string_view{} : text.substr(dot + 1);
  if (ip.empty() && fp.empty()) return fail("no digits");
  for (char c : ip) if (!std::isdigit(static_cast<unsigned char>(c))) return fail("not a decimal number");
  for (char c : fp) if (!std::isdigit(static_cast<unsigned char>(c))) return fail("not a decimal number");
  while (ip.size() > 1 && ip[0] == '0') ip.remove_prefix(1);
  while (!fp.empty() && fp.back() == '0') fp.remove_suffix(1);
  if (fp.size() > 36) return fail("more than 36 fraction digits");
  if (ip.size() > 18) return Q64{saturate_q(neg)};  // out of range for every format
  // Up to 18 integer digits: below 10^18 < 2^64, accumulated in 64 bits (a u128 product
  // is three multiplies; this parse runs six times a triangle of a trace).
  uint64_t int_part = 0;
  for (char c : ip) int_part = int_part * 10 + uint64_t(c - '0');
  // Fraction: frac / 10^k, converted to 64 binary fraction bits by long division,
  // with the remainder folded into the LSB (round to odd).
  u128 bits = 0, rem = 0;
  if (fp.size() <= 19) {  // frac < 10^k <= 10^19 < 2^64: frac 2^64 fits, one division
    uint64_t frac = 0, pow10 = 1;
    for (char c : fp) { frac = frac * 10 + uint64_t(c - '0'); pow10 *= 10; }
    const u128 num = u128(frac) << 64;
    bits = num / pow10;
    rem = num % pow10;
  } else {
    u128 frac = 0, pow10 = 1;
    for (char c : fp) { frac = frac * 10 + u128(c - '0'); pow10 *= 10; }
    rem = frac;
    for (int i = 0; i < 64; ++i) {
      rem <<= 1;
      bits <<= 1;
      if (rem >= pow10) { rem -= pow10; bits |= 1; }
    }
  }
  if (rem != 0) bits |= 1;  // sticky: round to odd
  const i128 mag = i128((u128(int_part) << 64) | bits);
  return Q64{neg ? -mag : mag};
}

Q64 Q64::from_double(double v) {
  if (!std::isfinite(v) || std::fabs(v) >= std::ldexp(1.0, 62)) return Q64{saturate_q(v < 0)};
  int exp = 0;
  const double m = std::frexp(std::fabs(v), &exp);  // v = m * 2^exp, m in [0.5, 1)
  const int64_t mant = static_cast<int64_t>(std::ldexp(m, 53));  // exact 53-bit integer
  // |v| = mant * 2^(exp - 53); in Q64 units: mant * 2^(exp - 53 + 64)
  const int sh = exp - 53 + 64;
  i128 mag;
  if (sh >= 0) {
    mag = i128(mant) << sh;
  } else if (sh > -64) {
    mag = i128(mant) >> (-sh);
    if ((i128(mant) & ((i128(1) << (-sh)) - 1)) != 0) mag |= 1;  // round to odd
  } else {
    mag = mant != 0 ? 1 : 0;
  }
  return Q64{v < 0 ? -mag : mag};
}

double Q64::to_double() const {
  return std::ldexp(static_cast<double>(q), -kFracBits);
}

bool Q64::saturated() const {
  const i128 s = i128(1) << kSaturateShift;
  return q >= s || q <= -s;
}

i128 shift_right_round(i128 v, int shift, Rounding mode) {
  if (shift <= 0) return v << (-shift);
  if (shift >= 128) {  // |v| <= 2^127 <= 2^(shift-1): |v / 2^shift| <= 1/2
    if (mode == Rounding::Floor) return v < 0 ? -1 : 0;
    // Only v = -2^127 with shift 128 is exactly -1/2: HalfUp rounds it to 0 and
    // NearestEven to the even 0 as well.
    return 0;
  }
  const i128 floor_q = v >> shift;  // arithmetic shift: floor
  const i128 rem = v - (floor_q << shift);  // in [0, 2^shift)
  const i128 half = i128(1) << (shift - 1);
  switch (mode) {
    case Rounding::Floor: return floor_q;
    case Rounding::HalfUp: return rem >= half ? floor_q + 1 : floor_q;
    case Rounding::NearestEven:
      if (rem > half) return floor_q + 1;
      if (rem < half) return floor_q;
      return (floor_q & 1) ? floor_q + 1 : floor_q;
  }
  return floor_q;
}

i128 div_round(i128 num, i128 den, Rounding mode) {
  if (den <= 0) throw std::invalid_argument("div_round: denominator must be positive");
  // Same result through the 64-bit divider: a 128-bit division is a library call
  // (__divti3) and dominates per-fragment interpolation when used unconditionally.
  if (fits_signed(num, 64) && fits_signed(den, 64))
    return div_round_in<int64_t>(static_cast<int64_t>(num), static_cast<int64_t>(den), mode);
  return div_round_in<i128>(num, den, mode);
}

int signed_width(i128 v) {
  int bits = 1;
  while (!fits_signed(v, bits)) ++bits;
  return bits;
}

std::optional<int64_t> snap_coord(Q64 v, int64_t origin_px, const FixedFormat& fmt) {
  if (v.saturated()) return std::nullopt;
  const i128 rel = v.q - (i128(origin_px) << Q64::kFracBits);
  const i128 raw = shift_right_round(rel, Q64::kFracBits - fmt.frac_bits, Rounding::NearestEven);
  if (raw < fmt.raw_min() || raw > fmt.raw_max()) return std::nullopt;
  return static_cast<int64_t>(raw);
}

std::optional<uint32_t> quantize_unorm(double v, int bits) {
  if (!std::isfinite(v) || v < 0.0 || v > 1.0 || bits < 1 || bits > 32) return std::nullopt;
  if (v == 0.0) return 0u;
  int exp = 0;
  const double m = std::frexp(v, &exp);
  const i128 mant = static_cast<i128>(std::ldexp(m, 53));  // v = mant * 2^(exp-53)
  if (53 - exp >= 120) return 0u;  // v < 2^-66: rounds to 0 for every width
  const i128 scale = (i128(1) << bits) - 1;
  const i128 prod = mant * scale;  // v * scale = prod * 2^(exp-53), exact
  const i128 q = shift_right_round(prod, 53 - exp, Rounding::NearestEven);
  return static_cast<uint32_t>(q);
}

std::string to_string(i128 v) {
  if (v == 0) return "0";
  const bool neg = v < 0;
  u128 m = neg ? u128(-(v + 1)) + 1 : u128(v);
  std::string s;
  while (m) { s.insert(s.begin(), char('0' + int(m % 10))); m /= 10; }
  return neg ? "-" + s : s;
}

}  // namespace rastsim
