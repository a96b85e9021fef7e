// SPDX-License-Identifier: Apache-2.0
// The scan-out's line fetch as a client of the timed memory system (sc/scanout.h:
// ScanoutFetch; docs/scanout.md, "Scan-out as a memory client"), in `simulate` with
// memory.model = "dram", on the default config's panel (128 x 128, double buffered,
// 2-line buffer, 500 MHz core, DDR4-2400):
//
// - a frame reads width x height x 4 bytes (one sample a pixel, RGBA8): linear, one
//   512-byte read a line, 8 whole bursts of 64 bytes; tiled 8 x 8, one 32-byte read a
//   tile row (16 a line), each in a burst of its own: twice the bytes in bursts;
// - with memory.model = "fixed" there is no memory client at all;
// - a DRAM slowed to 10 MHz (160 MB/s peak) still feeds the display alone, but under a
//   burst of full-screen clears (posted writes, queued ahead of the display's reads) the
//   display underruns; at the preset's 1200 MHz the same scene underruns no line;
// - a run started at a phase of the display's timeline (SimOptions::scanout_phase, frame
//   sampling's segments) fetches only the lines the whole timeline has not shown or
//   begun fetching by then.
#include <gtest/gtest.h>

#include <cmath>

#include <string>
#include <vector>

#include "display/scanout_fetch.h"
#include "ref/scene.h"
#include "scene/scene_io.h"
#include "sim_harness.h"

