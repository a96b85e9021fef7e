// SPDX-License-Identifier: Apache-2.0
// Trace parser tests: every command parsed exactly (expectations worked by hand), and
// every malformed input rejected with "file:line: what" naming the right line.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <vector>

#include <unistd.h>

#include "scene_test.h"
#include "ref/pipeline.h"
#include "ref/prim_assembly.h"
#include "ref/scene.h"
#include "scene/scene_io.h"
#include "config/raster_state_config.h"

namespace rastsim {
namespace scene_test {

// Declared in scene_test.h.
::testing::AssertionResult SceneFails(const std::function<void()>& fn, const std::string& where,
                                      const std::string& phrase) {
  try {
    fn();
  } catch (const SceneError& e) {
    const std::string msg = e.what();
    if (msg.rfind(where + " ", 0) == 0 && msg.find(phrase) != std::string::npos)
      return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "message \"" << msg << "\" does not start with \"" << where
                                         << " \" and contain \"" << phrase << "\"";
  }
  return ::testing::AssertionFailure() << "no SceneError";
}

// Renders with the default architecture; only SceneError may escape.
RenderStats render_default(const Scene& scene) {
  RenderStats stats;
  render_scene(scene, raster_state_from_config(Config{}), stats);
  return stats;
}

}  // namespace scene_test

namespace {

using scene_test::SceneFails;

Scene parse(const std::string& text) { return parse_trace(text, "t.trace"); }
Q64 dec(const char* s) { return Q64::parse_decimal(s); }

template <class T>
const T& body(const Scene& s, size_t i) {
  return std::get<T>(s.commands.at(i).body);
}

TEST(SceneTrace, StateCommands) {
  const Scene s = parse(
      "viewport 100 64\n"
      "clear 1 2 3\n"
      "cleardepth 0.5\n"
      "scissor 4 5 6 7\n"
      "scissor off\n"
      "tri 0 0 1 0 0 1\n");  // a trace must draw something
  EXPECT_EQ(s.source, "t.trace");
  ASSERT_EQ(s.commands.size(), 6u);
  EXPECT_EQ(body<CmdViewport>(s, 0).width, 100);
  EXPECT_EQ(body<CmdViewport>(s, 0).height, 64);
  const auto& c = body<CmdClear>(s, 1);
  EXPECT_EQ(c.r, 1);
  EXPECT_EQ(c.g, 2);
  EXPECT_EQ(c.b, 3);
  EXPECT_EQ(body<CmdClearDepth>(s, 2).z, 0.5);
  const auto& sc = body<CmdScissor>(s, 3);
  EXPECT_TRUE(sc.enabled);
  EXPECT_EQ(sc.x, 4);
  EXPECT_EQ(sc.y, 5);
  EXPECT_EQ(sc.width, 6);
  EXPECT_EQ(sc.height, 7);
  EXPECT_FALSE(body<CmdScissor>(s, 4).enabled);
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(s.commands[i].loc.file, "t.trace");
    EXPECT_EQ(s.commands[i].loc.line, i + 1);
  }
}

// A trace that draws nothing (empty, only state, a truncated or wrong file) is an error
// naming the file, from the whole-file and the streamed reader alike.
TEST(SceneTrace, TraceWithoutDrawIsAnError) {
  for (const char* text : {"", "# nothing\n\n", "viewport 10 10\nclear 0 0 0\ncolor 1 2 3\ndepth 0.5\n"}) {
    SCOPED_TRACE(text);
    EXPECT_TRUE(SceneFails([&] { parse(text); }, "t.trace:", "no draw command (tri, strip, fan"));
  }
  EXPECT_NO_THROW(parse("point 1 1\n"));  // a 2D draw is a draw
  const auto path = std::filesystem::temp_directory_path() / ("rastsim_empty_" + std::to_string(::getpid()) + ".trace");
  std::ofstream(path.string()) << "viewport 10 10\nclear 0 0 0\n";
  size_t consumed = 0;
  try {
    stream_trace(path.string(), 1, [&](std::vector<Command>& b) { consumed += b.size(); });
    ADD_FAILURE() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(path.string() + ": no draw command", 0), 0u) << e.what();
  }
  EXPECT_EQ(consumed, 2u);  // the state commands went by first, as a parse error's batches do
  std::filesystem::remove(path);
}

