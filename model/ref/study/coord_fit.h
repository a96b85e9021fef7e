// SPDX-License-Identifier: Apache-2.0
// The narrowest coordinate format a scene needs (`rastsim fit`) and the coordinate
// precision study (docs/stability.md, "Coordinate precision").
//
// - render_signature: what "the same render" means here: the colour buffer's CRC-32 and
//   the fragment stream (every fragment leaving interpolation, in pipeline order, as
//   its trace line "x y z r g b"), CRC-32 and count. A render that throws (a vertex
//   outside the format, a viewport too large for it) has no signature.
// - fit_coord_format: I = the fewest integer bits that hold every triangle vertex (at the
//   widest format s I.(31-I), relative to the viewport centre in effect) and every
//   viewport of the scene (display size and `viewport` commands); then F = the fewest
//   fraction bits (1 .. 31-I, scanned upward) whose render signature equals that of
//   s I.(31-I). Also says whether the scene is exact at 0 fraction bits.
// - snap_scene_to_integer_pixels: every triangle vertex rounded to an integer pixel
//   (nearest, ties to even): the "0 sub-pixel bits" case; a clip-space command becomes
//   the list of its front end's screen-space triangles (under `arch` and the scene's
//   viewport commands), snapped. The model's formats need
//   F >= 1 (pixel centres sit at +0.5), so F = 0 is rendered as these integer vertices
//   in s I.1, which is exactly what a 0-fraction-bit vertex grid gives.
// - measure_precision: for F = 0..max_frac, pixels whose colour differs from the render
//   at max_frac, cracks of a closed mesh, and the edge width of s I.F.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "ref/fixed_point.h"
#include "ref/raster_state.h"
#include "ref/scene.h"

namespace rastsim {

struct RenderSignature {
  bool ok = false;
  std::string error;             // why the render failed (!ok)
  uint32_t color_crc32 = 0;      // Framebuffer::color_crc32
  uint32_t fragments_crc32 = 0;  // CRC-32 of the fragment trace lines, '\n'-terminated
  uint64_t fragments = 0;
  uint32_t coverage_crc32 = 0;   // CRC-32 of the fragments' "x y" lines only: coverage
  // Identical renders: both succeeded with equal CRCs and counts.
  bool same_as(const RenderSignature& o) const {
    return ok && o.ok && color_crc32 == o.color_crc32 && fragments_crc32 == o.fragments_crc32 &&
           fragments == o.fragments;
  }
};

// Renders `scene` with `arch` (its coord_format as given, raster.out_of_range forced to
// error so that a vertex outside the format fails the render rather than vanishing).
RenderSignature render_signature(const Scene& scene, const RasterState& arch);

Scene snap_scene_to_integer_pixels(const Scene& scene, const RasterState& arch);

// Smallest I (0..30) whose format s I.(31-I) holds every viewport of the scene.
int int_bits_for_viewports(const Scene& scene, const RasterState& arch);
// Smallest I (0..30) whose format s I.(31-I) holds every triangle vertex; throws
// SceneError naming the vertex when none does.
int int_bits_for_vertices(const Scene& scene, const RasterState& arch);

struct FitTrial {
  int frac_bits = 0;
  bool identical = false;      // same_as the reference
  bool same_coverage = false;  // same fragment positions in the same order
  bool same_color = false;     // same colour buffer CRC
  std::string error;  // the render failed at this format
};

struct CoordFit {
  int int_bits_viewport = 0, int_bits_vertices = 0;  // the two lower bounds on I
  FixedFormat widest;        // s I.(31-I): the reference
  FixedFormat format;        // the fit: same I, fewest F rendering identically
  DatapathWidths widths;     // of `format` (datapath_widths)
  RenderSignature reference; // of `widest`
  RenderSignature fitted;    // of `format`
  bool exact_at_zero_frac = false;  // integer vertices in s I.1 render identically too
  // The fewest F with the same coverage and with the same colour buffer (weaker than
  // identity: depth and colour interpolation see every LSB of the vertices).
  int coverage_frac_bits = 0, color_frac_bits = 0;
  std::vector<FitTrial> trials;     // F = 1 .. format.frac_bits, in order
};

// Throws SceneError when the reference render itself fails (its message).
CoordFit fit_coord_format(const Scene& scene, const RasterState& arch);

// True when the scene's triangles form closed surfaces: every edge (by exact vertex
// position) is used by exactly two triangles, once in each direction. False for a scene
// with a clip-space command: the front end's clipping opens a closed mesh where a plane
// cuts it, so its screen triangles need not balance.
bool is_closed_mesh(const Scene& scene);

// Pixels whose signed coverage (clockwise triangles +1, counter-clockwise -1, the exact
// edge test of each triangle's setup with its fill rule, culling off) is not zero. For a
// closed mesh every pixel is covered as often from the front as from the back, so each
// such pixel is a crack (or a double cover) on a shared edge.
uint64_t unbalanced_pixels(const Scene& scene, const RasterState& arch);

struct PrecisionRow {
  int frac_bits = 0;        // sub-pixel bits (0: integer vertices, rendered in s I.1)
  FixedFormat format;       // the format rendered
  bool ok = false;          // false: the render failed (error)
  std::string error;
  uint64_t pixels_different = 0;  // colour differs from the max_frac render
  std::optional<uint64_t> cracks;  // closed meshes only
  int edge_width = 0;       // datapath_widths(format).edge: for F = 0 that of s I.1, since
                            // pixel-centre samples (+0.5) need the one fraction bit anyway
};

std::vector<PrecisionRow> measure_precision(const Scene& scene, const RasterState& arch, int int_bits,
                                            int max_frac = 16);

// The perspective datapath's widths a scene needs (`rastsim fit`, docs/clip-space.md):
// - texture coordinates: the largest |s|, |t| of a set-up triangle's vertex (the
//   perspective-correct value at any covered sample lies between its vertices') and the
//   fewest integer bits I of interp.texcoord_format s I.F holding it (2^I > it);
// - the reciprocal: for 0..kRecipFitIterations Newton-Raphson steps, the fewest
//   interp.recip_seed_bits (1..16, scanned upward) whose render signature equals that of
//   interp.recip = exact; 0 when none does. Only triangles whose three 1/w differ take a
//   reciprocal (SetupTriangle::affine): with none, nothing is scanned.
inline constexpr int kRecipFitIterations = 4;  // interp.recip_iterations' largest value
struct RecipFit {
  uint64_t triangles = 0, perspective_triangles = 0;  // set up (accepted); of them not affine
  double max_abs_texcoord = 0.0;
  int texcoord_int_bits = 0;
  RenderSignature exact;                                 // interp.recip = exact (perspective scenes only)
  std::array<int, kRecipFitIterations + 1> seed_bits{};  // by iterations
};
RecipFit fit_recip(const Scene& scene, const RasterState& arch);

}  // namespace rastsim
