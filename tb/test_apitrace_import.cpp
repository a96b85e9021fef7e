// SPDX-License-Identifier: Apache-2.0
// rastsim import-apitrace's converter (scene/apitrace_import.h) on hand-written excerpts of
// `apitrace dump --multiline=no --blobs` text; every expected number is worked by hand
// in the comment beside it.
#include <gtest/gtest.h>

#include <cstring>
#include <map>
#include <variant>

#include "ref/scene.h"
#include "scene/apitrace_import.h"
#include "scene/apitrace_shader.h"
#include "scene/scene_io.h"

namespace rastsim {
namespace {

using apitrace::ImportResult;

const char* kVs =
    "attribute vec3 position;\\nattribute vec3 normal;\\nuniform mat4 A;\\nuniform mat4 B;\\n"
    "void main(void)\\n{\\n    // a comment: gl_Position = nothing;\\n    gl_Position = A * B * vec4(position, 1.0);\\n}\\n";

std::string floats(std::initializer_list<float> v) {
  std::string s(v.size() * 4, '\0');
  size_t k = 0;
  for (float f : v) std::memcpy(&s[4 * k++], &f, 4);
  return s;
}

// A program (vertex shader kVs unless given), buffer 1 holding `verts`, A and B set.
std::string preamble(const std::string& vs = kVs, const std::string& b = "{2, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}") {
  return "// process.name = \"/usr/bin/test\"\n"
         "1 glViewport(x = 0, y = 0, width = 200, height = 100) // fake\n"
         "2 glCreateProgram() = 1\n"
         "3 glCreateShader(type = GL_VERTEX_SHADER) = 2\n"
         "4 glShaderSource(shader = 2, count = 1, string = &\"" + vs + "\", length = NULL)\n"
         "5 glAttachShader(program = 1, shader = 2)\n"
         "6 glBindAttribLocation(program = 1, index = 0, name = \"position\")\n"
         "7 glLinkProgram(program = 1)\n"
         "8 glUseProgram(program = 1)\n"
         "9 glGetUniformLocation(program = 1, name = \"A\") = 3\n"
         "10 glGetUniformLocation(program = 1, name = \"B\") = 4\n"
         // A: translate x by 1 (column 3 = 1 0 0 1); B: scale x by 2 (column-major).
         "11 glUniformMatrix4fv(location = 3, count = 1, transpose = GL_FALSE, value = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1, 0, 0, 1})\n"
         "12 glUniformMatrix4fv(location = 4, count = 1, transpose = GL_FALSE, value = " + b + ")\n"
         "13 glGenBuffers(n = 1, buffers = &1)\n"
         "14 glBindBuffer(target = GL_ARRAY_BUFFER, buffer = 1)\n"
         "15 glBufferData(target = GL_ARRAY_BUFFER, size = 48, data = blob(\"blob_call15.bin\"), usage = GL_STATIC_DRAW)\n"
         "16 glEnableVertexAttribArray(index = 0)\n"
         "17 glVertexAttribPointer(index = 0, size = 3, type = GL_FLOAT, normalized = GL_FALSE, stride = 0, pointer = NULL)\n";
}

ImportResult run(const std::string& dump) {
  apitrace::ImportOptions o;
  // Four vertices: (1, 0, 0.5), (0, 0.5, -1), (0, 0, 0), (0.25, -1, 1).
  o.read_blob = [](const std::string& n) -> std::string {
    if (n != "blob_call15.bin") throw std::runtime_error("no such blob");
    return floats({1, 0, 0.5f, 0, 0.5f, -1, 0, 0, 0, 0.25f, -1, 1});
  };
  return apitrace::import_apitrace_dump(dump, "t.dump", o);
}

std::string error_of(const std::string& dump) {
  try {
    run(dump);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

TEST(ApitraceImport, MatricesMultiplyInShaderOrderAndConventionsFlip) {
  const ImportResult r = run(preamble() + "18 glDrawArrays(mode = GL_TRIANGLES, first = 0, count = 3)\n"
                                          "19 glXSwapBuffers(dpy = 0x1, drawable = 2)\n");
  EXPECT_EQ(r.draws_imported, 1);
  EXPECT_EQ(r.draws_refused, 0);
  EXPECT_EQ(r.frames, 1);
  // A * B * (1, 0, 0.5, 1): B doubles x -> (2, 0, 0.5, 1), A adds 1 -> (3, 0, 0.5, 1)
  // (B * A would give 4). Written (x, -y, (z + w) / 2, w) = (3, -0, 0.75, 1).
  // (0, 0.5, -1, 1) -> (1, 0.5, -1, 1) -> (1, -0.5, 0, 1). (0, 0, 0) -> (1, -0, 0.5, 1).
  EXPECT_NE(r.trace.find("\nviewport 200 100\nviewport_xform 0 0 200 100\n"), std::string::npos) << r.trace;
  EXPECT_NE(r.trace.find("tri4 3 -0 0.75 1 255 255 255 1 -0.5 0 1 255 255 255 1 -0 0.5 1 255 255 255\nframe\n"),
            std::string::npos)
      << r.trace;
  // The output is a trace rastsim reads: one clip-space List command.
  const Scene s = parse_trace(r.trace, "out.trace");
  ASSERT_EQ(s.commands.size(), 2u);  // viewport, tri4
  const auto* p = std::get_if<CmdPrimitives>(&s.commands[1].body);
  ASSERT_NE(p, nullptr);
  ASSERT_EQ(p->clip_vertices.size(), 3u);
  EXPECT_EQ(p->clip_vertices[0].x, 3.0f);
  EXPECT_EQ(p->clip_vertices[1].y, -0.5f);
  EXPECT_EQ(p->clip_vertices[2].z, 0.5f);
}

TEST(ApitraceImport, TransposedMatrixAndStripFromIndices) {
  // B transposed: row-major {1 0 0 0.5 ...}: x += 0.5 (column 3 = 0.5 0 0 1 after transpose).
  const std::string b_t = "{1, 0, 0, 0.5, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}";
  std::string d = preamble(kVs, b_t);
  const std::string was = "transpose = GL_FALSE, value = " + b_t;
  d.replace(d.find(was), was.size(), "transpose = GL_TRUE, value = " + b_t);
  d += "18 glBindBuffer(target = GL_ELEMENT_ARRAY_BUFFER, buffer = 1)\n"
       "19 glDrawElements(mode = GL_TRIANGLE_STRIP, count = 3, type = GL_UNSIGNED_BYTE, indices = 0x2)\n"
       "20 glDrawArrays(mode = GL_TRIANGLES, first = 0, count = 3)\n";
  // The element buffer is buffer 1 as well: bytes 2, 3, 4 of the float 1.0f (00 00 80 3f)
  // and of 0: indices 0x80, 0x3f, 0x00 -> vertex 128 lies outside the 4-vertex buffer.
  const ImportResult r = run(d);
  EXPECT_EQ(r.draws_refused, 1);
  ASSERT_EQ(r.refusals.size(), 1u);
  EXPECT_NE(r.refusals[0].find("t.dump:20: call 19 glDrawElements refused: position vertex 128 lies outside buffer 1"),
            std::string::npos)
      << r.refusals[0];
  // Transposed, B translates x by 0.5: A * B * (1, 0, 0.5, 1) = (2.5, 0, 0.5, 1). Read
  // untransposed it would put 0.5 in w's row: (2, 0, 0.5, 1.5).
  EXPECT_NE(r.trace.find("tri4 2.5 -0 0.75 1 255 255 255 "), std::string::npos) << r.trace;
}

TEST(ApitraceImport, StripBlockAndYFlippedViewport) {
  std::string d = preamble();
  d += "18 glViewport(x = 10, y = 20, width = 100, height = 50)\n"
       "19 glDrawArrays(mode = GL_TRIANGLE_STRIP, first = 1, count = 3)\n";
  const ImportResult r = run(d);
  EXPECT_EQ(r.triangles, 1u);
  // GL's y = 20 from the bottom of a 100-high framebuffer, 50 high: top row 100 - 20 - 50 = 30.
  EXPECT_NE(r.trace.find("viewport_xform 10 30 100 50\n"), std::string::npos) << r.trace;
  // Vertices 1, 2, 3: (1, -0.5, 0, 1), (1, -0, 0.5, 1), and (0.25, -1, 1) -> (1.5, 1, 1, 1).
  EXPECT_NE(r.trace.find("strip\nv4 1 -0.5 0 1 255 255 255\nv4 1 -0 0.5 1 255 255 255\nv4 1.5 1 1 1 255 255 255\nend\n"),
            std::string::npos)
      << r.trace;
  EXPECT_NO_THROW(parse_trace(r.trace, "out.trace"));
}

TEST(ApitraceImport, ShaderOfAnotherFormIsRefusedNamingCallAndShader) {
  const std::string vs = "attribute vec3 position;\\nvoid main() { gl_Position = vec4(position, 1.0); }";
  const ImportResult r = run(preamble(vs) + "18 glDrawArrays(mode = GL_TRIANGLES, first = 0, count = 3)\n"
                                            "19 glXSwapBuffers(dpy = 0x1, drawable = 2)\n");
  EXPECT_EQ(r.draws_imported, 0);
  EXPECT_EQ(r.draws_refused, 1);
  ASSERT_EQ(r.refusals.size(), 1u);
  EXPECT_NE(r.refusals[0].find("t.dump:19: call 18 glDrawArrays refused: program 1's vertex shader 2 is not"),
            std::string::npos)
      << r.refusals[0];
  // The frame stays a valid frame (a placeholder command, not a bare 'frame').
  EXPECT_NE(r.trace.find("# frame 0: no command imported\nviewport 200 100\nframe\n"), std::string::npos) << r.trace;
}

TEST(ApitraceImport, DepthAndCullStateBecomeConfigAndAChangeIsRefused) {
  std::string d = preamble();
  d += "18 glEnable(cap = GL_DEPTH_TEST)\n19 glDepthFunc(func = GL_LEQUAL)\n20 glEnable(cap = GL_CULL_FACE)\n"
       "21 glClearColor(red = 0, green = 0.5, blue = 1, alpha = 1)\n22 glClearDepth(depth = 1)\n"
       "23 glClear(mask = GL_DEPTH_BUFFER_BIT | GL_COLOR_BUFFER_BIT)\n"
       "24 glDrawArrays(mode = GL_TRIANGLES, first = 0, count = 3)\n25 glXSwapBuffers(dpy = 0x1, drawable = 2)\n"
       "26 glDepthFunc(func = GL_LESS)\n27 glDrawArrays(mode = GL_TRIANGLES, first = 0, count = 3)\n";
  const ImportResult r = run(d);
  const std::vector<std::string> want{"raster.depth_func=lequal", "raster.depth_write=true", "raster.cull=back",
                                      "raster.front_face=ccw"};
  EXPECT_EQ(r.config_sets, want);
  EXPECT_EQ(r.draws_imported, 1);
  EXPECT_EQ(r.draws_refused, 1);
  EXPECT_NE(r.trace.find("clear 0 128 255\ncleardepth 1\n"), std::string::npos) << r.trace;  // 0.5 * 255 = 127.5 -> 128
  ASSERT_EQ(r.refusals.size(), 1u);
  EXPECT_NE(r.refusals[0].find("call 27 glDrawArrays refused: it needs raster.depth_func=less where"), std::string::npos);
}

TEST(ApitraceImport, MalformedLinesAreFileLineErrors) {
  EXPECT_EQ(error_of("1 glViewport(x = 0, y = 0, width = 200, height = 100\n"),
            "t.dump:1: expected ')' (column 53)");
  EXPECT_EQ(error_of("\n\n3 glViewport(x = 0, y = zero, width = 200, height = 100)\n"),
            "t.dump:3: call 3 glViewport: argument 'y' is not an integer: 'zero'");
  EXPECT_EQ(error_of("1 glClear()\n"), "t.dump:1: call 1 glClear: no argument 'mask'");
  EXPECT_EQ(error_of("1 glShaderSource(shader = 2, count = 1, string = &\"abc, length = NULL)\n"),
            "t.dump:1: unterminated string (column 71)");
  const std::string blob_bad = preamble();
  EXPECT_NE(error_of(std::string(blob_bad).replace(blob_bad.find("blob_call15"), 11, "blob_call99")).find(
                "t.dump:16: call 15 glBufferData: cannot read blob 'blob_call99.bin': no such blob"),
            std::string::npos);
  EXPECT_EQ(error_of("1 glXSwapBuffers(dpy = 0x1, drawable = 2)\n"),
            "t.dump: no glViewport in the capture (give the framebuffer size)");
}

// A textured program: vertex shader `vs` (position through A, texcoord passed through
// unless vs says otherwise), fragment shader `fs`; buffer 1 the four positions of run(),
// buffer 2 their texture coordinates; texture 5 a 3x2 RGB image in rows of 9 bytes padded
// to 12 (GL_UNPACK_ALIGNMENT 4), nearest, wraps clamp / repeat.
const char* kTexVs =
    "attribute vec3 position;\\nattribute vec2 texcoord;\\nuniform mat4 A;\\nvarying vec2 v_texcoord;\\n"
    "void main() {\\n  v_texcoord = texcoord;\\n  gl_Position = A * vec4(position, 1.0);\\n}\\n";
const char* kTexFs = "uniform sampler2D tex;\\nvarying vec2 v_texcoord;\\nvoid main() {\\n"
                     "  gl_FragColor = texture2D(tex, v_texcoord);\\n}\\n";

std::string textured(const std::string& vs = kTexVs, const std::string& fs = kTexFs) {
  return "1 glViewport(x = 0, y = 0, width = 200, height = 100) // fake\n"
         "2 glGenTextures(n = 1, textures = &5)\n"
         "3 glActiveTexture(texture = GL_TEXTURE1)\n"
         "4 glBindTexture(target = GL_TEXTURE_2D, texture = 5)\n"
         "5 glTexParameteri(target = GL_TEXTURE_2D, pname = GL_TEXTURE_MIN_FILTER, param = GL_NEAREST)\n"
         "6 glTexParameteri(target = GL_TEXTURE_2D, pname = GL_TEXTURE_MAG_FILTER, param = GL_NEAREST)\n"
         "7 glTexParameteri(target = GL_TEXTURE_2D, pname = GL_TEXTURE_WRAP_S, param = GL_CLAMP_TO_EDGE)\n"
         "8 glTexImage2D(target = GL_TEXTURE_2D, level = 0, internalformat = GL_RGB, width = 3, height = 2, "
         "border = 0, format = GL_RGB, type = GL_UNSIGNED_BYTE, pixels = blob(\"blob_call8.bin\"))\n"
         "9 glCreateProgram() = 1\n"
         "10 glCreateShader(type = GL_VERTEX_SHADER) = 2\n"
         "11 glShaderSource(shader = 2, count = 1, string = &\"" + vs + "\", length = NULL)\n"
         "12 glAttachShader(program = 1, shader = 2)\n"
         "13 glCreateShader(type = GL_FRAGMENT_SHADER) = 3\n"
         "14 glShaderSource(shader = 3, count = 1, string = &\"" + fs + "\", length = NULL)\n"
         "15 glAttachShader(program = 1, shader = 3)\n"
         "16 glBindAttribLocation(program = 1, index = 0, name = \"position\")\n"
         "17 glBindAttribLocation(program = 1, index = 1, name = \"texcoord\")\n"
         "18 glLinkProgram(program = 1)\n"
         "19 glUseProgram(program = 1)\n"
         "20 glGetUniformLocation(program = 1, name = \"A\") = 3\n"
         "21 glUniformMatrix4fv(location = 3, count = 1, transpose = GL_FALSE, value = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1})\n"
         "22 glGetUniformLocation(program = 1, name = \"tex\") = 4\n"
         "23 glUniform1i(location = 4, v0 = 1)\n"
         "24 glBindBuffer(target = GL_ARRAY_BUFFER, buffer = 1)\n"
         "25 glBufferData(target = GL_ARRAY_BUFFER, size = 48, data = blob(\"blob_call15.bin\"), usage = GL_STATIC_DRAW)\n"
         "26 glEnableVertexAttribArray(index = 0)\n"
         "27 glVertexAttribPointer(index = 0, size = 3, type = GL_FLOAT, normalized = GL_FALSE, stride = 0, pointer = NULL)\n"
         "28 glBindBuffer(target = GL_ARRAY_BUFFER, buffer = 2)\n"
         "29 glBufferData(target = GL_ARRAY_BUFFER, size = 32, data = blob(\"blob_call29.bin\"), usage = GL_STATIC_DRAW)\n"
         "30 glEnableVertexAttribArray(index = 1)\n"
         "31 glVertexAttribPointer(index = 1, size = 2, type = GL_FLOAT, normalized = GL_FALSE, stride = 0, pointer = NULL)\n";
}

// The 3x2 RGB image: texel (x, y) = (10 x + 1, 10 x + 2, 100 + y) in rows of 12 bytes
// (9 and 3 bytes of padding 0xEE). The last row needs only its 9 bytes.
std::string rgb_blob() {
  std::string b;
  for (int y = 0; y < 2; ++y) {
    for (int x = 0; x < 3; ++x) b += {char(10 * x + 1), char(10 * x + 2), char(100 + y)};
    if (y == 0) b += std::string(3, '\xEE');
  }
  return b;
}

ImportResult run_textured(const std::string& dump, const std::string& rgb = rgb_blob()) {
  apitrace::ImportOptions o;
  o.texture_stem = "out";
  o.read_blob = [rgb](const std::string& n) -> std::string {
    if (n == "blob_call15.bin") return floats({1, 0, 0.5f, 0, 0.5f, -1, 0, 0, 0, 0.25f, -1, 1});
    if (n == "blob_call29.bin") return floats({0.25f, 0.75f, 1, 0.1f, -0.5f, 2, 0, 0});
    if (n == "blob_call8.bin") return rgb;
    throw std::runtime_error("no such blob");
  };
  return apitrace::import_apitrace_dump(dump, "t.dump", o);
}

TEST(ApitraceImport, TexImage2DBlobToRgbaInGlRowOrderWithAlignment) {
  const ImportResult r = run_textured(textured() + "40 glDrawArrays(mode = GL_TRIANGLES, first = 0, count = 3)\n");
  EXPECT_EQ(r.draws_imported, 1) << (r.refusals.empty() ? "" : r.refusals[0]);
  EXPECT_EQ(r.draws_textured, 1);
  ASSERT_EQ(r.textures.size(), 1u);
  const apitrace::TextureFile& t = r.textures[0];
  EXPECT_EQ(t.file, "out.tex5.png");
  ASSERT_EQ(t.width, 3);
  ASSERT_EQ(t.height, 2);
  ASSERT_EQ(t.rgba.size(), 24u);
  // Row 0 is GL's first row (t = 0), unflipped; RGB gets alpha 255; row 1 starts after
  // the 3 padding bytes: texel (2, 1) = (21, 22, 101, 255), texel (0, 0) = (1, 2, 100, 255).
  EXPECT_EQ(std::vector<uint8_t>(t.rgba.begin(), t.rgba.begin() + 4), (std::vector<uint8_t>{1, 2, 100, 255}));
  EXPECT_EQ(std::vector<uint8_t>(t.rgba.begin() + 20, t.rgba.end()), (std::vector<uint8_t>{21, 22, 101, 255}));
  // The sampler is set to unit 1, where texture 5 is bound; its state, then the
  // triangle's (s, t) as the buffer holds them (binary32, 9 digits), t unchanged.
  EXPECT_NE(r.trace.find("texture 5 out.tex5.png\nbindtexture 5\ntexfilter nearest\ntexwrap clamp repeat\nmipmap off\n"
                         "texenv replace\n# call 40 glDrawArrays GL_TRIANGLES, 3 vertices, flat colour 255 255 255 "
                         "(no colour attribute); texture 5 (image of call 8, 3x2), nearest, texenv replace: the "
                         "fragment shader is a plain texture lookup\n"
                         "tri4 1 -0 0.75 1 255 255 255 0.25 0.75 0 -0.5 0 1 255 255 255 1 0.100000001 "
                         "0 -0 0.5 1 255 255 255 -0.5 2\n"),
            std::string::npos)
      << r.trace;
  // One row short of the padding GL_UNPACK_ALIGNMENT 4 asks (the blob 20 bytes, 21 needed):
  // the texture cannot be read, and a draw that samples it is refused naming the call.
  const ImportResult s = run_textured(textured() + "40 glDrawArrays(mode = GL_TRIANGLES, first = 0, count = 3)\n",
                                      rgb_blob().substr(0, 20));
  ASSERT_EQ(s.refusals.size(), 1u);
  EXPECT_EQ(s.refusals[0], "t.dump:32: call 40 glDrawArrays refused: texture 5: call 8 glTexImage2D: the pixels have 20 "
                           "bytes, 3x2 GL_RGB with rows of 12 bytes needs 21");
  // With GL_UNPACK_ALIGNMENT 1 the rows are 9 bytes: texel (0, 1) starts at byte 9 = the padding 0xEE.
  std::string d = textured();
  d.insert(d.find("8 glTexImage2D"), "7 glPixelStorei(pname = GL_UNPACK_ALIGNMENT, param = 1)\n");
  const ImportResult u = run_textured(d + "40 glDrawArrays(mode = GL_TRIANGLES, first = 0, count = 3)\n");
  ASSERT_EQ(u.textures.size(), 1u);
  EXPECT_EQ(u.textures[0].rgba[12], 0xEE);
}

TEST(ApitraceImport, TextureRespecifiedGetsANewFileAndModulateTakesTheColourAttribute) {
  const std::string vs =
      "attribute vec3 position;\\nattribute vec2 texcoord;\\nattribute vec4 vtxcolor;\\nuniform mat4 A;\\n"
      "varying vec2 tc;\\nvarying vec4 Color;\\nvoid main() {\\n  Color = vtxcolor;\\n  tc = texcoord.st;\\n"
      "  gl_Position = A * vec4(position, 1.0);\\n}\\n";
  const std::string fs = "uniform sampler2D s;\\nvarying vec2 tc;\\nvarying vec4 Color;\\nvoid main() {\\n"
                         "  vec4 texel = texture2D(s, tc);\\n  gl_FragColor = Color * texel;\\n}\\n";
  std::string d = textured(vs, fs);
  d.replace(d.find("name = \"tex\") = 4"), 17, "name = \"s\") = 4");
  d += "32 glBindAttribLocation(program = 1, index = 2, name = \"vtxcolor\")\n33 glLinkProgram(program = 1)\n"
       "34 glEnableVertexAttribArray(index = 2)\n"
       "35 glVertexAttribPointer(index = 2, size = 4, type = GL_UNSIGNED_BYTE, normalized = GL_TRUE, stride = 0, pointer = NULL)\n"
       "36 glDrawArrays(mode = GL_TRIANGLES, first = 0, count = 3)\n"
       "37 glTexSubImage2D(target = GL_TEXTURE_2D, level = 0, xoffset = 1, yoffset = 1, width = 1, height = 1, "
       "format = GL_LUMINANCE, type = GL_UNSIGNED_BYTE, pixels = blob(\"blob_call29.bin\"))\n"
       "38 glDrawArrays(mode = GL_TRIANGLES, first = 0, count = 3)\n";
  const ImportResult r = run_textured(d);
  ASSERT_EQ(r.draws_imported, 2) << (r.refusals.empty() ? "" : r.refusals[0]);
  ASSERT_EQ(r.textures.size(), 2u);
  EXPECT_EQ(r.textures[1].file, "out.tex5-2.png");
  // The sub-image's one LUMINANCE byte: the float 0.25f's first byte (00 00 80 3e) = 0 -> (0, 0, 0, 255) at (1, 1).
  EXPECT_EQ(std::vector<uint8_t>(r.textures[1].rgba.begin() + 16, r.textures[1].rgba.begin() + 20),
            (std::vector<uint8_t>{0, 0, 0, 255}));
  EXPECT_NE(r.trace.find("\ntexture 5 out.tex5-2.png\nbindtexture 5\n# call 38"), std::string::npos) << r.trace;
  // Modulate with vtxcolor, buffer 2's bytes as unsigned normalised: vertex 0's are the
  // float 0.25f's bytes 00 00 80 3e -> 0 0 128 (the fourth, alpha, is not written).
  EXPECT_NE(r.trace.find("texenv modulate\n# call 36 glDrawArrays GL_TRIANGLES, 3 vertices, vertex colour; texture 5 "
                         "(image of call 8, 3x2), nearest, texenv modulate: the fragment shader is a texture lookup "
                         "times the varying 'Color', the attribute 'vtxcolor' passed through\n"
                         "tri4 1 -0 0.75 1 0 0 128 0.25 0.75 "),
            std::string::npos)
      << r.trace;
}

TEST(ApitraceImport, TextureFormsThatCannotBeProvenAreRefusedByCallNumber) {
  auto refusal = [](const std::string& vs, const std::string& fs, const std::string& extra = "") {
    const ImportResult r = run_textured(textured(vs, fs) + extra + "40 glDrawArrays(mode = GL_TRIANGLES, first = 0, count = 3)\n");
    return r.refusals.empty() ? std::string("imported") : r.refusals[0];
  };
  const std::string head = "t.dump:32: call 40 glDrawArrays refused: ";
  // glmark2's texgen: the coordinate is computed in the vertex shader.
  const std::string texgen =
      "attribute vec3 position;\\nuniform mat4 A;\\nvarying vec2 v_texcoord;\\nvoid main() {\\n"
      "  v_texcoord = asin(normalize(position).xy) / 3.14159 + 0.5;\\n  gl_Position = A * vec4(position, 1.0);\\n}\\n";
  EXPECT_EQ(refusal(texgen, kTexFs), head + "vertex shader 2's texture coordinate 'v_texcoord': "
                                             "'v_texcoord = asin(normalize(position).xy) / 3.14159 + 0.5' is not a pass-through "
                                             "of an attribute at the top level of main()");
  // Through a texture matrix uniform: not proven, refused.
  const std::string matrix =
      "attribute vec3 position;\\nattribute vec2 texcoord;\\nuniform mat4 A;\\nuniform mat4 T;\\n"
      "varying vec2 v_texcoord;\\nvoid main() {\\n  v_texcoord = (T * vec4(texcoord, 0.0, 1.0)).xy;\\n"
      "  gl_Position = A * vec4(position, 1.0);\\n}\\n";
  EXPECT_NE(refusal(matrix, kTexFs).find(head + "vertex shader 2's texture coordinate 'v_texcoord': "
                                               "'v_texcoord = (T * vec4(texcoord, 0.0, 1.0)).xy' is not a pass-through"),
            std::string::npos);
  // A swizzle that reorders.
  std::string yx = kTexVs;
  yx.replace(yx.find("= texcoord;"), 11, "= texcoord.yx;");
  EXPECT_EQ(refusal(yx, kTexFs), head + "vertex shader 2's texture coordinate 'v_texcoord': 'v_texcoord = texcoord.yx': "
                                        "the swizzle .yx is not the attribute's first components in order");
  // Two samplers in a shader of another form: which one is not known.
  const std::string two = "uniform sampler2D a;\\nuniform sampler2D b;\\nvarying vec2 v_texcoord;\\nvoid main() {\\n"
                          "  gl_FragColor = texture2D(a, v_texcoord) + texture2D(b, v_texcoord);\\n}\\n";
  EXPECT_NE(refusal(kTexVs, two).find(head + "fragment shader 3 samples a texture in another form"), std::string::npos);
  // Mipmapped min filter without mip levels: GL's texture is incomplete.
  EXPECT_EQ(refusal(kTexVs, kTexFs,
                    "32 glTexParameteri(target = GL_TEXTURE_2D, pname = GL_TEXTURE_MIN_FILTER, param = GL_LINEAR_MIPMAP_LINEAR)\n"),
            "t.dump:33: call 40 glDrawArrays refused: texture 5: min filter GL_LINEAR_MIPMAP_LINEAR with mag filter "
            "GL_NEAREST has no rastsim texfilter (one filter for both)");
  // A texture rendered into (a framebuffer attachment): its image is not the blob's any more.
  EXPECT_EQ(refusal(kTexVs, kTexFs,
                    "32 glFramebufferTexture2D(target = GL_FRAMEBUFFER, attachment = GL_COLOR_ATTACHMENT0, "
                    "textarget = GL_TEXTURE_2D, texture = 5, level = 0)\n"),
            "t.dump:33: call 40 glDrawArrays refused: texture 5: call 32 glFramebufferTexture2D: rendered to, its "
            "image is not imported");
  // The sampler's unit (1) has no texture once unit 1 is unbound.
  EXPECT_EQ(refusal(kTexVs, kTexFs, "32 glBindTexture(target = GL_TEXTURE_2D, texture = 0)\n"),
            "t.dump:33: call 40 glDrawArrays refused: sampler 'tex' (unit 1) has no texture image bound");
  // Another form that still names one sampler and one varying: imported, its texenv stated.
  const std::string other = "uniform sampler2D tex;\\nvarying vec2 v_texcoord;\\nvoid main() {\\n"
                            "  gl_FragColor = texture2D(tex, v_texcoord + vec2(0.5, 0.0));\\n}\\n";
  const ImportResult r = run_textured(textured(kTexVs, other) + "40 glDrawArrays(mode = GL_TRIANGLES, first = 0, count = 3)\n");
  EXPECT_EQ(r.draws_textured, 1);
  ASSERT_EQ(r.texture_notes.size(), 1u);
  EXPECT_EQ(r.texture_notes.begin()->first,
            "texenv modulate stated for a fragment shader of another form (gl_FragColor = texture2D(tex,v_texcoord+"
            "vec2(0.5,0.0)) is neither a texture lookup nor one times a varying)");
}

TEST(ApitraceImport, GeneratedMipmapsMakeTrilinearAndANewImageDropsThem) {
  const std::string mips =
      "32 glTexParameteri(target = GL_TEXTURE_2D, pname = GL_TEXTURE_MIN_FILTER, param = GL_LINEAR_MIPMAP_LINEAR)\n"
      "33 glTexParameterf(target = GL_TEXTURE_2D, pname = GL_TEXTURE_MAG_FILTER, param = 9729)\n"  // GL_LINEAR as a float
      "34 glGenerateMipmapEXT(target = GL_TEXTURE_2D)\n"
      "35 glTexParameteri(target = GL_TEXTURE_2D, pname = GL_TEXTURE_WRAP_T, param = GL_MIRRORED_REPEAT)\n"
      "40 glDrawArrays(mode = GL_TRIANGLES, first = 0, count = 3)\n";
  const ImportResult r = run_textured(textured() + mips);
  ASSERT_EQ(r.draws_textured, 1) << (r.refusals.empty() ? "" : r.refusals[0]);
  EXPECT_NE(r.trace.find("bindtexture 5\ntexfilter trilinear\ntexwrap clamp mirror\nmipmap on\ntexenv replace\n"
                         "texlod_bias 0\n"),
            std::string::npos)
      << r.trace;
  // A new level-0 image after glGenerateMipmap has no chain in GL until generated again.
  const ImportResult s = run_textured(textured() + mips +
                                      "41 glTexImage2D(target = GL_TEXTURE_2D, level = 0, internalformat = GL_RGB, width = 3, "
                                      "height = 2, border = 0, format = GL_RGB, type = GL_UNSIGNED_BYTE, pixels = "
                                      "blob(\"blob_call8.bin\"))\n42 glDrawArrays(mode = GL_TRIANGLES, first = 0, count = 3)\n");
  ASSERT_EQ(s.refusals.size(), 1u);
  EXPECT_EQ(s.refusals[0], "t.dump:38: call 42 glDrawArrays refused: texture 5: min filter GL_LINEAR_MIPMAP_LINEAR "
                           "without mip levels (GL's texture is incomplete)");
}

TEST(ApitraceShader, FragmentForms) {
  using apitrace::FragmentForm;
  using apitrace::recognise_fragment_shader;
  // glmark2's light-basic-tex.frag: a lookup into a local, times the varying Color.
  const auto tex = recognise_fragment_shader(
      "#ifdef GL_ES\nprecision mediump float;\n#endif\nuniform sampler2D MaterialTexture0;\nvarying vec4 Color;\n"
      "varying vec2 TextureCoord;\nvoid main(void)\n{\n    vec4 texel = texture2D(MaterialTexture0, TextureCoord);\n"
      "    gl_FragColor = texel * Color;\n}\n");
  EXPECT_EQ(tex.kind, FragmentForm::Kind::Modulate) << tex.reason;
  EXPECT_EQ(tex.sampler, "MaterialTexture0");
  EXPECT_EQ(tex.coord, "TextureCoord");
  EXPECT_EQ(tex.colour, "Color");
  const auto plain = recognise_fragment_shader(
      "uniform sampler2D t;\nvarying vec2 uv;\nvoid main() { gl_FragColor = texture2D(t, uv); }");
  EXPECT_EQ(plain.kind, FragmentForm::Kind::Replace) << plain.reason;
  const auto none = recognise_fragment_shader("varying vec4 Color;\nvoid main() { gl_FragColor = Color; }");
  EXPECT_EQ(none.kind, FragmentForm::Kind::Untextured);
  // Multiplied by a uniform, not a varying: another form (one sampler, one vec2 still named).
  const auto uni = recognise_fragment_shader(
      "uniform sampler2D t;\nuniform vec4 k;\nvarying vec2 uv;\nvoid main() { gl_FragColor = texture2D(t, uv) * k; }");
  EXPECT_EQ(uni.kind, FragmentForm::Kind::Other);
  EXPECT_EQ(uni.reason, "'k' multiplied with the texture is not a varying vec4");
  EXPECT_EQ(uni.sampler, "t");
  EXPECT_EQ(uni.coord, "uv");
}

TEST(ApitraceShader, Glmark2FormsAndOthers) {
  using apitrace::recognise_vertex_shader;
  // glmark2's light-basic.vert with its #define prefix.
  const auto basic = recognise_vertex_shader(
      "#if defined(GL_ES)\n#define HIGHP_OR_DEFAULT highp\n#endif\nattribute vec3 position;\nattribute vec3 normal;\n"
      "uniform mat4 ModelViewProjectionMatrix;\nuniform mat4 NormalMatrix;\nvarying vec4 Color;\nvoid main(void)\n{\n"
      "    vec3 N = normalize(vec3(NormalMatrix * vec4(normal, 1.0)));\n"
      "    gl_Position = ModelViewProjectionMatrix * vec4(position, 1.0);\n}\n");
  EXPECT_TRUE(basic.ok) << basic.reason;
  EXPECT_EQ(basic.matrices, std::vector<std::string>{"ModelViewProjectionMatrix"});
  EXPECT_EQ(basic.position, "position");
  // light-phong.vert: through one local.
  const auto phong = recognise_vertex_shader(
      "attribute vec3 position;\nuniform mat4 MVP;\nvoid main(void)\n{\n vec4 current_position = vec4(position, 1.0);\n"
      " gl_Position = MVP * current_position;\n}\n");
  EXPECT_TRUE(phong.ok) << phong.reason;
  // conditionals.vert: the position is changed before the multiply.
  const auto cond = recognise_vertex_shader(
      "attribute vec3 position;\nuniform mat4 MVP;\nvoid main(void)\n{\n float d = fract(position.x);\n"
      " vec4 pos = vec4(position.x, position.y + 0.1 * d, position.z, 1.0);\n gl_Position = MVP * pos;\n}\n");
  EXPECT_FALSE(cond.ok);
  EXPECT_EQ(cond.reason, "the vector 'pos' multiplied into gl_Position is not vec4(position, 1.0)");
  const auto twice = recognise_vertex_shader(
      "attribute vec3 p;\nuniform mat4 M;\nvoid main() { gl_Position = M * vec4(p, 1.0); gl_Position.z = 0.0; }");
  EXPECT_EQ(twice.reason, "gl_Position is written more than once");
  const auto cond_write = recognise_vertex_shader(
      "attribute vec3 p;\nuniform mat4 M;\nuniform bool b;\nvoid main() { if (b) { gl_Position = M * vec4(p, 1.0); } }");
  EXPECT_FALSE(cond_write.ok);
  const auto not_uniform = recognise_vertex_shader(
      "attribute vec3 p;\nuniform mat4 M;\nvoid main() { mat4 N = M; gl_Position = N * vec4(p, 1.0); }");
  EXPECT_EQ(not_uniform.reason, "'N' multiplied into gl_Position is not a uniform mat4");
  const auto w2 = recognise_vertex_shader(
      "attribute vec3 p;\nuniform mat4 M;\nvoid main() { gl_Position = M * vec4(p, 2.0); }");
  EXPECT_FALSE(w2.ok);
}

}  // namespace
}  // namespace rastsim
