// SPDX-License-Identifier: Apache-2.0
// OBJ loader: a Wavefront OBJ subset placed on screen by ObjPlacement (docs/trace-format.md).
//
// - Parse: `v x y z [w] [r g b]`, `vt u [v [w]]`, `f` in the forms i, i/t, i//n, i/t/n
//   with negative (relative) indices and distinct corners, `mtllib`/`usemtl` with
//   `newmtl`/`Kd` from the MTL. What is read but not used (vn, o, g, s, the MTL's other
//   statements and texture maps, whose files must exist) is counted in
//   Scene::obj_ignored. `l` and `p` are drawn by the perspective camera; with the
//   orthographic one they stop the reader unless scene.obj_lines_points = skip, which
//   counts them too.
// - Place: turn the mesh's up axis (scene.obj_up) to +y, centre the bounding box of the
//   vertices faces use, rotate about y (yaw) then x (pitch); then either project
//   orthographically so the bounding sphere spans `fill` of the smaller viewport side, y
//   down on screen, depth 0 (near) .. 1 (far) over the sphere, or (scene.camera =
//   perspective) into binary32 clip space (obj_camera.h) for the geometry front end.
// - Texture coordinates: a corner's `vt u v` travels with it as s = u, t = 1 - v; a
//   material's `map_Kd` is the texture of its faces (modulating their shaded colour).
// - Shade: colour (vertex colour, else material Kd, else white) times a headlight
//   Lambert term 0.25 + 0.75 * max(0, n_z) of the face's view-space normal.
// - Triangulate (face_triangulate.h) on the corners snapped to raster.coord_format (in
//   the face's own plane for the perspective camera): a convex outline is fanned from
//   its first corner, a concave one ear-clipped; a face crossing itself in its own plane
//   is an error.
// - Emit: CmdClear, CmdClearDepth 1, then one List command per face, each named by the
//   face's line; or, with scene.obj_faces_per_command N > 1, one List command per N
//   faces, named by the first; each `l` a LineStrip and each `p` a Points command.
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <functional>
#include <iostream>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

#include "ref/scene.h"
#include "scene/face_triangulate.h"
#include "scene/obj_camera.h"
#include "scene/scene_text.h"
#include "scene/scene_io.h"
#include "scene/texture_file.h"

namespace rastsim {

namespace {

using scene_text::quote;
using scene_text::Tokens;
using Vec3 = std::array<double, 3>;
using Rgb = std::array<double, 3>;  // linear 0..1, as OBJ and MTL write colours

// Ambient share of the headlight shading: faces turned away from the viewer keep a
// quarter of their colour so silhouettes stay visible against the clear colour.
constexpr double kAmbient = 0.25;

struct ObjVertex {
  Vec3 p{};
  std::optional<Rgb> rgb;  // trailing `r g b` some exporters write
  int line = 0;
};

// What a face, `l` or `p` statement draws: a polygon, a polyline or points.
enum class ObjKind { Face, Line, Point };

// A corner without a texture coordinate.
constexpr size_t kNoTexcoord = SIZE_MAX;

struct ObjFace {
  int line = 0;
  ObjKind kind = ObjKind::Face;
  std::vector<size_t> v;   // 0-based vertex indices
  std::vector<size_t> vt;  // 0-based texture coordinate index of each corner, or kNoTexcoord
  std::optional<Rgb> kd;   // material in force at the face
  std::shared_ptr<const TextureImage> texture;  // its map_Kd, if any (faces only)
};

// Statements that carry nothing a flat-shaded triangle rasteriser uses: counted.
bool ignored_statement(std::string_view kw) {
  static constexpr std::string_view kIgnored[] = {
      "o", "g", "s", "vp", "mg", "lod", "usemap", "maplib",
      "shadow_obj", "trace_obj", "bevel", "c_interp", "d_interp", "ctech", "stech"};
  return std::find(std::begin(kIgnored), std::end(kIgnored), kw) != std::end(kIgnored);
}

// MTL statements naming a texture file (the last token; options such as -s u v w may
// precede it).
bool texture_map_statement(std::string_view kw) {
  return kw.substr(0, 4) == "map_" || kw == "bump" || kw == "disp" || kw == "decal" || kw == "refl";
}

// Material names may hold spaces (some exporters write them): the rest of the line.
std::string rest_of_line(const Tokens& t) {
  std::string s;
  for (size_t i = 1; i < t.size(); ++i) s += (i > 1 ? " " : "") + std::string(t[i]);
  return s;
}

class ObjParser {
 public:
  // `draw_lines_points`: `l` and `p` are drawn (the perspective camera); otherwise
  // `lines_points` says whether they stop the reader or are skipped.
  ObjParser(const std::string& name, const std::string& base_dir, ObjLinesPoints lines_points,
            bool draw_lines_points)
      : name_(name), base_dir_(base_dir), lines_points_(lines_points), draw_lines_points_(draw_lines_points) {}

