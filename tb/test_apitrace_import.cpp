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
