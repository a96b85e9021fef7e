// SPDX-License-Identifier: Apache-2.0
// `rastsim scanout`: render a scene, scan the framebuffer out through the DAC model,
// decode the signal with the virtual monitor and write the decoded frame and stats.
// `rastsim export-rtl-scanout`: the scan-out RTL's parameter header from a config.
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <vector>

#include "display/signal_reader.h"
#include "common.h"
#include "display/flip_schedule.h"
#include "display/scanout_fetch.h"
#include "fidelity/frames.h"
#include "report/stats_json.h"
#include "display/monitor.h"
#include "ref/pipeline.h"
#include "display/scanout.h"
#include "rtlsim/rtl_params.h"
#include "sc/scanout.h"
#include "scene/scene_io.h"
#include "image/image_io.h"
#include "config/raster_state_config.h"
#include "util/atomic_file.h"
#include "util/process.h"
#include "video_json.h"

namespace rastsim::app {

// Also used by `rastsim monitor` (cmd_monitor.cpp).
nlohmann::json timing_json(const VideoTiming& t) {
  return {{"name", t.name},
          {"h_active", t.h_active}, {"h_front_porch", t.h_front_porch}, {"h_sync", t.h_sync},
          {"h_back_porch", t.h_back_porch}, {"h_total", t.h_total},
          {"v_active", t.v_active}, {"v_front_porch", t.v_front_porch}, {"v_sync", t.v_sync},
          {"v_back_porch", t.v_back_porch}, {"v_total", t.v_total},
          {"h_sync_polarity", t.h_sync_positive ? "positive" : "negative"},
          {"v_sync_polarity", t.v_sync_positive ? "positive" : "negative"},
          {"pixel_clock_hz", t.pixel_clock_hz}, {"line_rate_hz", t.line_rate_hz()},
          {"frame_rate_hz", t.frame_rate_hz()}};
}

// The monitor's measured timing and verdict as stats keys (also `rastsim monitor`).
nlohmann::json measured_json(const MonitorResult& r) {
  const VideoTiming& m = r.measured;
  return {{"h_total", m.h_total}, {"v_total", m.v_total}, {"h_sync", m.h_sync}, {"v_sync", m.v_sync},
          {"h_active", m.h_active}, {"v_active", m.v_active},
          {"h_front_porch", m.h_front_porch}, {"h_back_porch", m.h_back_porch},
          {"v_front_porch", m.v_front_porch}, {"v_back_porch", m.v_back_porch},
          {"line_rate_hz", r.line_rate_hz}, {"frame_rate_hz", r.frame_rate_hz},
          {"frames_decoded", r.frames_decoded}, {"no_data_pixels", r.no_data_pixels},
          {"monitor_errors", r.errors}};
}

namespace {

// Writes the video signal to .vcd, or to .fst through gtkwave's vcd2fst (from a VCD at a
// temporary name); either appears only when complete (util/atomic_file.h).
struct SignalFile {
  std::string path;
  std::unique_ptr<PendingFile> scratch_vcd;  // .fst: the VCD vcd2fst reads, never kept
  std::unique_ptr<VideoVcdWriter> w;
  SignalFile(const std::string& p, const VideoTiming& t, int bits, long long first, long long count) : path(p) {
    const bool fst = p.size() > 4 && p.substr(p.size() - 4) == ".fst";
    if (fst) scratch_vcd = std::make_unique<PendingFile>(p + ".vcd");
    w = std::make_unique<VideoVcdWriter>(fst ? scratch_vcd->path() : p, t.pixel_clock_hz, bits, first, count);
  }
  void close() {
    w->close();
    if (!scratch_vcd) return;
    ProcessOptions po;
    po.out = Sink::Null;
    PendingFile fst(path);
    if (!run_process({"vcd2fst", scratch_vcd->path(), fst.path()}, po).ok())
      throw std::runtime_error(path + ": vcd2fst failed (install gtkwave, or write .vcd)");
    fst.commit();
  }
};

}  // namespace

namespace {

// The part of the signal --signal writes: [first, first + count) pixel clocks.
struct SignalWindow {
  long long first = 0, count = 0;
};

SignalWindow signal_window(const VideoTiming& t, const std::string& lines_arg, int signal_frames) {
  SignalWindow w{0, signal_frames * t.pixels_per_frame()};
  if (lines_arg.empty()) return w;
  int a = 0, n = 0;
  if (std::sscanf(lines_arg.c_str(), "%d:%d", &a, &n) != 2 || a < 0 || n < 1 || a + n > t.v_total)
    throw std::runtime_error("--signal-lines " + lines_arg + ": expected FIRST:COUNT within the " +
                             std::to_string(t.v_total) + " lines of a frame");
  return {static_cast<long long>(a) * t.h_total, static_cast<long long>(n) * t.h_total};
}

// Scans `scanout` out into `sink`: untimed (two frames at least: a picture lies between
// two vsync leading edges), or timed from a raster finish time. Returns the timed
// run's deadline report, null when untimed.
// `memory_underruns`: the lines the memory system's fetch delivered late in the timed
// raster run (--timed with memory.model = "dram"), also sent blank.
nlohmann::json scan_out(const ScanoutOptions& o, const ArchParams& arch, const DisplayParams& display,
                        int64_t raster_cycles, const Scanout& scanout, const SampleSink& sink,
                        const std::vector<int>& memory_underruns) {
  if (raster_cycles < 0) {
    scanout.run(std::max(2, o.signal_frames), sink);
    return nullptr;
  }
  // Timed: vertical blanking, then the frame (one vsync pulse each side of it).
  const auto p = scanout_params(display, arch.timing.core_mhz);
  nlohmann::json deadline =
      sc::run_scanout(p, static_cast<uint64_t>(raster_cycles), &scanout, sink, memory_underruns).to_json();
  if (arch.memory.enabled && o.timed) deadline["memory_underrun_lines"] = memory_underruns.size();
  deadline["buffering"] = arch.config.get_string("scanout.buffering");
  deadline["core_mhz"] = arch.timing.core_mhz;
  return deadline;
}

// The decoded frame against the framebuffer's visible corner (the active area).
struct DecodeCheck {
  long long mismatched = 0;
  int max_err = 0;
  bool same = false;
};

DecodeCheck compare_decoded(const MonitorResult& r, const Framebuffer& fb, const VideoTiming& t) {
  DecodeCheck d;
  for (int y = 0; y < t.v_active && r.locked; ++y)
    for (int x = 0; x < t.h_active; ++x) {
      bool diff = false;
      for (int c = 0; c < 3; ++c) {
        const int e = std::abs(int(r.image.pixel(x, y)[c]) - int(fb.pixel(x, y)[c]));
        d.max_err = std::max(d.max_err, e);
        diff |= e != 0;
      }
      d.mismatched += diff;
    }
  d.same = r.locked && d.mismatched == 0;
  return d;
}

nlohmann::json scanout_stats(const ScanoutOptions& o, const ArchParams& arch, const VideoTiming& t, const Dac& dac,
                             const MonitorResult& r, const DecodeCheck& d, uint32_t crc,
                             const nlohmann::json& deadline) {
  const Config& cfg = arch.config;
  nlohmann::json j = measured_json(r);
  j.update({
      {"config", cfg.source_name()}, {"scene", o.scene_path},
      {"decoded_equals_framebuffer", d.same}, {"mismatched_pixels", d.mismatched}, {"max_code_error", d.max_err},
      {"configured", timing_json(t)},
      {"dac", {{"bits", dac.config().bits}, {"full_scale_volts", dac.config().full_scale_volts},
               {"inl_lsb", dac.config().inl_lsb}, {"dnl_lsb", dac.config().dnl_lsb},
               {"lut", cfg.get_string("dac.lut")}}},
      {"framebuffer_crc32", crc32_hex(crc)}});
  if (!deadline.is_null()) j["deadline"] = deadline;
  j["provenance"] = provenance(o.config, cfg, o.scene_path);
  add_obj_ignored(j, o.scene_path, arch.placement.camera);
  return j;
}

void print_summary(std::ostream& out, const VideoTiming& t, const MonitorResult& r, const DecodeCheck& d,
                   const nlohmann::json& deadline) {
  const VideoTiming& m = r.measured;
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "scanout: %s, configured line %.3f kHz, frame %.2f Hz; measured %dx%d total, hsync %d px, "
                "vsync %d lines -> line %.3f kHz, frame %.2f Hz; decoded frame %s the framebuffer%s\n",
                describe_timing(t).substr(0, describe_timing(t).find(':')).c_str(), t.line_rate_hz() / 1e3,
                t.frame_rate_hz(), m.h_total, m.v_total, m.h_sync, m.v_sync, r.line_rate_hz / 1e3,
                r.frame_rate_hz, d.same ? "equals" : "differs from",
                d.same ? "" : (" (" + std::to_string(d.mismatched) + " pixels, max error " + std::to_string(d.max_err) + ")").c_str());
  out << buf;
  if (!deadline.is_null())
    out << "scanout: raster finishes at " << deadline["frame_time_cycles"] << " cycles, deadline "
              << deadline["deadline_cycles"] << " cycles (" << deadline["buffering"].get<std::string>()
              << " buffering): " << (deadline["frame_deadline_met"].get<bool>() ? "met" : "MISSED") << ", "
              << deadline["underrun_lines"] << " underrun lines\n";
}

// ---- Multi-frame traces: flips at vertical blank (display/flip_schedule.h) ----

// Each frame's image (resolved), from the reference model, frame by frame.
std::vector<Framebuffer> frame_images(const Scene& scene, const ArchParams& arch) {
  std::vector<Framebuffer> images;
  RenderStats stats;
  fidelity::FrameRenderer r(arch, stats, [&](const fidelity::FrameCounts&, const Framebuffer& fb) {
    images.push_back(fb.samples > 1 ? fb.resolve() : fb);
  });
  r.feed(scene.commands);
  r.finish();
  return images;
}

// The signal of every display period of `fs` (its vertical blanking, then its active
// lines from the frame it shows; `initial` before frame 0's flip), then one more
// blanking, whose vsync closes the last period for the monitor.
void scan_periods(const VideoTiming& t, const Dac& dac, const FlipSchedule& fs, const std::vector<Framebuffer>& images,
                  const Framebuffer& initial, const SampleSink& sink) {
  const auto lines = [&](const Framebuffer& fb, int from, int to) {
    const Scanout s(t, dac, fb);
    for (int v = from; v < to; ++v)
      for (int h = 0; h < t.h_total; ++h) sink(s.sample(h, v));
  };
  for (const int k : fs.shown) {
    const Framebuffer& fb = k < 0 ? initial : images[size_t(k)];
    lines(fb, t.v_active, t.v_total);
    lines(fb, 0, t.v_active);
  }
  lines(initial, t.v_active, t.v_total);
}

// `scanout` of a trace of more than one frame: the flip schedule (each frame's cycles
// from a `simulate --frames k:k+1` child with --timed; untimed, every frame takes 0 cycles and flips at
// the next vertical blank), the periods scanned out and decoded, each decoded period
// checked against the frame it shows; -o a pattern: one image a period.
void run_scanout_frames(const ScanoutOptions& o, const ArchParams& arch, const DisplayParams& display,
                        const Scene& scene) {
  if (o.raster_cycles >= 0)
    throw std::runtime_error("--raster-cycles is one frame's finish time: a multi-frame trace takes each frame's "
                             "cycles from --timed (or, untimed, flips every frame at the next vertical blank)");
  if (!o.signal_path.empty()) throw std::runtime_error("--signal: a multi-frame scan-out writes no signal yet: drop it");
  if (arch.config.get_string("scanout.buffering") != "double")
    throw ConfigError(arch.config.origin("scanout.buffering") + ": a multi-frame trace is shown with " +
                      "scanout.buffering = \"double\" (flips at vertical blank); single buffering would show "
                      "frames half drawn");
  const VideoTiming& t = display.video;
  const Dac dac(display.dac);
  const std::vector<Framebuffer> images = frame_images(scene, arch);
  std::vector<uint64_t> cycles(images.size(), 0);
  // Each frame alone, from an empty pipeline to its drain (the present waits for the
  // flip, so the next frame starts after it): `simulate --frames k:k+1`, a child each.
  for (size_t k = 0; o.timed && k < cycles.size(); ++k) {
    const std::string range = std::to_string(k) + ":" + std::to_string(k + 1);
    cycles[k] = simulate_in_child(o.config, o.scene_path, {"--frames", range}).at("cycles").get<uint64_t>();
  }
  const ScanoutParams sp = scanout_params(display, arch.timing.core_mhz);
  const FlipSchedule fs = vsync_flips(cycles, sp.core_hz * scanout_frame_period_s(t));
  Monitor mon(t, dac.config());
  mon.keep_images(true);
  const Framebuffer initial(arch.raster.fb_width, arch.raster.fb_height);
  scan_periods(t, dac, fs, images, initial, [&](const VideoSample& s) { mon.push(s); });
  const MonitorResult r = mon.finish();
  nlohmann::json periods = nlohmann::json::array();
  size_t wrong = 0;
  for (size_t n = 0; n < fs.shown.size(); ++n) {
    const int k = fs.shown[n];
    MonitorResult one;  // the period's decoded image alone, for compare_decoded
    one.locked = r.locked;
    one.image = n < r.images.size() ? r.images[n] : Framebuffer(t.h_active, t.v_active);
    const DecodeCheck d = compare_decoded(one, k < 0 ? initial : images[size_t(k)], t);
    const bool same = n < r.images.size() && d.same;
    wrong += !same;
    periods.push_back({{"period", n}, {"frame", k}, {"decoded_equals_frame", same}, {"mismatched_pixels", d.mismatched}});
    if (fidelity::is_frame_pattern(o.out_path)) write_image(one.image, fidelity::frame_image_path(o.out_path, n));
  }
  if (!fidelity::is_frame_pattern(o.out_path)) write_image(r.image, o.out_path);
  nlohmann::json j = measured_json(r);
  j.update(fs.to_json());
  j.update({{"config", arch.config.source_name()}, {"scene", o.scene_path}, {"frames_total", images.size()},
            {"display_periods", periods}, {"timed", o.timed}, {"decoded_equals_frames", wrong == 0},
            {"configured", timing_json(t)}, {"provenance", provenance(o.config, arch.config, o.scene_path)}});
  if (!o.stats_path.empty()) write_json(o.stats_path, j);
  std::ostream& out = summary_stream(o.stats_path, o.quiet);
  out << "scanout: " << images.size() << " frames in " << fs.shown.size() << " display periods (flips at vertical "
      << "blank, double buffering" << (o.timed ? ", frames timed by simulate" : ", untimed") << "): shown";
  for (const int k : fs.shown) out << " " << k;
  out << "; " << fs.shown.size() - wrong << " of " << fs.shown.size() << " decoded periods equal their frame\n";
  out.flush();
  for (const auto& e : r.errors) std::cerr << "scanout: monitor: " << e << "\n";
  if (!r.ok()) throw std::runtime_error("virtual monitor: " + std::to_string(r.errors.size()) + " timing errors (above)");
  if (wrong) throw std::runtime_error(std::to_string(wrong) + " display periods do not show their frame");
}

void add_scanout_options(CLI::App* cmd, ScanoutOptions& o) {
  add_config_options(cmd, o.config);
  add_scene_option(cmd, o.scene_path);
  cmd->add_option("-o,--output", o.out_path,
                  "Decoded frame to write: .png or .ppm; a multi-frame trace (flips at vertical blank): the last "
                  "period's, or with out_%04d.png one image a display period (docs/scanout.md)")
      ->required();
  cmd->add_option("--signal", o.signal_path,
                  "Write the video signal (hsync, vsync, blank, codes, levels in V) of the first frame (see --signal-frames): .vcd or .fst");
  auto* lines_opt = cmd->add_option("--signal-lines", o.lines_arg, "Only lines FIRST..FIRST+COUNT-1 of the first frame in --signal")
      ->type_name("FIRST:COUNT");
  cmd->add_option("--signal-frames", o.signal_frames,
                  "Write the first N frames in --signal (default 1); `rastsim monitor` needs 2 to decode a frame "
                  "(with --raster-cycles: at most the timed run)")
      ->check(CLI::PositiveNumber)
      ->excludes(lines_opt);
  cmd->add_option("--stats", o.stats_path, "Write configured and measured timing and the decode check as JSON ('-' for stdout)");
  auto* cycles_opt = cmd->add_option("--raster-cycles", o.raster_cycles,
                  "Raster pipeline finish time in core cycles (`rastsim simulate` stats: cycles): run the timed "
                  "scan-out (model/sc) from the start of vertical blanking at clock.core_mhz, report the deadline "
                  "check and decode its signal, underruns included")
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--timed", o.timed,
                "Take the raster finish time from the SystemC pipeline on this scene and config (a "
                "`rastsim simulate` child process), then run the timed scan-out as with --raster-cycles; with "
                "memory.model = \"dram\" the lines that child's DRAM line fetch delivered late (competing with "
                "the ROP; its scanout_underrun_lines) are sent blank too (deadline.memory_underrun_lines)")
      ->excludes(cycles_opt);
  add_quiet_flag(cmd, o.quiet, "the summary");
}

}  // namespace