  void line(int n, const Tokens& t) {
    line_ = n;
    const std::string_view kw = t[0];
    if (kw == "v") return vertex(t);
    if (kw == "vt") return texcoord(t);
    if (kw == "vn") return counted(t, 3, 3, vn_count_);
    if (kw == "f") return face(t);
    if (kw == "mtllib") return mtllib(t);
    if (kw == "usemtl") return usemtl(t);
    if (kw == "l" || kw == "p") return line_or_point(t);
    if (!ignored_statement(kw)) fail("unknown OBJ statement " + quote(kw));
    ++ignored[std::string(kw)];
  }

  std::vector<ObjVertex> vertices;
  std::vector<std::array<double, 2>> texcoords;  // `vt u v` (v 0 when not written)
  std::vector<ObjFace> faces;  // faces, and `l` and `p` when drawn, in file order
  StatementCounts ignored;  // statement -> count, the MTL files' included

 private:
  [[noreturn]] void fail(const std::string& what) const { scene_text::fail(name_, line_, what); }

  double number(std::string_view tok, const std::string& what) const {
    const auto v = scene_text::parse_double(tok);
    if (!v) fail(what + " " + quote(tok) + " is not a finite number");
    return *v;
  }

  double unit(std::string_view tok, const std::string& what) const {
    const double v = number(tok, what);
    if (v < 0.0 || v > 1.0) fail(what + " " + quote(tok) + " is outside [0, 1]");
    return v;
  }

  void vertex(const Tokens& t) {
    const size_t n = t.size() - 1;
    if (n != 3 && n != 4 && n != 6)
      fail("'v' takes x y z, x y z w or x y z r g b, got " + std::to_string(n) + " numbers");
    ObjVertex v;
    v.line = line_;
    v.p = {number(t[1], "x"), number(t[2], "y"), number(t[3], "z")};
    if (n == 4) number(t[4], "w");  // rational weight: meaningless for polygons, checked only
    if (n == 6) v.rgb = Rgb{unit(t[4], "red"), unit(t[5], "green"), unit(t[6], "blue")};
    vertices.push_back(v);
  }

  // 3D points and lines need depth, which only clip space carries: drawn by the
  // perspective camera; with the orthographic one refused at every level, or skipped and
  // counted on request.
  void line_or_point(const Tokens& t) {
    const std::string_view kw = t[0];
    if (draw_lines_points_) {
      const size_t least = kw == "l" ? 2 : 1;
      if (t.size() - 1 < least)
        fail("'" + std::string(kw) + "' needs at least " + std::to_string(least) + (least == 1 ? " vertex" : " vertices") +
             ", got " + std::to_string(t.size() - 1));
      ObjFace f;
      f.line = line_;
      f.kind = kw == "l" ? ObjKind::Line : ObjKind::Point;
      f.kd = material_;
      for (size_t k = 1; k < t.size(); ++k) corner(t[k], "vertex " + std::to_string(k) + " ", f);
      faces.push_back(std::move(f));
      return;
    }
    if (lines_points_ == ObjLinesPoints::Skip) {
      ++ignored[std::string(kw)];
      return;
    }
    fail(std::string(kw == "l" ? "'l' (polyline)" : "'p' (point)") +
         " statements are drawn by the perspective camera only (3D lines and points need clip space's depth; "
         "docs/trace-format.md, \"OBJ subset\"): set scene.camera = \"perspective\", remove them or set "
         "scene.obj_lines_points = \"skip\"");
  }

  // vt u [v [w]]: u and v kept (v 0 when not written), w checked only.
  void texcoord(const Tokens& t) {
    const size_t n = t.size() - 1;
    if (n < 1 || n > 3) fail("'vt' takes 1 to 3 numbers, got " + std::to_string(n));
    const double u = number(t[1], "'vt' u"), v = n >= 2 ? number(t[2], "'vt' v") : 0.0;
    if (n == 3) number(t[3], "'vt' w");
    // s = u and t = 1 - v become binary32 (corner_attributes): they must stay finite.
    if (!std::isfinite(static_cast<float>(u)) || !std::isfinite(static_cast<float>(1.0 - v)))
      fail("'vt' " + std::string(std::isfinite(static_cast<float>(u)) ? "v " + quote(t[2]) : "u " + quote(t[1])) +
           " is outside the binary32 range of a texture coordinate");
    texcoords.push_back({u, v});
  }

