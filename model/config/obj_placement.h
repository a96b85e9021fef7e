// SPDX-License-Identifier: Apache-2.0
// ObjPlacement: where an OBJ mesh lands on screen, from the config's display size and
// scene.obj_* keys (config -> typed parameters, one way). The OBJ reader (model/scene)
// places meshes with it.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "config/config.h"
#include "ref/fixed_point.h"
#include "ref/texture/texture.h"

namespace rastsim {

// The axis of an OBJ mesh that points up (scene.obj_up). Placement turns it to +y by
// an exact quarter or half turn (never a mirror), before yaw and pitch.
enum class ObjUp { PosY, PosZ, NegY, NegZ, PosX, NegX };

// "y", "z", "-y", "-z", "x", "-x" (the config's spelling); nullopt for anything else.
std::optional<ObjUp> parse_obj_up(const std::string& name);

// What the reader does with OBJ `l` (polyline) and `p` (point) statements
// (scene.obj_lines_points): stop at the first with its file:line, or skip and count them.
enum class ObjLinesPoints { Error, Skip };

// The OBJ camera (scene.camera): orthographic onto the screen, or perspective into clip
// space (docs/trace-format.md, "Perspective camera").
enum class ObjCamera { Ortho, Perspective };

// The order the OBJ faces are drawn in (scene.obj_order): the file's, or sorted by the
// face's nearest corner (the largest view-space z of its corners, i.e. the smallest
// depth) nearest first or farthest first, ties in file order; `l` and `p` statements
// then follow the faces, in file order (docs/depth-culling.md: the depth-order studies).
enum class ObjOrder { File, FrontToBack, BackToFront };

// Where an OBJ mesh lands on screen: a camera looking at the mesh's bounding sphere.
// Every value comes from the config (obj_placement_from_config); none has a default here.
struct ObjPlacement {
  int viewport_width = 0, viewport_height = 0;  // px (display.width, display.height)
  ObjUp up = ObjUp::PosY;             // the mesh's up axis (scene.obj_up)
  double yaw_deg = 0, pitch_deg = 0;  // then rotation about up (y), then x (scene.obj_*_deg)
  double fill = 0;                    // fraction of the viewport the sphere spans (scene.obj_fill)
  // Faces sent in one List command (scene.obj_faces_per_command): 1, each face its own
  // command as a naive driver would send it; more, as a draw call would batch them.
  int faces_per_command = 0;
  ObjOrder order = ObjOrder::File;  // scene.obj_order
  // raster.coord_format: polygon faces are triangulated on their corners snapped to it,
  // exactly as setup snaps them (docs/trace-format.md, "Polygon faces").
  FixedFormat coord_format{};
  ObjLinesPoints lines_points = ObjLinesPoints::Error;  // scene.obj_lines_points
  // scene.camera and, for perspective, its frustum: vertical field of view, near and far
  // planes and the eye's distance from the mesh centre, lengths in bounding radii.
  ObjCamera camera = ObjCamera::Ortho;
  double fov_deg = 0, near = 0, far = 0, distance = 0;
  uint8_t clear_r = 0, clear_g = 0, clear_b = 0;
  // scene.obj_texfilter and scene.obj_mipmap: a textured face's filter and whether it
  // samples the mip chain (MTL has neither).
  TexFilter tex_filter = TexFilter::Bilinear;
  bool tex_mipmap = false;
};

// From a validated config: the display size, raster.coord_format and the scene.obj_* keys.
ObjPlacement obj_placement_from_config(const Config& cfg);

}  // namespace rastsim
