// SPDX-License-Identifier: Apache-2.0
#include "ref/line_raster.h"

#include <numeric>

namespace rastsim {

const char* to_string(LineMethod m) {
  switch (m) {
    case LineMethod::Diamond: return "diamond";
    case LineMethod::Bresenham: return "bresenham";
    case LineMethod::Midpoint: return "midpoint";
    case LineMethod::Dda: return "dda";
  }
  return "?";
}

const char* to_string(DdaArith a) {
  switch (a) {
    case DdaArith::F32: return "f32";
    case DdaArith::F64: return "f64";
    case DdaArith::Fixed: return "fixed";
  }
  return "?";
}

int64_t bresenham_midpoint_ties(int64_t d_major, int64_t d_minor) {
  if (d_major == 0) return 0;
  const int64_t g = std::gcd(d_major, d_minor);
  return ((d_major / g) % 2 == 0) ? g : 0;
}

}  // namespace rastsim