  // vt / vn: only their count matters (faces may index them); the numbers are checked.
  void counted(const Tokens& t, size_t lo, size_t hi, size_t& count) {
    const size_t n = t.size() - 1;
    if (n < lo || n > hi)
      fail("'" + std::string(t[0]) + "' takes " + std::to_string(lo) +
           (lo == hi ? "" : " to " + std::to_string(hi)) + " numbers, got " + std::to_string(n));
    for (size_t i = 1; i <= n; ++i) number(t[i], "'" + std::string(t[0]) + "' component");
    ++count;
    ++ignored[std::string(t[0])];
  }

  // A 1-based (or negative, relative to the end so far) index into `count` elements.
  size_t index(std::string_view tok, size_t count, const std::string& what) const {
    const auto v = scene_text::parse_int(tok);
    if (!v) fail(what + " " + quote(tok) + " is not an integer");
    if (*v == 0) fail(what + " 0 is invalid (OBJ indices start at 1; negative ones count back)");
    const int64_t n = static_cast<int64_t>(count);
    if (*v > n || *v < -n)
      fail(what + " " + std::to_string(*v) + " is out of range (" + std::to_string(count) + " defined so far)");
    return static_cast<size_t>(*v > 0 ? *v - 1 : n + *v);
  }

  // One corner `i`, `i/t`, `i//n` or `i/t/n` appended to f (vertex and texture indices).
  void corner(std::string_view tok, const std::string& label, ObjFace& f) const {
    // Split "i/t/n" into at most three parts.
    std::array<std::string_view, 3> part{};
    size_t parts = 0;
    std::string_view rest = tok;
    for (;;) {
      if (parts == 3) fail(label + quote(tok) + " has more than three '/'-separated parts");
      const size_t slash = rest.find('/');
      part[parts++] = rest.substr(0, slash);
      if (slash == std::string_view::npos) break;
      rest.remove_prefix(slash + 1);
    }
    const bool bad_tex = parts == 2 && part[1].empty();
    if (part[0].empty() || bad_tex || (parts == 3 && part[2].empty()))
      fail(label + quote(tok) + " is not of the form i, i/t, i//n or i/t/n");
    f.v.push_back(index(part[0], vertices.size(), label + "index"));
    f.vt.push_back(parts >= 2 && !part[1].empty() ? index(part[1], texcoords.size(), label + "texture index")
                                                  : kNoTexcoord);
    if (parts == 3) index(part[2], vn_count_, label + "normal index");
  }

  void face(const Tokens& t) {
    if (t.size() - 1 < 3) fail("'f' needs at least 3 vertices, got " + std::to_string(t.size() - 1));
    ObjFace f;
    f.line = line_;
    f.kd = material_;
    f.texture = material_texture_;
    for (size_t k = 1; k < t.size(); ++k) {
      const std::string label = "face vertex " + std::to_string(k) + " ";
      corner(t[k], label, f);
      const size_t v = f.v.back();
      for (size_t j = 0; j + 1 < f.v.size(); ++j)
        if (f.v[j] == v)
          fail(label + quote(t[k]) + " is vertex " + std::to_string(v + 1) + " again (face vertex " +
               std::to_string(j + 1) + "): a face's corners must be distinct");
    }
    faces.push_back(std::move(f));
  }

  void mtllib(const Tokens& t) {
    if (t.size() < 2) fail("'mtllib' needs a file name");
    for (size_t i = 1; i < t.size(); ++i) {
      const std::string path = (std::filesystem::path(base_dir_) / std::string(t[i])).string();
      std::string text;
      try {
        text = scene_text::read_file(path);
      } catch (const SceneError&) {
        fail("cannot open material library " + quote(t[i]) + " (looked for " + quote(path) + ")");
      }
      parse_mtl(text, path);
    }
  }

