// SPDX-License-Identifier: Apache-2.0
// Random 2D scenes as trace text, shared by the SystemC and co-simulation tests: every
// 2D command of docs/trace-format.md mixed with triangles and scissor changes, random
// colours, patterns and ROP3 codes (fills only take codes without S), lines in every
// octant and both directions, overlapping blits in all four directions, shapes reaching
// past the framebuffer edges, text in random font states.
#pragma once

#include <cstdint>
#include <random>
#include <sstream>
#include <string>

#include "ref/2d/rop3.h"

namespace rastsim::testing {

inline std::string random_2d_trace(uint64_t seed, int w, int h, int commands) {
  std::mt19937_64 rng(seed);
  auto ri = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
  // A coordinate in quarter pixels, up to 8 px past each edge.
  auto coord = [&](int extent) { return std::to_string(ri(-32, 4 * extent + 32) / 4.0); };
  auto fill_code = [&] {
    int c;
    do c = ri(0, 255);
    while (rop3_reads_source(uint8_t(c)));
    return c;
  };
  auto hex2 = [](int v) {
    const char* d = "0123456789ABCDEF";
    return std::string{d[(v >> 4) & 15], d[v & 15]};
  };
  std::ostringstream t;
  t << "viewport " << w << " " << h << "\nclear " << ri(0, 255) << " " << ri(0, 255) << " " << ri(0, 255) << "\n";
  for (int i = 0; i < commands; ++i) {
    if (ri(0, 3) == 0) t << "color " << ri(0, 255) << " " << ri(0, 255) << " " << ri(0, 255) << "\n";
    if (ri(0, 5) == 0) t << "bgcolor " << ri(0, 255) << " " << ri(0, 255) << " " << ri(0, 255) << "\n";
    if (ri(0, 5) == 0) {
      if (ri(0, 2) == 0) {
        t << "pattern solid\n";
      } else {
        t << "pattern ";
        for (int r = 0; r < 8; ++r) t << hex2(ri(0, 255));
        t << "\n";
      }
    }
    const int kind = ri(0, 12);
    if (kind != 10) t << "rop3 " << hex2(fill_code()) << "\n";
    switch (kind) {
      case 0:
        t << "line " << coord(w) << " " << coord(h) << " " << coord(w) << " " << coord(h) << "\n";
        break;
      case 1: {
        const char* kw[] = {"linestrip", "lineloop", "lines"};
        const int k = ri(0, 2);
        t << kw[k] << "\n";
        for (int v = k == 2 ? 2 * ri(1, 3) : ri(2, 6); v > 0; --v) t << "v " << coord(w) << " " << coord(h) << "\n";
        t << "end\n";
        break;
      }
      case 2:
        t << "point_size " << ri(1, 6) << "\npoint " << coord(w) << " " << coord(h) << "\n";
        break;
      case 3:
        if (ri(0, 2) == 0) {
          const int a0 = ri(-360, 360);
          t << "arc " << ri(-8, w + 8) << " " << ri(-8, h + 8) << " " << ri(0, w / 3) << " " << a0 << " "
            << a0 + ri(0, 400) << "\n";
          break;
        }
        t << "circle " << ri(-8, w + 8) << " " << ri(-8, h + 8) << " " << ri(0, w / 3) << (ri(0, 1) ? " fill" : "")
          << "\n";
        break;
      case 4:
      case 5:
        t << "rect " << ri(-8, w) << " " << ri(-8, h) << " " << ri(0, w / 2) << " " << ri(0, h / 2) << "\n";
        break;
      case 6: {
        t << "polygon\n";
        for (int v = ri(3, 7); v > 0; --v) t << "v " << coord(w) << " " << coord(h) << "\n";
        t << "end\n";
        break;
      }
      case 7:
        t << "tri " << coord(w) << " " << coord(h) << " 0.5 " << ri(0, 255) << " " << ri(0, 255) << " " << ri(0, 255)
          << "  " << coord(w) << " " << coord(h) << " 0.5 " << ri(0, 255) << " " << ri(0, 255) << " " << ri(0, 255)
          << "  " << coord(w) << " " << coord(h) << " 0.5 " << ri(0, 255) << " " << ri(0, 255) << " " << ri(0, 255)
          << "\n";
        break;
      case 8:
        if (ri(0, 1)) t << "scissor " << ri(0, w / 2) << " " << ri(0, h / 2) << " " << ri(1, w) << " " << ri(1, h) << "\n";
        else t << "scissor off\n";
        break;
      case 9:
      case 10:
      case 11: {
        // Any code (blits have S); overlapping in any direction, or anywhere.
        if (kind != 10) t << "rop3 " << hex2(ri(0, 255)) << "\n";
        const int bw = ri(0, w / 2), bh = ri(0, h / 2), sx = ri(-8, w), sy = ri(-8, h);
        const bool overlap = ri(0, 2) != 0;
        const int dx = overlap ? sx + ri(-4, 4) : ri(-8, w), dy = overlap ? sy + ri(-4, 4) : ri(-8, h);
        t << "blit " << sx << " " << sy << " " << dx << " " << dy << " " << bw << " " << bh << "\n";
        break;
      }
      case 12: {
        // Text in a random font state: ink spans, and paper spans when opaque.
        t << "font " << ri(1, 3) << (ri(0, 1) ? " bold" : "") << (ri(0, 1) ? " underline" : "")
          << (ri(0, 1) ? " proportional" : "") << (ri(0, 1) ? " opaque" : "") << "\n";
        std::string str;
        for (int n = ri(1, 10); n > 0; --n) {
          const char c = char(ri(0x21, 0x7E));  // no blank at the ends; '#' and '\\' need escapes
          str += c == '#' || c == '\\' ? 'k' : c;
        }
        t << "text " << ri(-16, w) << " " << ri(-16, h) << " " << str << "\n";
        break;
      }
    }
  }
  return t.str();
}

}  // namespace rastsim::testing