TEST(SceneTrace, ByteOrderMarkIsAccepted) {
  const Scene s = parse("\xEF\xBB\xBF" "clear 1 2 3\ntri 0 0 1 0 0 1\n");
  ASSERT_EQ(s.commands.size(), 2u);
  EXPECT_EQ(body<CmdClear>(s, 0).r, 1);
  EXPECT_TRUE(SceneFails([] { parse("clear 1 2 3\n\xEF\xBB\xBF" "tri 0 0 1 0 0 1\n"); }, "t.trace:2:", "unknown command"));
}

TEST(SceneTrace, FlatTriUsesCurrentColourAndDepth) {
  const Scene s = parse(
      "tri 1 2 3 4 5 6\n"
      "color 10 20 30\n"
      "depth 0.25\n"
      "tri 10.25 -3.5 0 0 .5 7.\n");
  ASSERT_EQ(s.commands.size(), 2u);
  const auto& a = body<CmdPrimitives>(s, 0);
  EXPECT_EQ(a.topology, Topology::List);
  ASSERT_EQ(a.vertices.size(), 3u);
  // Defaults before any color/depth: white, depth 0.
  EXPECT_EQ(a.vertices[0].r, 255);
  EXPECT_EQ(a.vertices[0].g, 255);
  EXPECT_EQ(a.vertices[0].b, 255);
  EXPECT_EQ(a.vertices[0].z, 0.0);
  EXPECT_EQ(a.vertices[2].x.q, Q64::from_int(5).q);
  EXPECT_EQ(a.vertices[2].y.q, Q64::from_int(6).q);
  const auto& b = body<CmdPrimitives>(s, 1);
  EXPECT_EQ(s.commands[1].loc.line, 4);
  ASSERT_EQ(b.vertices.size(), 3u);
  // 10.25 = 41/4 and -3.5 = -7/2 exactly, in units of 2^-64.
  EXPECT_EQ(b.vertices[0].x.q, i128(41) << 62);
  EXPECT_EQ(b.vertices[0].y.q, -(i128(7) << 63));
  EXPECT_EQ(b.vertices[2].x.q, i128(1) << 63);  // .5
  EXPECT_EQ(b.vertices[2].y.q, Q64::from_int(7).q);  // 7.
  for (const SceneVertex& v : b.vertices) {
    EXPECT_EQ(v.r, 10);
    EXPECT_EQ(v.g, 20);
    EXPECT_EQ(v.b, 30);
    EXPECT_EQ(v.z, 0.25);
  }
}

TEST(SceneTrace, CoordinatesAreExactDecimals) {
  const Scene s = parse("tri 0.1 -0.1 +2 0 123456789012345678901234567890 0.000000000000000000000000000000000001\n");
  const auto& v = body<CmdPrimitives>(s, 0).vertices;
  // 0.1 * 2^64 = 1844674407370955161.6: truncated to ...161, which is odd, so round
  // to odd keeps it (the sticky bit is already set).
  EXPECT_EQ(v[0].x.q, i128(1844674407370955161LL));
  EXPECT_EQ(v[0].y.q, -i128(1844674407370955161LL));
  EXPECT_EQ(v[1].x.q, Q64::from_int(2).q);
  // Numerically huge is not a parse error: it saturates and setup reports it.
  EXPECT_TRUE(v[2].x.saturated());
  // 1e-36 is below 2^-64: truncates to 0, sticky makes it the odd 1.
  EXPECT_EQ(v[2].y.q, i128(1));
}