  // MTL: `newmtl NAME` starts a material, `Kd r [g b]` sets its diffuse colour, `map_Kd
  // FILE` its texture (decoded now, FILE relative to the MTL's directory); every other
  // statement (Ka, Ks, Ns, d, illum, other map_*, PBR extensions) is counted as ignored,
  // and a texture map's file must exist beside the MTL. A material without Kd is white;
  // a later `newmtl` of the same name replaces the earlier one.
  void parse_mtl(const std::string& text, const std::string& path) {
    std::string current;
    scene_text::for_each_line(text, path, [&](int n, const Tokens& t) {
      auto mtl_fail = [&](const std::string& what) { scene_text::fail(path, n, what); };
      if (t[0] != "newmtl" && t[0] != "Kd" && t[0] != "map_Kd") ++ignored[std::string(t[0])];
      if (texture_map_statement(t[0])) check_map_file(t, path, mtl_fail);
      if (t[0] == "map_Kd") {
        if (current.empty()) mtl_fail("'map_Kd' before any 'newmtl'");
        textures_[current] = load_texture_file(map_file(t, path).string(), path, n);
      }
      if (t[0] == "newmtl") {
        if (t.size() < 2) mtl_fail("'newmtl' needs a material name");
        current = rest_of_line(t);
        materials_[current] = Rgb{1.0, 1.0, 1.0};
        textures_.erase(current);
      } else if (t[0] == "Kd") {
        if (current.empty()) mtl_fail("'Kd' before any 'newmtl'");
        if (t.size() > 1 && (t[1] == "spectral" || t[1] == "xyz"))
          mtl_fail("'Kd " + std::string(t[1]) + "' is not supported (only 'Kd r g b')");
        if (t.size() != 2 && t.size() != 4) mtl_fail("'Kd' takes r g b (or one grey value) in [0, 1]");
        Rgb kd{};
        for (size_t c = 0; c < 3; ++c) {
          const std::string_view tok = t[t.size() == 2 ? 1 : c + 1];
          const auto v = scene_text::parse_double(tok);
          if (!v) mtl_fail("Kd " + quote(tok) + " is not a finite number");
          if (*v < 0.0 || *v > 1.0) mtl_fail("Kd " + quote(tok) + " is outside [0, 1]");
          kd[c] = *v;
        }
        materials_[current] = kd;
      }
    });
  }

  // A texture map's file (the last token), relative to the MTL's directory.
  static std::filesystem::path map_file(const Tokens& t, const std::string& mtl_path) {
    return std::filesystem::path(mtl_path).parent_path() / std::filesystem::path(std::string(t.back()));
  }
  template <class Fail>
  static void check_map_file(const Tokens& t, const std::string& mtl_path, const Fail& mtl_fail) {
    if (t.size() < 2) mtl_fail("'" + std::string(t[0]) + "' needs a file name");
    const std::filesystem::path file = map_file(t, mtl_path);
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec))
      mtl_fail("'" + std::string(t[0]) + "' names " + quote(t.back()) + ", which does not exist (looked for " +
               quote(file.string()) + ")");
  }

  void usemtl(const Tokens& t) {
    if (t.size() < 2) fail("'usemtl' needs a material name");
    const auto it = materials_.find(rest_of_line(t));
    if (it == materials_.end()) fail("unknown material " + quote(rest_of_line(t)) + " (no 'newmtl' of that name)");
    material_ = it->second;
    const auto tex = textures_.find(it->first);
    material_texture_ = tex == textures_.end() ? nullptr : tex->second;
  }

  const std::string& name_;
  const std::string& base_dir_;
  ObjLinesPoints lines_points_;
  bool draw_lines_points_;
  int line_ = 0;
  size_t vn_count_ = 0;
  std::map<std::string, Rgb> materials_;
  std::optional<Rgb> material_;
  std::map<std::string, std::shared_ptr<const TextureImage>> textures_;  // material -> map_Kd
  std::shared_ptr<const TextureImage> material_texture_;                 // usemtl's map_Kd
};

// The mesh's up axis turned to +y by a proper rotation (determinant +1, so faces keep
// their winding): only swaps and negations, exact in floating point, so a mesh authored
// Z-up and placed with obj_up = z gives bit for bit the commands of the same mesh
// authored Y-up. Z-up becomes Y-up by -90 deg about x, so the Z-up convention's front
// (the -y side, 3ds Max's front view) faces the viewer as OBJ's front (+z) does.
Vec3 to_y_up(const Vec3& p, ObjUp up) {
  const double x = p[0], y = p[1], z = p[2];
  switch (up) {
    case ObjUp::PosY: return {x, y, z};
    case ObjUp::NegY: return {x, -y, -z};  // half turn about x
    case ObjUp::PosZ: return {x, z, -y};   // -90 deg about x: +z up, -y toward the viewer
    case ObjUp::NegZ: return {x, -z, y};   // +90 deg about x
    case ObjUp::PosX: return {-y, x, z};   // +90 deg about z
    case ObjUp::NegX: return {y, -x, z};   // -90 deg about z
  }
  return {x, y, z};
}

