// SPDX-License-Identifier: Apache-2.0
// Scenes streamed in bounded batches (scene_io.h stream_scene): the same commands as the
// whole-file reader across the reader's chunk boundaries, batches no larger than needed,
// and a malformed last line reported with its line after everything before it was
// handed over.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "config/config.h"
#include "config/raster_state_config.h"
#include "ref/pipeline.h"
#include "scene/scene_io.h"

namespace rastsim {
namespace {

// n flat triangles (~3.5 MB for 60000: several 1 MB read chunks), a strip, comments,
// then `last` as the final line.
std::string write_trace(const std::string& name, int n, const std::string& last) {
  // The process id in the name: test binaries of two build trees may run at once.
  const std::string path = ::testing::TempDir() + std::to_string(getpid()) + "_" + name;
  std::ofstream os(path);
  os << "viewport 200 150\nclear 1 2 3\n# a comment\n";
  for (int i = 0; i < n; ++i)
    os << "color " << i % 256 << " 9 9\ntri " << i % 190 << ".25 " << i % 140 << ".5 " << i % 190 + 6 << " "
       << i % 140 + 1 << " " << i % 190 + 2 << ".75 " << i % 140 + 7 << "\n";
  os << "strip\nv 1 1\nv 30 2\nv 3 40\nv 35 45\nend\n" << last;
  return path;
}

TEST(SceneBatches, SameCommandsAsTheWholeFileInBoundedBatches) {
  const std::string path = write_trace("batches.trace", 60000, "tri 0 0 10 0 0 10\n");
  const Scene whole = load_trace(path);
  std::vector<Command> streamed;
  size_t batches = 0;
  stream_scene(path, ObjPlacement{}, 1000, [&](std::vector<Command>& b) {
    EXPECT_GE(b.size(), 1u);
    EXPECT_LE(b.size(), 1000u);  // a trace line makes at most one command
    ++batches;
    for (Command& c : b) streamed.push_back(std::move(c));
  });
  ASSERT_EQ(streamed.size(), whole.commands.size());
  EXPECT_GE(batches, 60u);
  for (size_t i = 0; i < streamed.size(); ++i) ASSERT_EQ(streamed[i].loc.str(), whole.commands[i].loc.str()) << i;
  // Rendered through SceneRenderer batch by batch: render_scene's CRC.
  RasterState st = raster_state_from_config(Config{});
  st.fb_width = 200, st.fb_height = 150;
  RenderStats a, b;
  render_scene(whole, st, a);
  SceneRenderer r(st, b);
  stream_scene(path, ObjPlacement{}, 777, [&](std::vector<Command>& batch) {
    r.run(batch);
  });
  r.finish();
  EXPECT_EQ(a.framebuffer_crc32, b.framebuffer_crc32);
  EXPECT_EQ(a.fragments_passed, b.fragments_passed);
  std::remove(path.c_str());
}

// Long strips are one command each: a batch is bounded by the lines it took too, so a
// reader thread hands the first strips over long before the file ends.
TEST(SceneBatches, LongStripsAreBatchedByLines) {
  const std::string path = ::testing::TempDir() + std::to_string(getpid()) + "_batches_strips.trace";
  {
    std::ofstream os(path);
    os << "viewport 200 150\n";
    for (int s = 0; s < 40; ++s) {  // 40 strips of 201 lines each
      os << "strip\n";
      for (int v = 0; v < 199; ++v) os << "v " << v % 190 << " " << (v % 2) * 5 + s * 3 << "\n";
      os << "end\n";
    }
  }
  const Scene whole = load_trace(path);
  std::vector<size_t> sizes;
  size_t total = 0;
  stream_scene(path, ObjPlacement{}, 1000, [&](std::vector<Command>& b) {
    sizes.push_back(b.size());
    total += b.size();
  });
  EXPECT_EQ(total, whole.commands.size());
  // 1000 lines hold at most 5 whole strips of 201 lines: batches of <= 6 commands (the
  // viewport rides with the first), so 40 strips make at least 7 batches.
  ASSERT_GE(sizes.size(), 7u);
  for (size_t n : sizes) EXPECT_LE(n, 6u);
  std::remove(path.c_str());
}

TEST(SceneBatches, MalformedLastLineStopsWithItsLineAfterTheRest) {
  const std::string path = write_trace("batches_bad.trace", 30000, "tri 1 2 3 4 5");  // no newline, 5 numbers
  const int last_line = 3 + 2 * 30000 + 6 + 1;
  size_t consumed = 0;
  try {
    stream_scene(path, ObjPlacement{}, 500, [&](std::vector<Command>& b) { consumed += b.size(); });
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(path + ":" + std::to_string(last_line) + ": 'tri' takes", 0), 0u)
        << e.what();
  }
  // Everything up to the bad line was handed over first (viewport, clear, the triangles,
  // the strip), in batches of 500: all but the last partial batch.
  EXPECT_EQ(consumed, (2 + 30000 + 1) / 500 * 500);
  // An unclosed strip at the end of the file: the line of the strip.
  const std::string open = write_trace("batches_open.trace", 10, "fan\nv 1 1\n");
  try {
    stream_scene(open, ObjPlacement{}, 4, [](std::vector<Command>&) {});
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(open + ":" + std::to_string(3 + 20 + 6 + 1) + ": 'fan' without 'end'", 0), 0u)
        << e.what();
  }
  std::remove(path.c_str());
  std::remove(open.c_str());
}

}  // namespace
}  // namespace rastsim