TEST(SceneTrace, PerVertexTri) {
  const Scene s = parse("tri 1 2 0 255 0 0   3 4 0.5 0 255 0   5 6 1 0 0 255\n");
  const auto& v = body<CmdPrimitives>(s, 0).vertices;
  ASSERT_EQ(v.size(), 3u);
  EXPECT_EQ(v[0].x.q, dec("1").q);
  EXPECT_EQ(v[1].y.q, dec("4").q);
  EXPECT_EQ(v[0].z, 0.0);
  EXPECT_EQ(v[1].z, 0.5);
  EXPECT_EQ(v[2].z, 1.0);
  EXPECT_EQ(v[0].r, 255);
  EXPECT_EQ(v[1].g, 255);
  EXPECT_EQ(v[2].b, 255);
  EXPECT_EQ(v[2].r, 0);
}

TEST(SceneTrace, StripKeepsWindingThroughAssembly) {
  const Scene s = parse(
      "color 9 8 7\n"
      "strip   # opens here\n"
      "\n"
      "v 0 0\n"
      "v 0 10 0.5 1 2 3\n"
      "v 10 0\n"
      "v 10 10\n"
      "end\n");
  ASSERT_EQ(s.commands.size(), 1u);
  // The command is named by its first vertex line.
  EXPECT_EQ(s.commands[0].loc.line, 4);
  const auto& p = body<CmdPrimitives>(s, 0);
  EXPECT_EQ(p.topology, Topology::Strip);
  ASSERT_EQ(triangle_count(p), 2u);
  // Triangle 1 of a strip is (v2, v1, v3): (10,0) (0,10) (10,10).
  const auto t1 = assemble_triangle(p, 1);
  EXPECT_EQ(t1[0].x.q, dec("10").q);
  EXPECT_EQ(t1[0].y.q, dec("0").q);
  EXPECT_EQ(t1[0].r, 9);  // flat vertices take the current colour
  EXPECT_EQ(t1[1].x.q, dec("0").q);
  EXPECT_EQ(t1[1].y.q, dec("10").q);
  EXPECT_EQ(t1[1].r, 1);  // the full vertex keeps its own colour
  EXPECT_EQ(t1[1].z, 0.5);
  EXPECT_EQ(t1[2].x.q, dec("10").q);
  EXPECT_EQ(t1[2].y.q, dec("10").q);
  // Both triangles keep one winding: doubled area in y-down screen space.
  for (size_t k = 0; k < 2; ++k) {
    const auto t = assemble_triangle(p, k);
    const double a = (t[1].x.to_double() - t[0].x.to_double()) * (t[2].y.to_double() - t[0].y.to_double()) -
                     (t[1].y.to_double() - t[0].y.to_double()) * (t[2].x.to_double() - t[0].x.to_double());
    EXPECT_LT(a, 0) << "triangle " << k;
  }
}

TEST(SceneTrace, FanAndColourInsideIt) {
  const Scene s = parse(
      "fan\n"
      "v 5 5\n"
      "color 1 1 1\n"
      "depth 1\n"
      "v 0 0\n"
      "v 10 0\n"
      "v 10 10\n"
      "end\n");
  const auto& p = body<CmdPrimitives>(s, 0);
  EXPECT_EQ(p.topology, Topology::Fan);
  EXPECT_EQ(s.commands[0].loc.line, 2);
  ASSERT_EQ(triangle_count(p), 2u);
  const auto t1 = assemble_triangle(p, 1);  // (v0, v2, v3)
  EXPECT_EQ(t1[0].x.q, dec("5").q);
  EXPECT_EQ(t1[0].r, 255);
  EXPECT_EQ(t1[0].z, 0.0);
  EXPECT_EQ(t1[1].x.q, dec("10").q);
  EXPECT_EQ(t1[1].y.q, dec("0").q);
  EXPECT_EQ(t1[1].r, 1);
  EXPECT_EQ(t1[1].z, 1.0);
  EXPECT_EQ(t1[2].y.q, dec("10").q);
}