// 0..1 colour times shade to RGB8, rounding half up (one rounding for both factors).
uint8_t to_rgb8(double c, double shade) {
  return static_cast<uint8_t>(std::clamp(std::floor(c * shade * 255.0 + 0.5), 0.0, 255.0));
}

// The mesh's bounding sphere: about its bounding box centre, over the vertices faces use.
struct BoundingSphere {
  Vec3 centre;
  double radius;
};

BoundingSphere bounding_sphere(const std::vector<ObjVertex>& verts, const std::vector<bool>& used,
                               const std::string& name) {
  // Bounding box centre; halves first so that two huge finite bounds cannot overflow.
  Vec3 lo, hi;
  lo.fill(HUGE_VAL);
  hi.fill(-HUGE_VAL);
  for (size_t i = 0; i < verts.size(); ++i)
    for (int a = 0; a < 3 && used[i]; ++a) {
      lo[a] = std::min(lo[a], verts[i].p[a]);
      hi[a] = std::max(hi[a], verts[i].p[a]);
    }
  Vec3 centre;
  for (int a = 0; a < 3; ++a) centre[a] = lo[a] / 2 + hi[a] / 2;

  // Bounding sphere about that centre; positions are then taken relative to its radius,
  // so every later quantity is O(1) whatever units the file uses.
  double radius = 0;
  for (size_t i = 0; i < verts.size(); ++i) {
    if (!used[i]) continue;
    const Vec3& p = verts[i].p;
    const double d = std::hypot(p[0] - centre[0], p[1] - centre[1], p[2] - centre[2]);
    if (!std::isfinite(d)) scene_text::fail(name, verts[i].line, "vertex is too far from the mesh centre to place");
    radius = std::max(radius, d);
  }
  if (radius == 0) radius = 1;  // a single point: every face is degenerate, keep it finite
  return {centre, radius};
}

// View-space position (unit sphere) of every used vertex: about the sphere's centre,
// rotated about y (yaw) then x (pitch).
std::vector<Vec3> view_positions(const std::vector<ObjVertex>& verts, const std::vector<bool>& used,
                                 const BoundingSphere& sphere, const ObjPlacement& pl) {
  const Vec3& centre = sphere.centre;
  const double radius = sphere.radius;
  const double yaw = pl.yaw_deg * std::numbers::pi / 180, pitch = pl.pitch_deg * std::numbers::pi / 180;
  const double cy = std::cos(yaw), sy = std::sin(yaw), cp = std::cos(pitch), sp = std::sin(pitch);
  std::vector<Vec3> view(verts.size());
  for (size_t i = 0; i < verts.size(); ++i) {
    if (!used[i]) continue;
    const double x = (verts[i].p[0] - centre[0]) / radius, y = (verts[i].p[1] - centre[1]) / radius,
                 z = (verts[i].p[2] - centre[2]) / radius;
    const double x1 = x * cy + z * sy, z1 = -x * sy + z * cy;  // about y: +z turns toward +x
    view[i] = {x1, y * cp - z1 * sp, y * sp + z1 * cp};        // about x: +y turns toward +z
  }
  return view;
}

// The headlight shade of a face: kAmbient + (1 - kAmbient) max(0, n_z). Newell's
// normal: the polygon's area vector, exact for triangles and well defined for
// non-planar polygons; its z is toward the viewer.
double face_shade(const ObjFace& f, const std::vector<Vec3>& view) {
  Vec3 n{};
  for (size_t k = 0; k < f.v.size(); ++k) {
    const Vec3& a = view[f.v[k]];
    const Vec3& b = view[f.v[(k + 1) % f.v.size()]];
    n[0] += (a[1] - b[1]) * (a[2] + b[2]);
    n[1] += (a[2] - b[2]) * (a[0] + b[0]);
    n[2] += (a[0] - b[0]) * (a[1] + b[1]);
  }
  const double len = std::hypot(n[0], n[1], n[2]);
  const double nz = len > 0 ? n[2] / len : 0.0;
  return kAmbient + (1 - kAmbient) * std::max(0.0, nz);
}

