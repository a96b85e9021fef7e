// SPDX-License-Identifier: Apache-2.0
// Recorded signal -> virtual monitor (model/display/signal_reader.h): the panel preset
// scanned out to a VCD and decoded from the file bit for bit; a shifted hsync edge
// edited into the file is named; malformed files give "file:line: what"; an RTL-style
// trace (Verilator names, a clock, codes only) decodes the same; FST through fst2vcd.
// Expected numbers are worked by hand from the panel preset (160x136 total, 16 px
// hsync, 1.3056 MHz), never taken from the code under test.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "ref/pipeline.h"
#include "ref/raster_state.h"
#include "scanout_test_util.h"
#include "display/signal_reader.h"
#include "scene/scene_io.h"
#include "util/process.h"
#include "config/raster_state_config.h"

namespace rastsim {
namespace {

namespace fs = std::filesystem;

const fs::path kSourceDir = RASTSIM_SOURCE_DIR;

fs::path temp_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  fs::path d = fs::temp_directory_path() /
               ("rastsim_signal_" + std::string(info->name()) + "_" + std::to_string(getpid()));
  fs::create_directories(d);
  return d;
}

std::string all_errors(const std::vector<std::string>& errs) {
  std::string s;
  for (auto& e : errs) s += e + "\n";
  return s;
}

bool has(const std::vector<std::string>& errs, const std::string& text) {
  return std::any_of(errs.begin(), errs.end(), [&](const std::string& e) { return e.find(text) != std::string::npos; });
}

struct Panel {
  Config cfg;  // defaults: display.timing = panel, 128x128 framebuffer
  VideoTiming t = video_timing_from_config(cfg);
  Dac dac{dac_config_from_config(cfg)};
  Framebuffer fb;
  Panel() {
    RenderStats st;
    fb = render_scene(load_scene((kSourceDir / "traces/torus.trace").string(), obj_placement_from_config(Config{})),
                      raster_state_from_config(cfg), st);
  }
  // The reference scan-out of `frames` frames from (0, 0) as `rastsim scanout --signal` writes it.
  void write_vcd(const fs::path& p, int frames) const {
    VideoVcdWriter w(p.string(), t.pixel_clock_hz, dac.config().bits);
    Scanout(t, dac, fb).run(frames, [&](const VideoSample& s) { w.push(s); });
    w.close();
  }
};

struct Decoded {
  SignalReadInfo info;
  MonitorResult r;
};
Decoded decode_file(const Panel& p, const fs::path& file, const SignalReaderOptions& o = {}) {
  Monitor mon(p.t, p.dac.config());
  Decoded d;
  d.info = read_video_signal(file.string(), p.t, p.dac, [&](const VideoSample& s) { mon.push(s); }, o);
  d.r = mon.finish();
  return d;
}

void expect_panel_decoded_exactly(const Panel& p, const Decoded& d) {
  EXPECT_TRUE(d.r.ok()) << all_errors(d.r.errors);
  EXPECT_TRUE(d.info.problems.empty()) << all_errors(d.info.problems);
  ASSERT_TRUE(d.r.locked);
  EXPECT_EQ(d.r.frames_decoded, 1);
  EXPECT_EQ(scanout_test::rgb_mismatches(d.r.image, p.fb), 0);
  // The panel preset by hand: 128 + 8 + 16 + 8 = 160 px, 128 + 2 + 2 + 4 = 136 lines.
  const VideoTiming& m = d.r.measured;
  EXPECT_EQ(m.h_total, 160);
  EXPECT_EQ(m.h_sync, 16);
  EXPECT_EQ(m.h_front_porch, 8);
  EXPECT_EQ(m.h_back_porch, 8);
  EXPECT_EQ(m.h_active, 128);
  EXPECT_EQ(m.v_total, 136);
  EXPECT_EQ(m.v_sync, 2);
  EXPECT_EQ(m.v_front_porch, 2);
  EXPECT_EQ(m.v_back_porch, 4);
  EXPECT_EQ(m.v_active, 128);
  EXPECT_NEAR(d.r.line_rate_hz, 8160.0, 1e-6);
  EXPECT_NEAR(d.r.frame_rate_hz, 60.0, 1e-9);
  VideoTiming conf = p.t;
  conf.name = m.name;
  EXPECT_EQ(m, conf);
}

TEST(SignalReader, PanelVcdRoundTripBitExact) {
  const Panel p;
  const fs::path f = temp_dir() / "panel.vcd";
  p.write_vcd(f, 2);
  const Decoded d = decode_file(p, f);
  EXPECT_EQ(d.info.samples, 2 * 160 * 136);
  EXPECT_EQ(d.info.clock, "");
  EXPECT_EQ(d.info.levels_from, "level_r/g/b");
  EXPECT_EQ(d.info.variables.at("hsync"), "video.hsync");
  expect_panel_decoded_exactly(p, d);
  fs::remove_all(f.parent_path());
}

// One frame from (0, 0) holds one vsync pulse: no frame lies between two of them.
TEST(SignalReader, SingleFrameFileIsNotEnough) {
  const Panel p;
  const fs::path f = temp_dir() / "one.vcd";
  p.write_vcd(f, 1);
  const Decoded d = decode_file(p, f);
  EXPECT_EQ(d.info.samples, 160 * 136);
  EXPECT_FALSE(d.r.locked);
  EXPECT_TRUE(has(d.r.errors, "no complete frame")) << all_errors(d.r.errors);
  fs::remove_all(f.parent_path());
}

std::vector<std::string> read_lines(const fs::path& f) {
  std::ifstream in(f);
  std::vector<std::string> v;
  for (std::string l; std::getline(in, l);) v.push_back(l);
  return v;
}
void write_lines(const fs::path& f, const std::vector<std::string>& v) {
  std::ofstream os(f);
  for (auto& l : v) os << l << "\n";
}

// The hsync leading edge of frame 1, line 50 (hcount 128 + 8 = 136) moved one pixel clock
// later in the file's text. Lines start at hsync leading edges; the decoded frame starts
// at the line holding frame 0's vsync leading edge (vcount 130, hcount 0), i.e. the line
// from (129, 136): the edited edge starts line 136 - 129 + 50 = 57 of it. So line 56
// is 161 px long with a 9 px front porch, line 57 is 159 px with a 15 px hsync.
TEST(SignalReader, ShiftedHsyncEdgeInFileCaught) {
  const Panel p;
  const fs::path f = temp_dir() / "porch.vcd";
  p.write_vcd(f, 2);
  auto lines = read_lines(f);
  const double ps = 1e12 / 1.3056e6;
  const long long i = (136LL + 50) * 160 + 136;
  const std::string at = "#" + std::to_string(std::llround(i * ps));
  auto ts = std::find(lines.begin(), lines.end(), at);
  ASSERT_NE(ts, lines.end()) << at;
  auto edge = std::find(ts, lines.end(), "0h");
  ASSERT_NE(edge, lines.end());
  auto next_ts = std::find_if(ts + 1, lines.end(), [](const std::string& l) { return l[0] == '#'; });
  ASSERT_LT(edge, next_ts);  // the edge is in this time's block
  const std::string later = "#" + std::to_string(std::llround((i + 1) * ps));
  ASSERT_NE(*next_ts, later);  // nothing else changes one clock later (inside the sync)
  const long long next_pos = next_ts - lines.begin() - 1;  // after the erase
  lines.erase(edge);
  lines.insert(lines.begin() + next_pos, {later, "0h"});
  write_lines(f, lines);

  const Decoded d = decode_file(p, f);
  EXPECT_TRUE(d.info.problems.empty()) << all_errors(d.info.problems);
  const auto& e = d.r.errors;
  EXPECT_TRUE(has(e, "h_total: measured 161 px, expected 160 (2 of 136 lines; first on frame 0, line 56 after the "
                     "vsync leading edge)")) << all_errors(e);
  EXPECT_TRUE(has(e, "h_sync: measured 15 px, expected 16 (1 of 136 lines; first on frame 0, line 57 after the "
                     "vsync leading edge)")) << all_errors(e);
  EXPECT_TRUE(has(e, "h_front_porch: measured 9 px, expected 8 (1 of 128 lines with data; first on frame 0, line 56"))
      << all_errors(e);
  // Line 57 carries active line 51 (57 - 2 sync - 4 back porch lines), sampled where the
  // expected mode puts it: one pixel late, so its last pixel falls in the front porch.
  EXPECT_TRUE(has(e, "no pixel data (BLANK high) at 1 of 16384 active pixels of frame 0, columns 127..127 of lines "
                     "51..51")) << all_errors(e);
  EXPECT_EQ(e.size(), 4u) << all_errors(e);
  EXPECT_GT(scanout_test::rgb_mismatches(d.r.image, p.fb), 0);
  fs::remove_all(f.parent_path());
}

// ---- malformed files: "file:line: what" ----

const char* const kGoodVcd[] = {
    "$timescale 1ps $end",             // 1
    "$scope module video $end",        // 2
    "$var wire 1 h hsync $end",        // 3
    "$var wire 1 v vsync $end",        // 4
    "$var wire 1 k blank $end",        // 5
    "$var wire 8 R code_r [7:0] $end", // 6
    "$var wire 8 G code_g [7:0] $end", // 7
    "$var wire 8 B code_b [7:0] $end", // 8
    "$upscope $end",                   // 9
    "$enddefinitions $end",            // 10
    "#0",                              // 11
    "1h",                              // 12
    "1v",                              // 13
    "1k",                              // 14
    "b0 R",                            // 15
    "b0 G",                            // 16
    "b0 B",                            // 17
    "#1000000",                        // 18
};

struct BadCase {
  int line;                 // 1-based line to replace; 0 = append; negative = delete line -line
  const char* text;
  const char* expected;     // the whole message
};
const BadCase kBad[] = {
    {0, "1q", "bad.vcd:19: value change for identifier 'q', which no $var declares"},
    {0, "#12a", "bad.vcd:19: timestamp '#12a' is not a non-negative integer"},
    {0, "#5", "bad.vcd:19: timestamp #5 goes back in time (the previous one is #1000000)"},
    {0, "b0120 R", "bad.vcd:19: vector value 'b0120': '2' is not 0, 1, x or z"},
    {0, "b101010101 R", "bad.vcd:19: value of 9 bits for identifier 'R', declared 8 bits wide"},
    {0, "r0.5 h", "bad.vcd:19: real value for identifier 'h', declared as bits"},
    {0, "b0101", "bad.vcd:19: vector value change 'b0101' has no identifier"},
    {0, "hello", "bad.vcd:19: 'hello' is not a value change (0/1/x/z, b..., r...), a timestamp (#...) or a $dump section"},
    {0, "$end", "bad.vcd:19: $end without an open $dumpvars/$dumpall/$dumpon/$dumpoff"},
    {6, "$var wire eight R code_r $end", "bad.vcd:6: $var: width 'eight' is not a positive number"},
    {6, "$var wire 8 R $end", "bad.vcd:6: $var: expected 'type width identifier name [range]', got 3 fields"},
    {1, "$timescale 3 ps $end",
     "bad.vcd:1: $timescale: expected 1, 10 or 100 and a unit (s, ms, us, ns, ps, fs), got '3ps'"},
    {3, "$var wire 1 h hsync", "bad.vcd:4: '$var' inside $var (opened on line 3): a $end is missing"},
    {-3, "", "bad.vcd:9: no hsync variable among the $var declarations (names tried: hsync, hsync_o, hs)"},
    {-9, "", "bad.vcd:9: $enddefinitions with $scope video still open"},
    {1, "hello", "bad.vcd:1: 'hello' in the header: expected $timescale, $scope, $var, $upscope, $enddefinitions, ..."},
    {3, "$var real 64 h hsync $end", "bad.vcd:3: video.hsync is declared real, expected bits"},
};

std::string vcd_text(const BadCase& c) {
  std::vector<std::string> v(std::begin(kGoodVcd), std::end(kGoodVcd));
  if (c.line == 0) v.push_back(c.text);
  else if (c.line > 0) v[c.line - 1] = c.text;
  else v.erase(v.begin() + (-c.line - 1));
  std::string s;
  for (auto& l : v) s += l + "\n";
  return s;
}

std::string read_error(const std::string& text, const Panel& p) {
  std::istringstream in(text);
  try {
    read_video_vcd(in, "bad.vcd", p.t, p.dac, [](const VideoSample&) {});
  } catch (const SignalFileError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(SignalReader, MalformedFilesNameFileAndLine) {
  const Panel p;
  EXPECT_EQ(read_error(vcd_text({0, "", ""}), p), "(no error)");  // the base file is good
  for (const BadCase& c : kBad) {
    SCOPED_TRACE(c.text);
    EXPECT_EQ(read_error(vcd_text(c), p), c.expected);
  }
  // Truncations.
  std::string head;
  for (int k = 0; k < 5; ++k) head += std::string(kGoodVcd[k]) + "\n";
  EXPECT_EQ(read_error(head, p), "bad.vcd:5: end of the file before $enddefinitions: not a complete VCD header");
  EXPECT_EQ(read_error("$timescale 1ps $end\n$scope module video\n", p),
            "bad.vcd:2: $scope (opened here) is not closed by $end before the end of the file");
  EXPECT_EQ(read_error("", p), "bad.vcd: empty file: not a VCD");
  std::string defs;
  for (int k = 0; k < 10; ++k) defs += std::string(kGoodVcd[k]) + "\n";
  EXPECT_EQ(read_error(defs, p), "bad.vcd:10: no timestamps (#...) after $enddefinitions: nothing to sample");
  try {
    read_video_signal("/nonexistent/x.vcd", p.t, p.dac, [](const VideoSample&) {});
    ADD_FAILURE() << "no error";
  } catch (const SignalFileError& e) {
    EXPECT_STREQ(e.what(), "/nonexistent/x.vcd: cannot open for reading");
  }
}

TEST(SignalReader, UnknownValuesReported) {
  const Panel p;
  std::string text = vcd_text({0, "", ""});
  text.replace(text.find("\n1h\n"), 4, "\nxh\n");
  std::istringstream in(text);
  long long n = 0;
  const SignalReadInfo info = read_video_vcd(in, "x.vcd", p.t, p.dac, [&](const VideoSample&) { ++n; });
  // #0 .. #1000000 ps at 765.93 ns a pixel clock: samples at (k + 0.5) * 765931.4 ps < 1e6: k = 0 only.
  EXPECT_EQ(n, 1);
  ASSERT_EQ(info.problems.size(), 1u) << all_errors(info.problems);
  EXPECT_EQ(info.problems[0], "video.hsync is x or z at 1 of 1 sampled pixel clocks (first at clock 0), read as 0");
}

// ---- an RTL-style trace: Verilator names (TOP.*, *_o), a clock, codes only, x before the first edge ----

void write_rtl_style_vcd(const Panel& p, const fs::path& f, int frames) {
  std::ofstream os(f);
  os << "$version Verilator $end\n$timescale 1ns $end\n$scope module TOP $end\n"
        "$var wire 1 # clk_i $end\n$var wire 1 $ hsync_o $end\n$var wire 1 % vsync_o $end\n"
        "$var wire 1 & blank_o $end\n$var wire 8 ' dac_r_o [7:0] $end\n$var wire 8 ( dac_g_o [7:0] $end\n"
        "$var wire 8 ) dac_b_o [7:0] $end\n"
        "$scope module scanout_cosim_top $end\n$var wire 1 # clk_i $end\n$var wire 1 $ hsync_o $end\n"
        "$var wire 1 * hsync_q $end\n$upscope $end\n$upscope $end\n$enddefinitions $end\n"
        "#0\n$dumpvars\n0#\nx$\nx%\nx&\nbxxxxxxxx '\nbxxxxxxxx (\nbxxxxxxxx )\n0*\n$end\n";
  auto bits = [](uint16_t v) {
    std::string s;
    for (int b = 7; b >= 0; --b) s += char('0' + (v >> b & 1));
    return s;
  };
  long long k = 0;
  Scanout(p.t, p.dac, p.fb).run(frames, [&](const VideoSample& s) {
    // Edge k at 10 (k + 1) ns launches sample k (100 MHz: not the panel's pixel clock).
    os << '#' << 10 * (k + 1) << "\n1#\n" << s.hsync << "$\n" << s.vsync << "%\n" << s.blank << "&\n";
    const char id[3] = {'\'', '(', ')'};
    for (int c = 0; c < 3; ++c) os << 'b' << bits(s.code[c]) << ' ' << id[c] << '\n';
    os << '#' << 10 * (k + 1) + 5 << "\n0#\n";
    ++k;
  });
}

TEST(SignalReader, RtlStyleTraceWithClockDecodesBitExact) {
  const Panel p;
  const fs::path f = temp_dir() / "rtl.vcd";
  write_rtl_style_vcd(p, f, 2);
  const Decoded d = decode_file(p, f);
  EXPECT_EQ(d.info.clock, "TOP.clk_i");
  EXPECT_EQ(d.info.variables.at("hsync"), "TOP.hsync_o");
  EXPECT_EQ(d.info.levels_from, "code_r/g/b through the DAC");
  EXPECT_EQ(d.info.samples, 2 * 160 * 136);
  EXPECT_NEAR(d.info.sample_clock_hz, 100e6, 1);
  ASSERT_EQ(d.info.notes.size(), 1u);
  EXPECT_NE(d.info.notes[0].find("runs at 100 MHz"), std::string::npos) << d.info.notes[0];
  expect_panel_decoded_exactly(p, d);
  // Ignoring the clock samples at the panel's pixel clock in 1 ns units: wrong, and named.
  const Decoded none = decode_file(p, f, {"none"});
  EXPECT_EQ(none.info.clock, "");
  EXPECT_FALSE(none.r.ok());
  fs::remove_all(f.parent_path());
}

TEST(SignalReader, FstThroughFst2vcd) {
  if (rastsim::find_program("fst2vcd").empty() || rastsim::find_program("vcd2fst").empty())
    GTEST_SKIP() << "fst2vcd/vcd2fst (Debian package gtkwave) not installed";
  const Panel p;
  const fs::path dir = temp_dir();
  p.write_vcd(dir / "panel.vcd", 2);
  rastsim::ProcessOptions quiet;
  quiet.out = quiet.err = rastsim::Sink::Null;
  ASSERT_TRUE(rastsim::run_process({"vcd2fst", (dir / "panel.vcd").string(), (dir / "panel.fst").string()}, quiet).ok());
  const Decoded d = decode_file(p, dir / "panel.fst");
  EXPECT_EQ(d.info.samples, 2 * 160 * 136);
  expect_panel_decoded_exactly(p, d);
  // Not an FST: fst2vcd fails, and the error names the file.
  try {
    decode_file(p, dir / "panel.vcd.fst");
    ADD_FAILURE() << "no error";
  } catch (const SignalFileError& e) {
    EXPECT_NE(std::string(e.what()).find("panel.vcd.fst: cannot open"), std::string::npos) << e.what();
  }
  fs::copy_file(dir / "panel.vcd", dir / "text.fst");
  try {
    decode_file(p, dir / "text.fst");
    ADD_FAILURE() << "no error";
  } catch (const SignalFileError& e) {
    EXPECT_NE(std::string(e.what()).find("text.fst"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace rastsim