TEST(SceneTrace, CommentsBlankLinesTabsAndCrlf) {
  const Scene s = parse("# header\r\n\r\n\tclear\t1 2 3# trailing\r\n   \r\n#tri 1\r\nviewport 8 8\r\npoint 1 1\r\n");
  ASSERT_EQ(s.commands.size(), 3u);
  EXPECT_EQ(s.commands[0].loc.line, 3);
  EXPECT_EQ(s.commands[1].loc.line, 6);
  EXPECT_EQ(body<CmdClear>(s, 0).b, 3);
}

TEST(SceneTrace, ExactErrorMessage) {
  try {
    parse("clear 0 0 0\nfrob 1\n");
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_STREQ(e.what(), "t.trace:2: unknown command 'frob'");
  }
}

struct BadTrace {
  std::string text;
  int line;
  const char* phrase;
};

TEST(SceneTrace, ErrorsNameTheLine) {
  using namespace std::string_literals;  // "..."s keeps the embedded NUL
  const BadTrace cases[] = {
      {"frob", 1, "unknown command 'frob'"},
      {"\n\n# c\nclear 0 0", 4, "'clear' takes 3 arguments"},
      {"viewport 128", 1, "'viewport' takes 2 arguments"},
      {"viewport 0 128", 1, "viewport width 0 is outside 1..16384"},
      {"viewport 128 16385", 1, "viewport height 16385 is outside 1..16384"},
      {"viewport 99999999999999999999999 1", 1, "is not an integer"},
      {"viewport 12px 10", 1, "viewport width '12px' is not an integer"},
      {"viewport 1.5 10", 1, "is not an integer"},
      {"viewport +-5 10", 1, "viewport width '+-5' is not an integer"},
      {"viewport 5 +", 1, "viewport height '+' is not an integer"},
      {"clear 256 0 0", 1, "red 256 is outside 0..255"},
      {"clear 0 -1 0", 1, "green -1 is outside 0..255"},
      {"clear 0 0 0x10", 1, "blue '0x10' is not an integer"},
      {"color 1 2", 1, "'color' takes 3 arguments"},
      {"color 1 2 3 4", 1, "'color' takes 3 arguments"},
      {"cleardepth 1.5", 1, "clear depth '1.5' is outside [0, 1]"},
      {"cleardepth -0.001", 1, "is outside [0, 1]"},
      {"cleardepth", 1, "'cleardepth' takes 1 argument"},
      {"depth abc", 1, "depth 'abc' is not a decimal number"},
      {"depth 1e-3", 1, "is not a decimal number"},
      {"depth nan", 1, "is not a decimal number"},
      {"scissor 1 2 3", 1, "'scissor' takes 4 arguments"},
      {"scissor on", 1, "'scissor' takes 4 arguments (X Y W H, or 'off')"},
      {"scissor -1 0 4 4", 1, "scissor x -1 is outside 0..16384"},
      {"scissor 0 0 4 99999", 1, "scissor height 99999 is outside"},
      {"tri 1 2 3 4 5", 1, "'tri' takes 6 numbers"},
      {"tri 1 2 3 4 5 6 7", 1, "got 7"},
      {"tri 1 2 3 4 5 6x", 1, "vertex 2 y '6x' is not a decimal number"},
      {"tri 1 2 3 4 1e3 6", 1, "vertex 2 x '1e3' is not a decimal number"},
      {"tri 1 2 3 -- 5 6", 1, "vertex 1 y '--' is not a decimal number"},
      {"tri 1 2 3 4 . 6", 1, "vertex 2 x '.' is not a decimal number"},
      {"tri 0 0 2 1 1 1  1 0 0 1 1 1  0 1 0 1 1 1", 1, "vertex 0 z '2' is outside [0, 1]"},
      {"tri 0 0 0 1 1 1  1 0 0 300 1 1  0 1 0 1 1 1", 1, "vertex 1 red 300 is outside 0..255"},
      {"tri 0.0000000000000000000000000000000000001 0 1 0 0 1", 1, "more than 36 fraction digits"},
      {"clear 0 0 0\nv 1 2", 2, "'v' outside a strip or fan"},
      {"end", 1, "'end' without a 'strip' or 'fan'"},
      {"strip extra", 1, "'strip' takes 0 arguments"},
      {"fan\nv 1 1\nv 2 2\nv 3 3\nend now", 5, "'end' takes 0 arguments"},
      {"fan\nv 1 1 1", 2, "'v' takes 2 numbers (x y) or 6"},
      {"strip\nv 1 1\nv 2 2\nend", 1, "'strip' has 2 vertices; it needs at least 3"},
      {"clear 0 0 0\nfan\nend", 2, "'fan' has 0 vertices"},
      {"clear 0 0 0\nfan\nv 1 1\nv 2 2\nv 3 3\n", 2, "'fan' without 'end'"},
      {"strip\nv 1 1\ntri 0 0 1 0 0 1", 3, "'tri' inside the 'strip' begun at line 1 (missing 'end'?)"},
      {"strip\nfan", 2, "'fan' inside the 'strip' begun at line 1"},
      {"strip\nv 0 0\nviewport 8 8", 3, "'viewport' inside the 'strip'"},
      {"strip\nv 0 0\nfrob", 3, "unknown command 'frob'"},
      {"clear 0 0 0\ntri 0 0 1\0 1 2 2\n"s, 2, "NUL byte"},
      {"\x01\x7f\xff 1", 1, "unknown command '\\x01\\x7f\\xff'"},
      {"a\r\nb\r\nfrob\r\n", 1, "unknown command 'a'"},
  };
  for (const BadTrace& c : cases) {
    SCOPED_TRACE(c.text);
    EXPECT_TRUE(SceneFails([&] { parse(c.text); }, "t.trace:" + std::to_string(c.line) + ":", c.phrase));
  }
}

