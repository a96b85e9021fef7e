// SPDX-License-Identifier: Apache-2.0
// Fine raster: per-pixel coverage of a tile footprint that coarse raster found partial
// (ref/coarse_raster.h), and whole-footprint emission of an accepted one.
//
// - A partial footprint is walked row by row, stepping each edge value by a * 2^F per
//   pixel and b * 2^F per row (exact integers, i128).
// - With raster.samples = S > 1 each pixel's coverage is an S-bit mask: bit s is set when
//   every edge, at the centre plus the edge's constant offset a dx_s + b dy_s
//   (ref/sample_pattern.h), is >= 0 with bias. A pixel is emitted when its mask is not
//   zero; an accepted footprint emits full masks. sample_tests = footprint area x S.
// - emit may take (px, py) or (px, py, mask); a one-sample triangle's mask is 1. An
//   emitter with a span() member (SpanEmitter) gets runs of covered pixels instead.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <type_traits>

#include "ref/sample_pattern.h"
#include "ref/tri_setup.h"

namespace rastsim {

// Calls emit(px, py, mask) or, for a callable of two arguments, emit(px, py).
template <class Emit>
inline void emit_pixel(Emit& emit, int px, int py, uint32_t mask) {
  if constexpr (std::is_invocable_v<Emit&, int, int, uint32_t>) emit(px, py, mask);
  else emit(px, py);
}

// An emitter that also takes runs: emit.span(py, x0, x1, mask) stands for
// emit(px, py, mask) for px = x0 .. x1 - 1 in that order, every pixel of the same mask
// (the reference pipeline shades and writes a run at a time, pipeline.cpp). The walks
// below hand such an emitter whole runs; any other callable gets the pixels one by one.
template <class Emit>
concept SpanEmitter = requires(Emit& e, int i, uint32_t m) { e.span(i, i, i, m); };

template <class Emit>
inline void emit_span(Emit& emit, int py, int x0, int x1, uint32_t mask) {
  if constexpr (SpanEmitter<Emit>) {
    emit.span(py, x0, x1, mask);
  } else {
    for (int px = x0; px < x1; ++px) emit_pixel(emit, px, py, mask);
  }
}

// Per-edge offsets of every sample: off[i][s] = a_i dx_s + b_i dy_s (raw^2 units; |a|,
// |dx| < 2^(I+F+2), 2^(F-1), so it fits 64 bits for any format the model accepts).
struct SampleEdgeOffsets {
  std::array<std::array<int64_t, kMaxSamples>, 3> off{};
  int count = 1;
  SampleEdgeOffsets(const SetupTriangle& t, int frac_bits) : count(t.samples) {
    const SamplePattern& p = sample_pattern(t.samples, frac_bits);
    for (int i = 0; i < 3; ++i)
      for (int s = 0; s < count; ++s) off[size_t(i)][size_t(s)] = t.edge[size_t(i)].a * p.dx[size_t(s)] + t.edge[size_t(i)].b * p.dy[size_t(s)];
  }
  // Mask of the samples covered, given the three edge values (bias included) at the
  // centre (i128, or int64 for a triangle whose edges64 holds).
  template <class T>
  uint32_t mask(T e0, T e1, T e2) const {
    uint32_t m = 0;
    for (int s = 0; s < count; ++s)
      if (e0 + off[0][size_t(s)] >= 0 && e1 + off[1][size_t(s)] >= 0 && e2 + off[2][size_t(s)] >= 0) m |= 1u << s;
    return m;
  }
};

// Coverage of one pixel (fill-rule bias included).
inline bool pixel_covered(const SetupTriangle& t, int px, int py, int frac_bits) {
  const int64_t sx = t.sample_x(px, frac_bits), sy = t.sample_y(py, frac_bits);
  for (const auto& e : t.edge)
    if (e.eval(sx, sy) + e.bias < 0) return false;
  return true;
}

// Coverage mask of one pixel's samples (bit s: sample s covered; one sample: 0 or 1).
inline uint32_t pixel_sample_mask(const SetupTriangle& t, int px, int py, int frac_bits) {
  if (t.samples == 1) return pixel_covered(t, px, py, frac_bits) ? 1u : 0u;
  const int64_t sx = t.sample_x(px, frac_bits), sy = t.sample_y(py, frac_bits);
  return SampleEdgeOffsets(t, frac_bits)
      .mask(t.edge[0].eval(sx, sy) + t.edge[0].bias, t.edge[1].eval(sx, sy) + t.edge[1].bias,
            t.edge[2].eval(sx, sy) + t.edge[2].bias);
}

// The walk of fine_raster_partial with edge values in T: i128, or int64_t when the
// triangle's edges64 holds (every value it meets is an edge value at a pixel centre or
// sample of the clipped box, or one row below it: in the format's range).
template <class T, class Emit>
void fine_raster_walk(const SetupTriangle& t, const PixelRect& fp, int frac_bits, Emit& emit) {
  const int64_t sx0 = t.sample_x(fp.x0, frac_bits), sy0 = t.sample_y(fp.y0, frac_bits);
  T row[3], step_x[3], step_y[3];
  for (int i = 0; i < 3; ++i) {
    row[i] = static_cast<T>(t.edge[i].eval(sx0, sy0) + t.edge[i].bias);
    step_x[i] = static_cast<T>(i128(t.edge[i].a) << frac_bits);
    step_y[i] = static_cast<T>(i128(t.edge[i].b) << frac_bits);
  }
  if (t.samples > 1) {
    const SampleEdgeOffsets so(t, frac_bits);
    for (int py = fp.y0; py < fp.y1; ++py) {
      T e0 = row[0], e1 = row[1], e2 = row[2];
      for (int px = fp.x0; px < fp.x1; ++px) {
        if (const uint32_t m = so.mask(e0, e1, e2)) emit_pixel(emit, px, py, m);
        e0 += step_x[0];
        e1 += step_x[1];
        e2 += step_x[2];
      }
      for (int i = 0; i < 3; ++i) row[i] += step_y[i];
    }
    return;
  }
  for (int py = fp.y0; py < fp.y1; ++py) {
    T e0 = row[0], e1 = row[1], e2 = row[2];
    // Up to 64 pixels' coverage as a bit mask first, without branches (all three edges
    // >= 0 is the OR of the three being >= 0), then the covered ones emitted in order.
    for (int x0 = fp.x0; x0 < fp.x1; x0 += 64) {
      const int n = std::min(64, fp.x1 - x0);
      uint64_t bits = 0;
      for (int k = 0; k < n; ++k) {
        bits |= uint64_t((e0 | e1 | e2) >= 0) << k;
        e0 += step_x[0];
        e1 += step_x[1];
        e2 += step_x[2];
      }
      // The covered pixels in order, as runs of consecutive ones.
      while (bits != 0) {
        const int first = std::countr_zero(bits);
        const int end = first + std::countr_one(bits >> first);  // <= 64
        emit_span(emit, py, x0 + first, x0 + end, 1u);
        bits = end >= 64 ? 0 : bits & (~uint64_t{0} << end);
      }
    }
    for (int i = 0; i < 3; ++i) row[i] += step_y[i];
  }
}

// Fine raster of a partial footprint: calls emit(px, py[, mask]) for each pixel with a
// covered sample, in row-major order; returns the number of pixel tests made (= footprint
// area; sample tests are that times t.samples).
template <class Emit>
uint64_t fine_raster_partial(const SetupTriangle& t, const PixelRect& fp, int frac_bits, Emit&& emit) {
  if (t.edges64) fine_raster_walk<int64_t>(t, fp, frac_bits, emit);
  else fine_raster_walk<i128>(t, fp, frac_bits, emit);
  return static_cast<uint64_t>(fp.area());
}

// Whole-footprint emission of an accepted tile (no tests): every mask full.
template <class Emit>
void fine_raster_accepted(const PixelRect& fp, Emit&& emit, uint32_t full_mask = 1u) {
  for (int py = fp.y0; py < fp.y1; ++py) emit_span(emit, py, fp.x0, fp.x1, full_mask);
}

}  // namespace rastsim