void run_scanout_command(const ScanoutOptions& o) {
  const ArchParams arch = resolve_arch(o.config, o.scene_path);
  const DisplayParams display = DisplayParams::resolve(arch.config);  // faults in the timing keys stop here
  const VideoTiming& t = display.video;
  const Dac dac(display.dac);
  const Scene scene = load_scene(o.scene_path, arch.placement);
  if (fidelity::frame_spans(scene.commands).size() > 1) return run_scanout_frames(o, arch, display, scene);
  RenderStats rstats;
  const Framebuffer fb = render_scene(scene, arch.raster, rstats);

  const SignalWindow win = signal_window(t, o.lines_arg, o.signal_frames);
  std::unique_ptr<SignalFile> sig;
  if (!o.signal_path.empty()) sig = std::make_unique<SignalFile>(o.signal_path, t, dac.config().bits, win.first, win.count);
  Monitor mon(t, dac.config());
  auto sink = [&](const VideoSample& s) {
    mon.push(s);
    if (sig) sig->w->push(s);
  };
  const Scanout scanout(t, dac, fb);
  int64_t raster_cycles = o.raster_cycles;
  std::vector<int> memory_underruns;  // with memory.model = "dram": the DRAM fetch's late lines
  if (o.timed) {
    const nlohmann::json sim = simulate_in_child(o.config, o.scene_path);
    raster_cycles = sim.at("cycles").get<int64_t>();
    const nlohmann::json::json_pointer lines("/memory/clients/scanout/underrun_line_list");
    if (sim.contains(lines)) memory_underruns = sim.at(lines).get<std::vector<int>>();
  }
  const nlohmann::json deadline = scan_out(o, arch, display, raster_cycles, scanout, sink, memory_underruns);
  if (sig) sig->close();
  const MonitorResult r = mon.finish();
  write_image(r.image, o.out_path);

  const DecodeCheck d = compare_decoded(r, fb, t);
  if (!o.stats_path.empty()) write_json(o.stats_path, scanout_stats(o, arch, t, dac, r, d, rstats.framebuffer_crc32, deadline));
  std::ostream& out = summary_stream(o.stats_path, o.quiet);
  print_summary(out, t, r, d, deadline);
  out.flush();  // the summary first, then the monitor's messages
  for (const auto& e : r.errors) std::cerr << "scanout: monitor: " << e << "\n";
  if (!r.ok()) throw std::runtime_error("virtual monitor: " + std::to_string(r.errors.size()) + " timing errors (above)");
}

void register_scanout(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "scanout", "Render a scene, scan it out through the video DAC, decode it with the virtual monitor");
  static ScanoutOptions opts;
  add_scanout_options(cmd, opts);
  cmd->callback([] { run_scanout_command(opts); });

  auto* exp = app.add_subcommand("export-rtl-scanout",
                                 "Write the scan-out RTL's parameters (Verilog parameter list) from a config");
  static ConfigOptions eopts;
  static std::string vh_path;
  static bool quiet = false;  // the header is the output: nothing else is printed
  add_config_options(exp, eopts);
  exp->add_option("-o,--output", vh_path, "Verilog header to write ('-' for stdout)")->required();
  add_quiet_flag(exp, quiet, "anything but the header");
  exp->callback([] {
    const Config cfg = load_config(eopts);
    const std::string text = scanout_rtl_params_verilog(scanout_rtl_params(ArchParams::resolve(cfg), DisplayParams::resolve(cfg)), cfg.source_name());
    if (vh_path == "-") {
      std::cout << text;
      return;
    }
    AtomicFile f(vh_path);
    f.stream() << text;
    f.commit();
  });
}

}  // namespace rastsim::app
