// SPDX-License-Identifier: Apache-2.0
// Triangle traversal: the four methods of raster.traversal (docs/traversal.md) over one
// set-up triangle, each calling emit(px, py) once per pixel it covers.
//
// - tiled: the coarse tile walk with early-out / early-in, then the fine raster
//   (ref/coarse_raster.h: traverse_triangle). Exact.
// - bbox: every pixel centre of the triangle's clipped bounding box tested with the edge
//   functions (fine_raster_partial over the whole box). Exact.
// - hierarchical: the tile walk at raster.hier_levels sizes (e.g. 64/16/4): a rejected
//   tile is dropped, an accepted one emitted whole, a partial one split into the next
//   level's tiles, a partial tile of the last level tested per pixel. Exact: the same
//   classify_tile and fine raster as tiled, on smaller footprints.
// - scanline: the lecture notes' screen coordinate setup (ref/scanline.h). Inexact in
//   f32/f64/fixed; counted against the exact coverage (ref/study/coverage_check.h). One
//   sample a pixel only (the config rejects raster.samples > 1 with it).
//
// The exact methods emit the same SET of pixels as tiled, in a different order (bbox:
// row-major over the box; hierarchical: depth-first in tile walk order, row-major inside
// each leaf). The timed model (model/sc) walks with the same functions.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "ref/coarse_raster.h"
#include "ref/scanline.h"

namespace rastsim {

const char* to_string(Traversal m);  // Traversal is declared in ref/raster_state.h
// True for the methods whose coverage equals the edge-function rule on every triangle.
inline bool traversal_is_exact(Traversal m) { return m != Traversal::Scanline; }

// Parses raster.hier_levels, "64/16/4": 1 to 8 powers of two in [2, 1024], strictly
// decreasing (so each level's tiles split the previous level's exactly). Returns the
// sizes, or an empty vector when the text is not of that form.
std::vector<int> parse_hier_levels(const std::string& text);

// The hierarchical tile walk over `region` (a footprint clipped to t.bbox) at levels
// [level, levels.size()). leaf(fp, cls) receives each accepted tile of any level and
// each partial tile of the last level, in walk order. Counts every tile classified
// (tiles_visited = rejected + accepted + partial, partial including the split ones).
template <class Leaf>
void walk_hierarchical(const SetupTriangle& t, const PixelRect& region, const std::vector<int>& levels,
                       size_t level, int frac_bits, TraversalCounters& c, Leaf&& leaf) {
  const int size = levels[level];
  const PixelRect tiles = tile_range(region, size);
  for (int ty = tiles.y0; ty < tiles.y1; ++ty) {
    for (int tx = tiles.x0; tx < tiles.x1; ++tx) {
      const PixelRect fp = tile_footprint(region, size, tx, ty);
      ++c.tiles_visited;
      const TileClass cls = classify_tile(t, fp, frac_bits);
      if (cls == TileClass::Rejected) {
        ++c.tiles_rejected;
      } else if (cls == TileClass::Accepted) {
        ++c.tiles_accepted;
        leaf(fp, cls);
      } else {
        ++c.tiles_partial;
        if (level + 1 < levels.size()) walk_hierarchical(t, fp, levels, level + 1, frac_bits, c, leaf);
        else leaf(fp, cls);
      }
    }
  }
}

// What traverse() needs of the state: the method and its parameters.
struct TraversalParams {
  Traversal method = Traversal::Tiled;
  int tile_size = 0;             // tiled, px
  std::vector<int> hier_levels;  // hierarchical, px, decreasing
  DdaArith scan_arith = DdaArith::F32;
  int frac_bits = 0;             // raster.coord_format's F
};

inline TraversalParams traversal_params(const RasterState& st) {
  return {st.traversal, st.tile_size, st.hier_levels, st.scanline_arith, st.coord_format.frac_bits};
}

// One triangle by the configured method; emit(px, py) or emit(px, py, mask) per pixel with
// a covered sample.
template <class Emit>
void traverse(const SetupTriangle& t, const TraversalParams& p, TraversalCounters& c, Emit&& emit) {
  const int F = p.frac_bits;
  switch (p.method) {
    case Traversal::Tiled: traverse_triangle(t, p.tile_size, F, c, emit); break;
    case Traversal::Bbox:
      // One "tile": the whole box, tested pixel by pixel.
      ++c.tiles_visited;
      ++c.tiles_partial;
      c.count_tests(fine_raster_partial(t, t.bbox, F, counted(c, t.samples, emit)), t.samples);
      break;
    case Traversal::Hierarchical:
      walk_hierarchical(t, t.bbox, p.hier_levels, 0, F, c, [&](const PixelRect& fp, TileClass cls) {
        if (cls == TileClass::Accepted) {
          c.count_accepted(fp.area(), t.samples);
          fine_raster_accepted(fp, emit, t.full_mask());
        } else {
          c.count_tests(fine_raster_partial(t, fp, F, counted(c, t.samples, emit)), t.samples);
        }
      });
      break;
    case Traversal::Scanline:
      scanline_spans(t, p.scan_arith, F, [&](int py, int x0, int x1) {
        if (x0 >= x1) return;
        ++c.spans;
        c.fragments += static_cast<uint64_t>(x1 - x0);
        c.samples_covered += static_cast<uint64_t>(x1 - x0);  // one sample: config validation
        emit_span(emit, py, x0, x1, 1u);
      });
      break;
  }
}

}  // namespace rastsim
