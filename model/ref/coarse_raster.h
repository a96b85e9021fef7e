// SPDX-License-Identifier: Apache-2.0
// Coarse raster: the tile walk with early-out / early-in, and the whole tiled traversal
// of a triangle (coarse raster feeding fine raster, ref/fine_raster.h).
//
// - Tiles are raster.tile_size squares aligned to the framebuffer origin; the walk
//   visits, row by row, every tile that overlaps the triangle's clipped bounding box.
// - A tile's footprint is the tile clipped to that box. Each edge is linear, so over
//   the footprint's pixel centres its extremes lie at two opposite corners, chosen by
//   the signs of a and b: if some edge's maximum (with bias) is < 0 the tile is
//   rejected (early-out); if every edge's minimum is >= 0 it is accepted whole
//   (early-in, no per-pixel tests); otherwise it is partial and tested per pixel.
//   With raster.samples > 1 the two corners move by the sample offsets' bounding box
//   (ref/sample_pattern.h), so both decisions hold for every sample of the footprint.
#pragma once

#include <bit>
#include <cstdint>

#include "ref/fine_raster.h"
#include "ref/tri_setup.h"

namespace rastsim {

enum class TileClass { Rejected, Accepted, Partial };

// Counters a hardware tile walker would keep.
struct TraversalCounters {
  uint64_t tiles_visited = 0, tiles_rejected = 0, tiles_accepted = 0, tiles_partial = 0;
  uint64_t pixel_tests = 0;  // per-pixel coverage tests (partial tiles only)
  uint64_t fragments = 0;    // covered pixels emitted
  uint64_t spans = 0;        // non-empty spans (raster.traversal = scanline only)
  // Multisampling (raster.samples = S; with S = 1: sample_tests = pixel_tests,
  // samples_covered = fragments, pixels_partially_covered = 0).
  uint64_t sample_tests = 0;              // pixel_tests x S
  uint64_t samples_covered = 0;           // covered samples of the emitted pixels
  uint64_t pixels_partially_covered = 0;  // emitted pixels whose mask is not full

  // Counts one emitted pixel of mask m (S = samples).
  void count_pixel(uint32_t m, int samples) {
    ++fragments;
    const int n = std::popcount(m);
    samples_covered += uint64_t(n);
    pixels_partially_covered += n != samples;
  }
  // Counts n emitted pixels of the same mask m (a run, fine_raster.h SpanEmitter).
  void count_pixels(uint32_t m, int samples, uint64_t n) {
    fragments += n;
    const int k = std::popcount(m);
    samples_covered += uint64_t(k) * n;
    if (k != samples) pixels_partially_covered += n;
  }
  void count_accepted(int64_t area, int samples) {
    fragments += uint64_t(area);
    samples_covered += uint64_t(area) * uint64_t(samples);
  }
  void count_tests(uint64_t pixels, int samples) {
    pixel_tests += pixels;
    sample_tests += pixels * uint64_t(samples);
  }
  // Every counter summed (the parallel pipeline's workers, pipeline.cpp).
  TraversalCounters& operator+=(const TraversalCounters& o) {
    for (auto m : {&TraversalCounters::tiles_visited, &TraversalCounters::tiles_rejected,
                   &TraversalCounters::tiles_accepted, &TraversalCounters::tiles_partial, &TraversalCounters::pixel_tests,
                   &TraversalCounters::fragments, &TraversalCounters::spans, &TraversalCounters::sample_tests,
                   &TraversalCounters::samples_covered, &TraversalCounters::pixels_partially_covered})
      this->*m += o.*m;
    return *this;
  }
};

// `emit` with every pixel it passes on counted as an emitted fragment (count_pixel): the
// emitter of every walk's per-pixel tests. A run passes on as a run, counted at once.
template <class Emit>
struct CountedEmit {
  TraversalCounters& c;
  int samples;
  Emit& emit;
  void operator()(int px, int py, uint32_t m) {
    c.count_pixel(m, samples);
    emit_pixel(emit, px, py, m);
  }
  void span(int py, int x0, int x1, uint32_t m) {
    c.count_pixels(m, samples, uint64_t(x1 - x0));
    emit_span(emit, py, x0, x1, m);
  }
};
template <class Emit>
CountedEmit<Emit> counted(TraversalCounters& c, int samples, Emit& emit) {
  return {c, samples, emit};
}

// The tile grid cells overlapping `bbox`, in tile units [tx0, tx1) x [ty0, ty1).
PixelRect tile_range(const PixelRect& bbox, int tile_size);
// Footprint of tile (tx, ty): the tile's pixels clipped to bbox.
PixelRect tile_footprint(const PixelRect& bbox, int tile_size, int tx, int ty);

// Early-out / early-in classification of one footprint.
TileClass classify_tile(const SetupTriangle& t, const PixelRect& footprint, int frac_bits);

// A tile filter of traverse_triangle: asked about every tile that coarse raster does not
// reject (true: fine raster it), told when such a tile is done. The default draws every
// tile; the reference's Hi-Z (ref/hiz.h, pipeline.cpp) culls some.
struct NoTileFilter {
  bool operator()(const PixelRect&, TileClass) const { return true; }
  void done() const {}
};

// The whole traversal of one set-up triangle: tile walk, classification, fine raster.
// emit(px, py) is called once per covered pixel, tile by tile (row-major tiles,
// row-major pixels inside each tile). A tile the filter refuses is counted by its class
// (tiles_accepted or tiles_partial) but not fine-rastered: no fragment, no pixel test.
template <class Emit, class Filter = NoTileFilter>
void traverse_triangle(const SetupTriangle& t, int tile_size, int frac_bits, TraversalCounters& c,
                       Emit&& emit, Filter&& filter = Filter{}) {
  const PixelRect tiles = tile_range(t.bbox, tile_size);
  for (int ty = tiles.y0; ty < tiles.y1; ++ty) {
    for (int tx = tiles.x0; tx < tiles.x1; ++tx) {
      const PixelRect fp = tile_footprint(t.bbox, tile_size, tx, ty);
      ++c.tiles_visited;
      switch (classify_tile(t, fp, frac_bits)) {
        case TileClass::Rejected: ++c.tiles_rejected; break;
        case TileClass::Accepted:
          ++c.tiles_accepted;
          if (!filter(fp, TileClass::Accepted)) break;
          c.count_accepted(fp.area(), t.samples);
          fine_raster_accepted(fp, emit, t.full_mask());
          filter.done();
          break;
        case TileClass::Partial:
          ++c.tiles_partial;
          if (!filter(fp, TileClass::Partial)) break;
          c.count_tests(fine_raster_partial(t, fp, frac_bits, counted(c, t.samples, emit)), t.samples);
          filter.done();
          break;
      }
    }
  }
}

}  // namespace rastsim
