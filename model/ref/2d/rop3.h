// SPDX-License-Identifier: Apache-2.0
// ROP3: the ternary raster operations of bit-block transfer (the lecture notes' truth
// table). The 8-bit code is the truth table itself: the result bit for pattern bit P,
// source bit S and destination bit D is bit number (P << 2 | S << 1 | D) of the code.
// Applied bit by bit to each 8-bit colour channel (alpha stays 255 in the framebuffer).
#pragma once

#include <cstdint>

namespace rastsim {

// One channel (8 bits) of P, S and D through the code: for every bit position i the
// result bit is code bit (p_i << 2 | s_i << 1 | d_i). Bit-parallel: each of the eight
// minterms selects the positions whose (p, s, d) equal it.
inline uint8_t rop3(uint8_t code, uint8_t p, uint8_t s, uint8_t d) {
  uint8_t r = 0;
  for (int m = 0; m < 8; ++m) {
    if (!((code >> m) & 1)) continue;
    const uint8_t pm = (m & 4) ? p : uint8_t(~p), sm = (m & 2) ? s : uint8_t(~s), dm = (m & 1) ? d : uint8_t(~d);
    r |= uint8_t(pm & sm & dm);
  }
  return r;
}

// Whether the result depends on S (the code differs between S = 0 and S = 1 for some P, D):
// a fill (no source) with such a code is an error.
inline bool rop3_reads_source(uint8_t code) { return ((code >> 2) & 0x33) != (code & 0x33); }
// Whether the result depends on D (the ROP must read the destination: read-modify-write).
inline bool rop3_reads_destination(uint8_t code) { return ((code >> 1) & 0x55) != (code & 0x55); }

// Well-known codes (Windows GDI names).
inline constexpr uint8_t kRopPatCopy = 0xF0, kRopSrcCopy = 0xCC, kRopPatInvert = 0x5A, kRopDstInvert = 0x55,
                         kRopBlackness = 0x00, kRopWhiteness = 0xFF, kRopSrcInvert = 0x66;

}  // namespace rastsim
