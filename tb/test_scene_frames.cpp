// SPDX-License-Identifier: Apache-2.0
// The trace's `frame` command (docs/trace-format.md, "Frames"): which command each
// frame starts at (worked by hand from the line numbers), the same marks from the
// streamed reader, and every misuse rejected as file:line naming the right line.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <vector>

#include <unistd.h>

#include "scene_test.h"
#include "scene/scene_io.h"

namespace rastsim {
namespace {

using scene_test::SceneFails;

// Lines:              1             2             3                  4        5               6
const char* kThree = "viewport 8 8\nclear 0 0 0\ntri 0 0 8 0 0 8\nframe\nclear 9 9 9\ntri 0 0 8 0 8 8\n"
                     // 7      8         9               10                  11
                     "frame\ncolor 1 2 3\nscissor 0 0 4 4\ntri 1 1 7 1 1 7\nframe\n";

// The frame_line of every command, in order.
std::vector<int> marks(const std::vector<Command>& cmds) {
  std::vector<int> m;
  for (const Command& c : cmds) m.push_back(c.frame_line);
  return m;
}

TEST(SceneFrames, EachFrameStartsAtTheCommandAfterItsFrameLine) {
  const Scene s = parse_trace(kThree, "t.trace");
  // viewport, clear, tri | clear (after line 4), tri | scissor (after line 7; `color`
  // makes no command), tri. The trailing `frame` (line 11) ends the last frame: no mark.
  ASSERT_EQ(s.commands.size(), 7u);
  EXPECT_EQ(marks(s.commands), (std::vector<int>{0, 0, 0, 4, 0, 7, 0}));
  EXPECT_EQ(s.commands[3].loc.line, 5);
  EXPECT_EQ(s.commands[5].loc.line, 9);
}

TEST(SceneFrames, ATraceWithoutFrameIsOneFrame) {
  const Scene s = parse_trace("viewport 8 8\ntri 0 0 8 0 0 8\ntri 0 0 8 0 8 8\n", "t.trace");
  EXPECT_EQ(marks(s.commands), (std::vector<int>{0, 0, 0}));
  // A trailing `frame` changes nothing.
  const Scene t = parse_trace("viewport 8 8\ntri 0 0 8 0 0 8\ntri 0 0 8 0 8 8\nframe\n", "t.trace");
  EXPECT_EQ(marks(t.commands), marks(s.commands));
}

TEST(SceneFrames, TheStreamedReaderMarksTheSameCommands) {
  const std::string path = ::testing::TempDir() + "frames_" + std::to_string(getpid()) + ".trace";
  std::ofstream(path) << kThree;
  for (size_t batch : {1, 2, 100}) {
    std::vector<Command> all;
    stream_trace(path, batch, [&](std::vector<Command>& b) { all.insert(all.end(), b.begin(), b.end()); });
    EXPECT_EQ(marks(all), (std::vector<int>{0, 0, 0, 4, 0, 7, 0})) << "batch " << batch;
  }
  std::filesystem::remove(path);
}

TEST(SceneFrames, MisusesNameTheirLine) {
  const auto parse = [](const char* text) { return [text] { parse_trace(text, "t.trace"); }; };
  EXPECT_TRUE(SceneFails(parse("viewport 8 8\ntri 0 0 8 0 0 8\nframe now\n"), "t.trace:3:",
                         "'frame' takes 0 arguments"));
  EXPECT_TRUE(SceneFails(parse("frame\nviewport 8 8\ntri 0 0 8 0 0 8\n"), "t.trace:1:", "before any command"));
  EXPECT_TRUE(SceneFails(parse("# state only\ncolor 1 2 3\nframe\ntri 0 0 8 0 0 8\n"), "t.trace:3:",
                         "before any command"));
  EXPECT_TRUE(SceneFails(parse("viewport 8 8\ntri 0 0 8 0 0 8\nframe\nframe\ntri 0 0 8 0 0 8\n"), "t.trace:4:",
                         "right after the 'frame' at line 3"));
  EXPECT_TRUE(SceneFails(parse("viewport 8 8\ntri 0 0 8 0 0 8\nframe\ncolor 1 1 1\nframe\ntri 0 0 8 0 0 8\n"),
                         "t.trace:5:", "right after the 'frame' at line 3"));
  EXPECT_TRUE(SceneFails(parse("viewport 8 8\nstrip\nv 0 0\nv 8 0\nframe\nv 0 8\nend\n"), "t.trace:5:",
                         "'frame' inside the 'strip' begun at line 2"));
  // Frames of nothing but state still draw nothing at all: the whole-trace rule.
  EXPECT_TRUE(SceneFails(parse("viewport 8 8\nframe\nclear 0 0 0\nframe\n"), "t.trace:", "no draw command"));
}

}  // namespace
}  // namespace rastsim