// A corner's colour (its vertex colour, else the face's material Kd, else white) times
// `shade`, and its texture coordinate, s = u and t = 1 - v (t = 0 is the image's top
// row, as D3D and Vulkan sample), each computed in double and rounded once to binary32;
// (0, 0) without a `vt`. For a SceneVertex or a ClipVertex.
template <class V>
void corner_attributes(V& out, const ObjFace& f, size_t k, const ObjParser& obj, double shade) {
  const Rgb rgb = obj.vertices[f.v[k]].rgb.value_or(f.kd.value_or(Rgb{1.0, 1.0, 1.0}));
  out.r = to_rgb8(rgb[0], shade);
  out.g = to_rgb8(rgb[1], shade);
  out.b = to_rgb8(rgb[2], shade);
  if (f.vt[k] == kNoTexcoord) return;
  const std::array<double, 2>& uv = obj.texcoords[f.vt[k]];
  out.s = static_cast<float>(uv[0]);
  out.t = static_cast<float>(1.0 - uv[1]);
}

// A face's corners on screen: orthographic, the unit sphere spanning `fill` of the
// smaller viewport side, y down, depth 0 (near) .. 1 (far) over the sphere, shaded.
std::vector<SceneVertex> face_corners(const ObjFace& f, const std::vector<Vec3>& view, const ObjParser& obj,
                                      const ObjPlacement& pl) {
  const double px_per_radius = pl.fill * std::min(pl.viewport_width, pl.viewport_height) / 2.0;
  const double mid_x = pl.viewport_width / 2.0, mid_y = pl.viewport_height / 2.0;
  const double shade = face_shade(f, view);
  std::vector<SceneVertex> corner;
  for (size_t k = 0; k < f.v.size(); ++k) {
    const Vec3& q = view[f.v[k]];
    SceneVertex sv;
    sv.x = Q64::from_double(mid_x + px_per_radius * q[0]);
    sv.y = Q64::from_double(mid_y - px_per_radius * q[1]);  // object +y is up on screen
    sv.z = std::clamp(0.5 - 0.5 * q[2], 0.0, 1.0);           // larger view z is nearer
    corner_attributes(sv, f, k, obj, shade);
    corner.push_back(sv);
  }
  return corner;
}

// The corners of a face (shaded as on screen), polyline or points in clip space.
std::vector<ClipVertex> clip_corners(const ObjFace& f, const std::vector<Vec3>& view, const ObjParser& obj,
                                     const PerspectiveCamera& camera, double shade) {
  std::vector<ClipVertex> corner;
  for (size_t k = 0; k < f.v.size(); ++k) {
    ClipVertex c = camera.clip(view[f.v[k]]);
    corner_attributes(c, f, k, obj, shade);
    corner.push_back(c);
  }
  return corner;
}

// What a face's crossing edges are, for its error: corners are numbered from 1, edge k
// runs from corner k to corner k + 1 (the last back to corner 1).
std::string crossing_text(std::pair<size_t, size_t> e, size_t n) {
  auto edge = [&](size_t k) { return std::to_string(k + 1) + "-" + std::to_string((k + 1) % n + 1); };
  if (e.first == e.second) return "corners " + edge(e.first) + " are at one position";
  return "edges " + edge(e.first) + " and " + edge(e.second) +
         ((e.second == (e.first + 1) % n) ? " fold back onto each other" : " cross or touch");
}

// A polygon face's corners in model space, after checking that it does not cross itself
// in its own plane (an error whatever the view; docs/trace-format.md, "Polygon faces").
std::vector<Vec3> simple_face(const ObjFace& f, const std::vector<ObjVertex>& verts, const std::string& name) {
  std::vector<Vec3> face;
  for (size_t i : f.v) face.push_back(verts[i].p);
  if (face.size() == 3) return face;
  if (const auto e = face_crossing_in_plane(face))
    scene_text::fail(name, f.line, "the face crosses itself: " + crossing_text(*e, face.size()) +
                                       " (split it into simple polygons)");
  return face;
}

// The triangles of a face as corner indices, in its winding (docs/trace-format.md,
// "Polygon faces"), on the corners snapped as setup snaps them, relative to the viewport
// centre, so that the triangles cover exactly the snapped outline.
std::vector<FaceTriangle> face_triangles(const ObjFace& f, const std::vector<SceneVertex>& corner,
                                         const std::vector<ObjVertex>& verts, const ObjPlacement& pl,
                                         const std::string& name) {
  if (corner.size() == 3) return fan_triangles(3);
  simple_face(f, verts, name);
  std::vector<ScreenPoint> outline;
  for (const SceneVertex& c : corner) {
    const auto x = snap_coord(c.x, pl.viewport_width / 2, pl.coord_format);
    const auto y = snap_coord(c.y, pl.viewport_height / 2, pl.coord_format);
    if (!x || !y) return fan_triangles(corner.size());  // outside the format: setup reports or culls it
    outline.push_back({*x, *y});
  }
  FaceTriangulation t = triangulate_outline(outline);
  // An outline that crosses although the face does not is the view's doing (nearly
  // edge-on, corners within a coordinate LSB of an edge): fanned, a sliver that wide at
  // most, so that every view of a good mesh draws.
  if (t.shape == OutlineShape::Crossing) return fan_triangles(corner.size());
  return std::move(t.triangles);
}