TEST(SceneTrace, OverlongLine) {
  const std::string text = "clear 0 0 0\n# " + std::string(4094, 'x') + "\ntri " + std::string(4093, ' ') + "\n";
  // Line 2 is exactly 4096 characters (fine); line 3 is 4097.
  EXPECT_TRUE(SceneFails([&] { parse(text); }, "t.trace:3:", "longer than 4096 characters"));
}

TEST(SceneTrace, LongTokenIsCutInMessage) {
  const std::string text = "tri " + std::string(3000, '9') + "z 0 1 0 0 1\n";
  try {
    parse(text);
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_LT(std::string(e.what()).size(), 120u) << e.what();
    EXPECT_NE(std::string(e.what()).find("...'"), std::string::npos) << e.what();
  }
}

TEST(SceneTrace, LoadMissingFile) {
  const std::string path = std::string(RASTSIM_TEST_DATA) + "/no_such.trace";
  try {
    load_trace(path);
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()), path + ": cannot open");
  }
  // A directory is not a trace either.
  EXPECT_TRUE(SceneFails([] { load_trace(RASTSIM_TEST_DATA); }, std::string(RASTSIM_TEST_DATA) + ":", ""));
}

TEST(SceneTrace, LoadSceneDispatchesOnExtension) {
  const auto dir = std::filesystem::temp_directory_path() / ("rastsim_scene_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  for (const char* n : {"m.obj", "m.OBJ", "m.Obj"}) std::ofstream(dir / n) << obj;
  std::ofstream(dir / "m.trace") << "clear 1 2 3\ntri 0 0 1 0 0 1\n";
  std::ofstream(dir / "obj") << "clear 1 2 3\ntri 0 0 1 0 0 1\n";  // no extension: a trace
  for (const char* n : {"m.obj", "m.OBJ", "m.Obj"}) {
    SCOPED_TRACE(n);
    const Scene s = load_scene((dir / n).string(), obj_placement_from_config(Config{}));
    ASSERT_EQ(s.commands.size(), 3u);  // clear, clear depth, one face
    EXPECT_TRUE(std::holds_alternative<CmdPrimitives>(s.commands[2].body));
  }
  for (const char* n : {"m.trace", "obj"}) {
    const Scene s = load_scene((dir / n).string(), obj_placement_from_config(Config{}));
    ASSERT_EQ(s.commands.size(), 2u);
    EXPECT_EQ(body<CmdClear>(s, 0).r, 1);
    EXPECT_EQ(s.source, (dir / n).string());
  }
  std::filesystem::remove_all(dir);
}

// Every example trace parses and renders with the default architecture.
TEST(SceneTrace, ExampleTracesRender) {
  int seen = 0;
  // traces/ and traces/3d/ (clip space); the 2D traces draw no triangle fragments.
  std::vector<std::filesystem::path> paths;
  for (const char* dir : {"/traces", "/traces/3d"})
    for (const auto& e : std::filesystem::directory_iterator(std::string(RASTSIM_SOURCE_DIR) + dir))
      if (e.path().extension() == ".trace") paths.push_back(e.path());
  for (const auto& path : paths) {
    SCOPED_TRACE(path.string());
    ++seen;
    const Scene s = load_trace(path.string());
    EXPECT_FALSE(s.commands.empty());
    RenderStats stats;
    ASSERT_NO_THROW(stats = scene_test::render_default(s));
    EXPECT_GT(stats.fragments_passed, 0u);
  }
  EXPECT_GE(seen, 3);
}

std::string example(const char* name) { return std::string(RASTSIM_SOURCE_DIR) + "/traces/" + name + ".trace"; }

// The hand-written examples are all counter-clockwise on screen, so back-face culling
// (front = CCW) keeps every triangle.
TEST(SceneTrace, ExampleTracesAreFrontFacing) {
  RasterState st = raster_state_from_config(Config{});
  st.cull = CullMode::Back;
  for (const char* name : {"primitives", "fill_rule", "state"}) {
    SCOPED_TRACE(name);
    RenderStats stats;
    render_scene(load_trace(example(name)), st, stats);
    EXPECT_EQ(stats.triangles_culled, 0u);
    EXPECT_EQ(stats.triangles_rasterized, stats.triangles_in);
  }
}

// fill_rule.trace: edges shared through pixel centres give every pixel one fragment.
// Regions worked by hand: the split square covers centres 8.5..39.5 (32 x 32), the
// four-triangle square 48.5..79.5 (32 x 32), the strip x 8.5..71.5, y 56.5..87.5.
TEST(SceneTrace, FillRuleTraceDrawsSharedEdgesOnce) {
  std::map<std::pair<int, int>, int> hits;
  RenderStats stats;
  render_scene(load_trace(example("fill_rule")), raster_state_from_config(Config{}), stats,
               [&](const Fragment& f) { ++hits[{f.x, f.y}]; });
  for (const auto& [xy, n] : hits) EXPECT_EQ(n, 1) << "pixel " << xy.first << "," << xy.second;
  auto covered = [&](int x0, int y0, int x1, int y1) {
    int n = 0;
    for (const auto& [xy, c] : hits) n += xy.first >= x0 && xy.first < x1 && xy.second >= y0 && xy.second < y1;
    return n;
  };
  EXPECT_EQ(covered(8, 8, 40, 40), 32 * 32);
  EXPECT_EQ(covered(0, 0, 48, 48), 32 * 32);  // nothing outside the square either
  EXPECT_EQ(covered(48, 8, 80, 40), 32 * 32);
  EXPECT_EQ(covered(44, 4, 84, 44), 32 * 32);
  EXPECT_EQ(covered(8, 56, 72, 88), 64 * 32);
}

// A huge coordinate parses, and setup then reports it against the format at its line.
TEST(SceneTrace, HugeCoordinateIsASetupErrorNotAParseError) {
  const Scene s = parse("clear 0 0 0\n\ntri 0 0 100000 0 0 10\n");
  EXPECT_TRUE(SceneFails([&] { scene_test::render_default(s); }, "t.trace:3:", "outside the"));
}

}  // namespace
}  // namespace rastsim
