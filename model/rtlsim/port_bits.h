// SPDX-License-Identifier: Apache-2.0
// Field access on verilated ports: a C integer for ports of up to 64 bits, a VlWide
// (32-bit words, least significant first) above that. The port adapter (cosim_driver.h)
// moves every field between the testbench and the models through these.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <type_traits>

namespace rastsim::rtlsim {

// A w-bit two's-complement port value (w <= 32, in the low bits of v) as a signed int.
inline int signed_field(uint32_t v, int w) {
  const int unused = 32 - w;
  return int(int32_t(v << unused) >> unused);
}

// Bits [lsb, lsb + w) of a verilated port (C integer or VlWide), w <= 64.
template <class T>
uint64_t port_bits(const T& v, int lsb, int w) {
  const uint64_t mask = (w >= 64) ? ~uint64_t{0} : ((uint64_t{1} << w) - 1);
  if constexpr (std::is_integral_v<T>) {
    return (static_cast<uint64_t>(v) >> lsb) & mask;
  } else {
    // A 32-bit word (or the part of one the field covers) at a time: at most 3 words for
    // w <= 64 (the testbench reads every fragment lane's fields this way).
    uint64_t r = 0;
    for (int b = lsb; b < lsb + w;) {
      const int sh = b % 32;
      const int n = std::min(32 - sh, lsb + w - b);  // bits taken from this word, 1..32
      r |= ((static_cast<uint64_t>(v[size_t(b / 32)]) >> sh) & ((uint64_t{1} << n) - 1)) << (b - lsb);
      b += n;
    }
    return r & mask;
  }
}

// Sets bits [lsb, lsb + w) of a verilated port (C integer or VlWide) to v, w <= 64.
template <class T>
void set_port_bits(T& port, int lsb, int w, uint64_t v) {
  if constexpr (std::is_integral_v<T>) {
    const T mask = static_cast<T>(((w >= 64) ? ~uint64_t{0} : ((uint64_t{1} << w) - 1)) << lsb);
    port = static_cast<T>((port & ~mask) | (static_cast<T>(v << lsb) & mask));
  } else {
    for (int i = 0; i < w; ++i) {
      const int b = lsb + i;
      if ((v >> i) & 1) port[size_t(b / 32)] |= (1u << (b % 32));
      else port[size_t(b / 32)] &= ~(1u << (b % 32));
    }
  }
}

// Sets 32-bit word i of a port (an integral port of up to 64 bits, or a VlWide).
template <class T>
void set_port_word(T& port, size_t i, uint32_t v) {
  if constexpr (std::is_integral_v<T>) set_port_bits(port, int(i) * 32, 32, v);
  else port[i] = v;
}

// Sets a port's low 8 N bits to bytes, byte i in bits [8 i + 7 : 8 i] (a little-endian
// memory beat, e.g. the texture cache's 128-bit line-fill beat).
template <class T, size_t N>
void set_port_bytes(T& port, const std::array<uint8_t, N>& bytes) {
  for (size_t i = 0; i < N; ++i) set_port_bits(port, int(8 * i), 8, bytes[i]);
}

}  // namespace rastsim::rtlsim