namespace rastsim::sctest {
namespace {

constexpr uint64_t kPanelBytes = 128 * 128 * 4;  // a frame of the shown buffer, RGBA8

Scene one_triangle() {
  return parse_trace("viewport 128 128\ntri 0 0 0.5 255 0 0  0 128 0.5 255 0 0  128 0 0.5 255 0 0\n", "tri");
}

// Ten colour clears, then the triangle: each clear writes 128 x 128 x 4 = 64 KiB, posted
// in 256 ROP cycles (rop.clear_pixels_per_cycle = 64), so all ten are queued within the
// first ~6 us (before the triangle, whose line fills the ROP waits for).
Scene clears_scene() {
  std::string text = "viewport 128 128\n";
  for (int i = 0; i < 10; ++i) text += "clear " + std::to_string(i) + " 0 0\n";
  text += "tri 0 0 0.5 255 0 0  0 128 0.5 255 0 0  128 0 0.5 255 0 0\n";
  return parse_trace(text, "clears");
}

nlohmann::json run(const Scene& scene, std::vector<std::string> kv) {
  kv.push_back("memory.model=dram");
  const Config cfg = make_config(kv);
  const nlohmann::json s = run_isolated([&] { return simulate_stats(scene, cfg); });
  EXPECT_FALSE(s.contains("error")) << s["error"];
  return s;
}

TEST(ScScanoutMemory, LinearFrameReadsWidthTimesHeightTimesFourBytes) {
  const nlohmann::json s = run(one_triangle(), {});
  const nlohmann::json& c = s["memory"]["clients"]["scanout"];
  EXPECT_EQ(c["bytes_read"].get<uint64_t>(), kPanelBytes);
  EXPECT_EQ(c["reads"].get<uint64_t>(), 128u);           // one a line
  EXPECT_EQ(c["bursts_read"].get<uint64_t>(), 128u * 8u);  // 512 bytes = 8 bursts of 64
  EXPECT_EQ(c["lines_fetched"].get<uint64_t>(), 128u);
  EXPECT_EQ(c["underrun_lines"].get<uint64_t>(), 0u);
  EXPECT_EQ(s["scanout_underrun_lines"].get<uint64_t>(), 0u);
  // The front buffer follows the 64 KiB colour surface at memory.color_base = 0.
  EXPECT_EQ(c["shown_base"].get<uint64_t>(), kPanelBytes);
  // The render's own counts are the ROP's alone (render --stats' keys).
  EXPECT_FALSE(s["memory"]["clients"]["rop_color"].contains("lines_fetched"));
}

TEST(ScScanoutMemory, TiledFrameReadsTileRows) {
  const nlohmann::json s = run(one_triangle(), {"memory.fb_layout=tiled"});
  const nlohmann::json& c = s["memory"]["clients"]["scanout"];
  EXPECT_EQ(c["bytes_read"].get<uint64_t>(), kPanelBytes);
  EXPECT_EQ(c["reads"].get<uint64_t>(), 128u * 16u);  // 16 tiles a line, 8 px x 4 bytes each
  // Each 32-byte tile row is half a 64-byte burst; the next line's half is read again.
  EXPECT_EQ(c["bursts_read"].get<uint64_t>() * 64u, 2 * kPanelBytes);
  EXPECT_EQ(c["underrun_lines"].get<uint64_t>(), 0u);
}

TEST(ScScanoutMemory, SingleBufferedReadsTheDrawnSurface) {
  const nlohmann::json s = run(one_triangle(), {"scanout.buffering=single"});
  const nlohmann::json& c = s["memory"]["clients"]["scanout"];
  EXPECT_EQ(c["shown_base"].get<uint64_t>(), 0u);  // memory.color_base
  EXPECT_EQ(c["bytes_read"].get<uint64_t>(), kPanelBytes);
  EXPECT_EQ(c["underrun_lines"].get<uint64_t>(), 0u);
}

TEST(ScScanoutMemory, FixedMemoryHasNoClient) {
  const Config cfg = make_config({"memory.model=fixed"});
  const nlohmann::json s = run_isolated([&] { return simulate_stats(one_triangle(), cfg); });
  ASSERT_FALSE(s.contains("error")) << s["error"];
  EXPECT_FALSE(s.contains("memory"));
  EXPECT_FALSE(s.contains("scanout_underrun_lines"));
}

// Hand reasoning (panel: a line is 160 / 1.3056 MHz = 122.55 us; line y is due at
// (8 + y) x 122.55 us; a fetch starts when the previous one has ended and a slot of the
// 2-line buffer is free).
// - At dram.clock_mhz = 10 the DDR4 channel moves at most 16 bytes a clock, 160 MB/s.
//   Alone, a 512-byte line takes 32 data clocks plus an activate and CAS, a few us, well
//   inside its 122.55 us.
// - With the clears: line 0's read enters first, at cycle 0. The frame's depth clear and
//   the ten colour clears, 11 x 64 KiB = 720896 bytes of posted writes, are queued
//   within the first ~6 us. Line 2's fetch cannot start before line 0's slot frees, at
//   its due time 980.4 us; by then at most 160 MB/s x 980.4 us = 156864 bytes have
//   moved, and only the 40 bursts the scheduler sees may overtake in FR-FCFS (the rest
//   wait in arrival order), so line 2's read waits for at least (720896 - 156864 -
//   40 x 64) / 160 MB/s = 3.51 ms: it ends after 4.49 ms, past the due times of lines
//   2 .. 28 ((8 + 28) x 122.55 us = 4.41 ms). At least 27 lines underrun, the first of
//   them line 1 or 2 (line 1's fetch starts after line 0's, a few us in, when the clears
//   may already be queued).
// - At the preset's 1200 MHz (19.2 GB/s) the writes drain in 38 us: no line underruns.
TEST(ScScanoutMemory, RopClearsStarveASlowDram) {
  const nlohmann::json alone = run(one_triangle(), {"dram.clock_mhz=10"});
  EXPECT_EQ(alone["scanout_underrun_lines"].get<uint64_t>(), 0u);
  const nlohmann::json slow = run(clears_scene(), {"dram.clock_mhz=10"});
  const nlohmann::json& c = slow["memory"]["clients"]["scanout"];
  EXPECT_GE(c["underrun_lines"].get<uint64_t>(), 27u);
  EXPECT_GE(c["first_underrun_line"].get<int>(), 1);
  EXPECT_LE(c["first_underrun_line"].get<int>(), 2);
  EXPECT_EQ(c["lines_fetched"].get<uint64_t>() + c["underrun_lines"].get<uint64_t>(), 128u);
  EXPECT_EQ(slow["scanout_underrun_lines"], c["underrun_lines"]);
  const nlohmann::json fast = run(clears_scene(), {});
  EXPECT_EQ(fast["scanout_underrun_lines"].get<uint64_t>(), 0u);
  EXPECT_EQ(fast["memory"]["clients"]["scanout"]["bytes_read"].get<uint64_t>(), kPanelBytes);
}

// Phase P = D_64, line 64's due cycle on the whole timeline (the panel: 2 line slots).
// By then lines 0..64 are due (shown: 65 lines), and the timeline has begun fetching
// line 65 (at D_63) and line 66 (at D_64, when line 64 freed its slot) but not line 67
// (at D_65 > P). So the run fetches lines 67..127: 61 lines of 512 bytes, no underrun
// (the DRAM is idle but for them). A phase past line 127's due leaves nothing to fetch.
TEST(ScScanoutMemory, PhaseFetchesOnlyTheLinesNotYetStarted) {
  const ArchParams arch = ArchParams::resolve(make_config({"memory.model=dram"}));
  const std::optional<ScanoutParams> p = scanout_params_if_display(arch);
  ASSERT_TRUE(p && !p->single_buffered && p->line_buffer_lines == 2 && p->timing.v_active == 128);
  const auto due = [&](int y) { return uint64_t(std::floor(scanout_line_due_seconds(p->timing, y) * p->core_hz)); };
  const auto fetch = [&](uint64_t phase) {
    return run_isolated([&] {
      sc::SimOptions o;
      o.scanout_phase = phase;
      const sc::SimResult r = sc::simulate_scene(one_triangle(), arch, o);
      return r.scanout ? r.scanout->to_json() : nlohmann::json{{"error", "no scan-out client"}};
    });
  };
  const nlohmann::json mid = fetch(due(64));
  ASSERT_FALSE(mid.contains("error")) << mid;
  EXPECT_EQ(mid["lines_fetched"].get<uint64_t>(), 61u);
  EXPECT_EQ(mid["bytes_read"].get<uint64_t>(), 61u * 512u);
  EXPECT_EQ(mid["underrun_lines"].get<uint64_t>(), 0u);
  const nlohmann::json past = fetch(due(127) + 1);
  EXPECT_EQ(past["bytes_read"].get<uint64_t>(), 0u);
  EXPECT_EQ(past["underrun_lines"].get<uint64_t>(), 0u);
  EXPECT_EQ(fetch(0)["lines_fetched"].get<uint64_t>(), 128u);  // phase 0: the whole frame, as before
}

}  // namespace
}  // namespace rastsim::sctest