// What the placement needs of the parsed mesh, for each face, `l` and `p`.
struct Placed {
  const ObjParser& obj;
  const std::vector<Vec3>& view;
  const ObjPlacement& pl;
  const PerspectiveCamera camera;
  const std::string& name;
};

// A face's triangles appended to a List command: on screen (ortho) or in clip space,
// triangulated in the face's own plane (part of it may lie behind the eye).
void append_face(CmdPrimitives& p, const ObjFace& f, const Placed& m) {
  if (m.pl.camera == ObjCamera::Ortho) {
    const std::vector<SceneVertex> corner = face_corners(f, m.view, m.obj, m.pl);
    for (const FaceTriangle& t : face_triangles(f, corner, m.obj.vertices, m.pl, m.name))
      for (uint32_t k : t) p.vertices.push_back(corner[k]);
    return;
  }
  const std::vector<ClipVertex> corner = clip_corners(f, m.view, m.obj, m.camera, face_shade(f, m.view));
  for (const FaceTriangle& t : triangulate_in_plane(simple_face(f, m.obj.vertices, m.name)))
    for (uint32_t k : t) p.clip_vertices.push_back(corner[k]);
}

// An `l` as a clip-space LineStrip, a `p` as Points: unlit (no normal), full colour.
CmdPrimitives line_or_point_command(const ObjFace& f, const Placed& m) {
  CmdPrimitives p;
  p.topology = f.kind == ObjKind::Line ? Topology::LineStrip : Topology::Points;
  p.clip_vertices = clip_corners(f, m.view, m.obj, m.camera, 1.0);
  return p;
}

// scene.obj_order: the faces sorted by their nearest corner (the largest view z of their
// corners), stably; `l` and `p` statements after them, in file order.
void order_faces(std::vector<ObjFace>& faces, const std::vector<Vec3>& view, ObjOrder order) {
  if (order == ObjOrder::File) return;
  const auto nearest = [&](const ObjFace& f) {
    double z = -std::numeric_limits<double>::infinity();
    for (size_t i : f.v) z = std::max(z, view[i][2]);
    return z;
  };
  const auto first = std::stable_partition(faces.begin(), faces.end(),
                                           [](const ObjFace& f) { return f.kind == ObjKind::Face; });
  std::vector<std::pair<double, size_t>> key;  // (nearest z, file position): the stable sort's key
  for (auto it = faces.begin(); it != first; ++it) key.emplace_back(nearest(*it), size_t(it - faces.begin()));
  std::stable_sort(key.begin(), key.end(), [&](const auto& a, const auto& b) {
    return order == ObjOrder::FrontToBack ? a.first > b.first : a.first < b.first;
  });
  std::vector<ObjFace> sorted;
  sorted.reserve(faces.size());
  for (const auto& k : key) sorted.push_back(std::move(faces[k.second]));
  for (auto it = first; it != faces.end(); ++it) sorted.push_back(std::move(*it));
  faces = std::move(sorted);
}

