// SPDX-License-Identifier: Apache-2.0
// rastsim_llvmpipe_render: a trace rendered by Mesa's llvmpipe (OSMesa), whole process,
// for scripts/bench_mesa (docs/results.md, "Reference model against llvmpipe").
//
//   rastsim_llvmpipe_render --scene FILE --width W --height H -o OUT.ppm|png
//
// - Reads the trace with the same reader as `rastsim render` (model/scene stream_scene,
//   in batches of 4096 commands), so both processes pay the same parse.
// - Draws each batch's triangles with one glDrawArrays(GL_TRIANGLES) from client arrays
//   (positions as floats, RGB8 colours), smooth shading, no depth buffer, set up like
//   Direct3D 11 exactly as the coverage tests do (osmesa_renderer.h: top-left rule,
//   power-of-two viewport so that every vertex on the 2^-8 px grid reaches llvmpipe
//   unrounded). A vertex off that grid is an error naming its file:line: the comparison
//   is of rasterizers, not of two snapping rules.
// - `clear R G B` clears; `viewport` must equal W x H; `cleardepth` is ignored (no depth
//   buffer: the bench's config tests depth with `always`); anything else is an error.
// - Writes the colour buffer, row 0 at the top, through the same image writer as
//   `rastsim render` (model/display image_io).
// LP_NUM_THREADS chooses llvmpipe's rasterizer threads (unset: Mesa's default, all cores).
#include <GL/osmesa.h>

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include "image/image_io.h"
#include "osmesa_renderer.h"
#include "ref/prim_assembly.h"
#include "ref/scene.h"
#include "scene/scene_io.h"

namespace {

using namespace rastsim;

struct Options {
  std::string scene, out;
  int width = 0, height = 0;
};

[[noreturn]] void usage(const std::string& why) {
  std::cerr << "rastsim_llvmpipe_render: " << why
            << "\nusage: rastsim_llvmpipe_render --scene FILE --width W --height H -o OUT.ppm|png\n";
  std::exit(2);
}

Options parse_args(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "-h" || a == "--help") usage("renders a trace's triangles with llvmpipe (see the source's header)");
    if (i + 1 >= argc) usage(a + " needs a value");
    const std::string v = argv[++i];
    if (a == "--scene") o.scene = v;
    else if (a == "-o" || a == "--output") o.out = v;
    else if (a == "--width") o.width = std::atoi(v.c_str());
    else if (a == "--height") o.height = std::atoi(v.c_str());
    else usage("unknown option " + a);
  }
  if (o.scene.empty() || o.out.empty()) usage("--scene and -o are required");
  if (o.width < 1 || o.height < 1 || o.width > mesa::kViewport / 2 || o.height > mesa::kViewport / 2)
    usage("--width and --height must be in [1, " + std::to_string(mesa::kViewport / 2) + "]");
  return o;
}

