// SPDX-License-Identifier: Apache-2.0
// Seeded random clip-space triangle scenes for the llvmpipe comparison of the geometry
// front end (docs/mesa.md, "Clip space"). Every coordinate is an IEEE binary32 value, as
// a vertex stage hands it over; colours are random RGB8 per vertex.
//
// - Inside: all three vertices inside the view volume, w from 0.1 to 100, NDC extents
//   from a few pixels to the whole viewport.
// - NearCrossing: one or two vertices in front of the near plane (z < 0 < w).
// - BehindEye: one or two vertices behind the eye (w < 0).
// - Sliver: the third vertex a homogeneous combination of the other two, moved off
//   their line by 0 to about 1 px on screen (0: collinear up to binary32 rounding).
// - NearZeroW: one or two vertices with |w| in [1e-7, 1e-2], either on screen (x, y
//   scaled with w) or far off it, in front of and behind the eye.
// - BeyondGuardBand: vertices up to 10^5 viewports outside (|x/w|, |y/w| up to 1e5).
// - Camera: eye-space triangles around a camera, some through it, projected by a
//   binary32 perspective matrix (Vulkan depth 0..1, y down): what a vertex stage makes.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "ref/scene.h"

namespace rastsim::mesa {

struct ClipTri {
  std::array<ClipVertex, 3> v;
};

// Where clip space maps on screen: `viewport_xform X Y W H` resolved to pixels (y down).
struct ViewRect {
  int x = 0, y = 0, width = 0, height = 0;
};

enum class ClipKind { Inside, NearCrossing, BehindEye, Sliver, NearZeroW, BeyondGuardBand, Camera };
const char* to_string(ClipKind k);
inline constexpr ClipKind kClipKinds[] = {ClipKind::Inside,    ClipKind::NearCrossing, ClipKind::BehindEye,
                                          ClipKind::Sliver,    ClipKind::NearZeroW,    ClipKind::BeyondGuardBand,
                                          ClipKind::Camera};

// `count` triangles of one kind; the same seed gives the same triangles everywhere.
std::vector<ClipTri> make_clip_scene(ClipKind kind, uint64_t seed, int count);

// The viewport transform a seeded scene is drawn with inside a fb_width x fb_height
// framebuffer: the whole framebuffer, or a sub-rectangle (odd sizes included, so W/2 and
// X + W/2 are not whole pixels).
ViewRect make_view_rect(uint64_t seed, int fb_width, int fb_height);

// The triangle as the trace lines that reproduce it:
// "viewport_xform X Y W H\ntri4 x y z w r g b (three times)", binary32 values printed
// with 9 significant digits (read back to the same binary32).
std::string describe(const ClipTri& t, const ViewRect& vp);

}  // namespace rastsim::mesa