// Places the parsed mesh and emits its commands (see the file comment for the maths).
Scene place(ObjParser& obj, const std::string& name, const ObjPlacement& pl) {
  for (ObjVertex& v : obj.vertices) v.p = to_y_up(v.p, pl.up);  // in place: no second copy
  const auto& verts = obj.vertices;
  std::vector<bool> used(verts.size(), false);
  for (const ObjFace& f : obj.faces)
    for (size_t i : f.v) used[i] = true;
  const std::vector<Vec3> view = view_positions(verts, used, bounding_sphere(verts, used, name), pl);
  const Placed m{obj, view, pl, PerspectiveCamera(pl), name};
  const SourceLoc first{name, obj.faces.front().line};  // the file's first statement, before any reorder
  order_faces(obj.faces, view, pl.order);

  Scene scene;
  scene.source = name;
  scene.obj_ignored = std::move(obj.ignored);
  scene.commands.push_back({CmdClear{pl.clear_r, pl.clear_g, pl.clear_b}, first});
  scene.commands.push_back({CmdClearDepth{1.0}, first});
  int faces_in_command = 0;  // faces in the List command being filled (0: start a new one)
  for (const ObjFace& f : obj.faces) {
    if (f.kind != ObjKind::Face) {  // its own command, between the faces before and after it
      scene.commands.push_back({line_or_point_command(f, m), SourceLoc{name, f.line}});
      faces_in_command = 0;
      continue;
    }
    // A new List command every faces_per_command faces, named by its first face's line,
    // and where the texture (map_Kd) changes; the triangles and their order are the same
    // whatever the grouping.
    if (faces_in_command > 0 && std::get<CmdPrimitives>(scene.commands.back().body).texture.image != f.texture)
      faces_in_command = 0;
    if (faces_in_command == 0) {
      CmdPrimitives p{Topology::List, {}};
      p.texture.image = f.texture;  // the initial texture state otherwise (docs/texture.md) but
      p.texture.filter = pl.tex_filter;  // scene.obj_texfilter and scene.obj_mipmap
      p.texture.mipmap = pl.tex_mipmap;
      scene.commands.push_back({std::move(p), SourceLoc{name, f.line}});
    }
    append_face(std::get<CmdPrimitives>(scene.commands.back().body), f, m);
    if (++faces_in_command == pl.faces_per_command) faces_in_command = 0;
  }
  return scene;
}

// "vn 34834, vt 12, s 1": the counts in keyword order.
std::string counts_text(const StatementCounts& c) {
  std::string s;
  for (const auto& [kw, n] : c) s += (s.empty() ? "" : ", ") + kw + " " + std::to_string(n);
  return s;
}

}  // namespace

Scene parse_obj(const std::string& text, const std::string& name, const ObjPlacement& placement,
                const std::string& base_dir) {
  const ObjPlacement& pl = placement;
  if (pl.viewport_width < 1 || pl.viewport_height < 1 || !std::isfinite(pl.fill) || pl.fill <= 0 ||
      !std::isfinite(pl.yaw_deg) || !std::isfinite(pl.pitch_deg) || pl.faces_per_command < 1 ||
      pl.coord_format.frac_bits < 1 || pl.coord_format.int_bits + pl.coord_format.frac_bits > kMaxFormatBits)
    throw SceneError(name + ": OBJ placement needs a positive viewport, a positive finite fill, "
                            "finite yaw and pitch, at least one face a command and a coordinate format");
  const bool perspective = pl.camera == ObjCamera::Perspective;
  if (perspective && !(std::isfinite(pl.fov_deg) && pl.fov_deg > 0 && pl.fov_deg < 180 && pl.near > 0 &&
                       pl.far > pl.near && std::isfinite(pl.far) && pl.distance >= 0 && std::isfinite(pl.distance)))
    throw SceneError(name + ": OBJ perspective camera needs a field of view in (0, 180) degrees, "
                            "0 < near < far and a finite distance >= 0");
  ObjParser obj(name, base_dir, pl.lines_points, perspective);
  const int lines = scene_text::for_each_line(text, name, [&](int n, const Tokens& t) { obj.line(n, t); });
  if (obj.faces.empty())
    scene_text::fail(name, std::max(lines, 1),
                     perspective ? "no faces, lines or points (an OBJ scene needs at least one 'f', 'l' or 'p')"
                                 : "no faces (an OBJ scene needs at least one 'f')");
  return place(obj, name, pl);
}

namespace {
std::string dir_of(const std::string& path) {
  const std::string dir = std::filesystem::path(path).parent_path().string();
  return dir.empty() ? "." : dir;
}
}  // namespace

Scene load_obj(const std::string& path, const ObjPlacement& placement) {
  Scene scene = parse_obj(scene_text::read_file(path), path, placement, dir_of(path));
  // Once per file read: what the scene leaves out is never silent.
  if (!scene.obj_ignored.empty()) std::cerr << path << ": ignored: " << counts_text(scene.obj_ignored) << "\n";
  return scene;
}

std::optional<StatementCounts> obj_ignored_counts(const std::string& path, ObjCamera camera) {
  if (!is_obj_path(path)) return std::nullopt;
  const std::string dir = dir_of(path);
  ObjParser obj(path, dir, ObjLinesPoints::Skip, camera == ObjCamera::Perspective);
  scene_text::for_each_line(scene_text::read_file(path), path, [&](int n, const Tokens& t) { obj.line(n, t); });
  return std::move(obj.ignored);
}

}  // namespace rastsim
