// SPDX-License-Identifier: Apache-2.0
// rastsim import-apitrace's converter (docs/workloads.md, "Importing an apitrace
// capture"): the text of `apitrace dump --multiline=no --blobs` of an OpenGL capture in,
// a rastsim trace (docs/trace-format.md) out, with clip-space `tri4` / `v4` vertices the
// program's vertex shader would have made (apitrace_shader.h: gl_Position = M * vec4(p, 1)).
//
// GL -> rastsim conventions: GL clip space has -w <= z <= w and NDC y = -1 at the bottom;
// rastsim's has 0 <= z <= w and NDC y = -1 at the top (docs/clip-space.md), so a vertex's
// (x, y, z, w) is written as (x, -y, (z + w) / 2, w), each computed in double from the
// binary32 matrices and attributes (the matrix product M1 * ... * Mk first, then the
// row-vector dot products) and rounded once to binary32. glViewport(x, y, w, h) and
// glScissor are flipped to y down against the framebuffer's height.
//
// State that rastsim keeps in its config, not in the trace (depth test and function,
// depth writes, culling, front face) is fixed by the first imported draw and returned as
// config assignments (`config_sets`); a later draw that needs other settings is refused.
//
// Textures (apitrace_texture.h, apitrace_shader.h's FragmentForm): a draw whose fragment
// shader samples a texture is drawn with the texture bound to its sampler's unit, its
// texture coordinate the vertex shader's pass-through of an attribute (binary32 s, t
// written unchanged: the image's rows stay in GL's order, t = 0 the file's first row),
// texenv replace for a plain lookup, modulate for a lookup times a varying colour (the
// attribute it passes through, else the flat colour, stated), `other_texenv` otherwise
// (stated). Each texture image a draw uses is returned in `textures`, one file a GL
// texture and version, for the caller to write beside the trace.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace rastsim::apitrace {

struct ImportOptions {
  // Framebuffer size; 0: the first glViewport's (apitrace records the window's size as a
  // "fake" glViewport at each glXMakeCurrent).
  int width = 0, height = 0;
  // The flat colour of a draw whose program has no vertex colour attribute.
  int flat_r = 255, flat_g = 255, flat_b = 255;
  // Reads a blob file `--blobs` wrote (name as printed); throws on failure.
  std::function<std::string(const std::string&)> read_blob;
  // Texture files are named STEM.texN.png (GL texture N; its k-th image STEM.texN-k.png),
  // relative to the trace's directory.
  std::string texture_stem = "trace";
  // The texenv of a textured draw whose fragment shader is neither a plain lookup nor a
  // lookup times a varying: replace, modulate or decal.
  std::string other_texenv = "modulate";
};

// A texture image to write beside the trace: `file` relative to its directory, RGBA8
// rows in GL's order (row 0 = t = 0).
struct TextureFile {
  std::string file;
  int width = 0, height = 0;
  std::vector<uint8_t> rgba;
};

struct ImportResult {
  std::string trace;                     // the rastsim trace text
  std::vector<std::string> config_sets;  // "raster.depth_func=lequal", ...
  int frames = 0;                        // glXSwapBuffers / eglSwapBuffers seen
  int draws = 0, draws_imported = 0, draws_refused = 0, clears_refused = 0;
  uint64_t triangles = 0;                // triangles written (strips and fans counted)
  std::vector<std::string> refusals;     // one message a refused draw or clear
  int draws_textured = 0;                // imported draws drawn with a texture
  std::vector<TextureFile> textures;     // the images the textured draws use
  // How the textured draws' colours relate to the program's: "texenv replace: ... plain
  // texture lookup" and every approximation stated, each with its count of draws.
  std::map<std::string, int> texture_notes;
};

// Throws SceneError("name:line: what") on a dump line that cannot be read or a call
// whose arguments are malformed (a missing argument, a blob that does not exist).
ImportResult import_apitrace_dump(const std::string& dump, const std::string& name, const ImportOptions& opt);

// Writes the trace text to `path`, zstd-compressed (level 3, with a checksum) when the
// name ends in .zst; throws SceneError when it cannot.
void write_trace_file(const std::string& path, const std::string& text);

}  // namespace rastsim::apitrace
