// SPDX-License-Identifier: Apache-2.0
// Keys of the triangle traversal method (docs/traversal.md): raster.traversal and the
// parameters of the hierarchical and scanline methods. Sweepable like any key (the
// levels are '/'-separated so that `rastsim sweep --set` can list several with ',').
#include "config/config_schema.h"
#include "ref/traverse.h"

namespace rastsim {

namespace {
bool is_hier_levels(const ParamValue& v) { return !parse_hier_levels(std::get<std::string>(v)).empty(); }
}  // namespace

void add_traversal_params(std::vector<ParamDef>& s) {
  using T = ParamType;
  s.push_back({"raster.traversal", T::Enum, std::string("tiled"), "", 1, 0,
               {"tiled", "bbox", "hierarchical", "scanline"},
               "Triangle traversal: tiled (coarse tiles of raster.tile_size, then per-pixel tests), bbox (every "
               "pixel of the bounding box tested), hierarchical (tiles of raster.hier_levels), scanline (the notes' "
               "dx/dy edge walk in raster.scanline_arith; inexact, counted as pixels_wrong/cracks/overlaps)"});
  s.push_back({"raster.hier_levels", T::String, std::string("64/16/4"), "px", 1, 0, {},
               "Tile sizes of the hierarchical traversal, largest first; a partial tile is split into the next "
               "level's, a partial tile of the last level is tested per pixel",
               is_hier_levels, "of form L0/L1/...: 1 to 8 powers of two in [2, 1024], strictly decreasing"});
  s.push_back({"raster.scanline_arith", T::Enum, std::string("f32"), "", 1, 0, {"f32", "f64", "fixed"},
               "Arithmetic of the scanline traversal: IEEE single, double, or fixed point with the fraction bits of "
               "raster.coord_format (gradient and x-intersections rounded to nearest even)"});
}

void validate_traversal(const Config& cfg) {
  if (cfg.get_string("raster.traversal") == "scanline" && cfg.get_string("raster.fill_rule") != "top_left")
    throw ConfigError(cfg.origin("raster.traversal") + ": raster.traversal = scanline implements the top-left "
                      "convention only, but raster.fill_rule = " + cfg.get_string("raster.fill_rule") + " (" +
                      cfg.origin("raster.fill_rule") + "); use fill_rule top_left or another traversal");
}

}  // namespace rastsim