// A scene coordinate (px) as raw 2^-8 px units, or an error naming loc.
float grid_coord(const Q64& v, const SourceLoc& loc) {
  const double px = v.to_double(), raw = px * double(1 << mesa::kSubpixelBits);
  if (raw != std::floor(raw) || std::fabs(raw) >= double(1 << 24))
    throw SceneError(loc.str() + ": vertex coordinate " + std::to_string(px) +
                     " is not on the 1/256 px grid (rastsim_llvmpipe_render feeds llvmpipe exact coordinates)");
  return float(raw);
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse_args(argc, argv);
  try {
    // Mesa's default thread count unless the caller set LP_NUM_THREADS (the bench does).
    setenv("GALLIUM_DRIVER", "llvmpipe", 0);
    const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 0, OSMESA_STENCIL_BITS, 0,
                           OSMESA_ACCUM_BITS, 0, OSMESA_PROFILE, OSMESA_COMPAT_PROFILE, 0};
    OSMesaContext ctx = OSMesaCreateContextAttribs(attribs, nullptr);
    if (!ctx) throw std::runtime_error("OSMesaCreateContextAttribs failed");
    std::vector<uint32_t> buffer(size_t(o.width) * size_t(o.height));
    if (!OSMesaMakeCurrent(ctx, buffer.data(), GL_UNSIGNED_BYTE, o.width, o.height))
      throw std::runtime_error("OSMesaMakeCurrent failed");
    using ClipControlFn = void (*)(GLenum, GLenum);
    auto clip_control = reinterpret_cast<ClipControlFn>(OSMesaGetProcAddress("glClipControl"));
    if (!clip_control) throw std::runtime_error("glClipControl not available");
    clip_control(GL_UPPER_LEFT, GL_ZERO_TO_ONE);  // D3D's y-down window: top-left rule (docs/mesa.md)
    const int P = mesa::kViewport;
    glViewport(-P / 2, o.height - P / 2, P, P);   // row = ndc_y * P/2 exactly (osmesa_renderer.cpp)
    mesa::set_coverage_state(false);
    glShadeModel(GL_SMOOTH);
    glEnableClientState(GL_VERTEX_ARRAY);
    glEnableClientState(GL_COLOR_ARRAY);

    // raw (2^-8 px) -> NDC: a power-of-two scale, exact in binary32.
    const float scale = 2.0f / (float(1 << mesa::kSubpixelBits) * float(P));
    std::vector<float> pos;
    std::vector<uint8_t> rgb;
    auto flush = [&] {
      if (pos.empty()) return;
      glVertexPointer(2, GL_FLOAT, 0, pos.data());
      glColorPointer(3, GL_UNSIGNED_BYTE, 0, rgb.data());
      glDrawArrays(GL_TRIANGLES, 0, GLsizei(pos.size() / 2));
      pos.clear();
      rgb.clear();
    };
    stream_scene(o.scene, ObjPlacement{}, 4096, [&](std::vector<Command>& batch) {
      for (const Command& cmd : batch) {
        if (const auto* p = std::get_if<CmdPrimitives>(&cmd.body)) {
          const size_t n = triangle_count(*p);
          for (size_t k = 0; k < n; ++k)
            for (const SceneVertex& v : assemble_triangle(*p, k)) {
              pos.push_back(grid_coord(v.x, cmd.loc) * scale);
              pos.push_back(grid_coord(v.y, cmd.loc) * scale);
              rgb.insert(rgb.end(), {v.r, v.g, v.b});
            }
        } else if (const auto* c = std::get_if<CmdClear>(&cmd.body)) {
          flush();
          glClearColor(c->r / 255.0f, c->g / 255.0f, c->b / 255.0f, 1.0f);
          glClear(GL_COLOR_BUFFER_BIT);
        } else if (const auto* vp = std::get_if<CmdViewport>(&cmd.body)) {
          if (vp->width != o.width || vp->height != o.height)
            throw SceneError(cmd.loc.str() + ": viewport " + std::to_string(vp->width) + "x" +
                             std::to_string(vp->height) + " differs from --width x --height");
        } else if (!std::holds_alternative<CmdClearDepth>(cmd.body)) {
          throw SceneError(cmd.loc.str() + ": rastsim_llvmpipe_render draws only triangles, clear and viewport");
        }
      }
      flush();
    });
    glFinish();
    if (glGetError() != GL_NO_ERROR) throw std::runtime_error("OpenGL error while drawing");
    // Gallium stores this window-system buffer top row first (osmesa_renderer.cpp);
    // glReadPixels returns GL rows bottom first: row r of the image is GL row H-1-r.
    std::vector<uint32_t> gl_rows(buffer.size());
    glReadPixels(0, 0, o.width, o.height, GL_RGBA, GL_UNSIGNED_BYTE, gl_rows.data());
    Framebuffer fb(o.width, o.height);
    for (int r = 0; r < o.height; ++r)
      fb.write_row(r, reinterpret_cast<const uint8_t*>(gl_rows.data() + size_t(o.height - 1 - r) * size_t(o.width)));
    write_image(fb, o.out);
    OSMesaDestroyContext(ctx);
  } catch (const std::exception& e) {
    std::cerr << "rastsim_llvmpipe_render: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
