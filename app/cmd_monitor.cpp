// SPDX-License-Identifier: Apache-2.0
// `rastsim monitor`: decode a recorded video signal (.vcd, or .fst through fst2vcd) with
// the virtual monitor set to the config's timing; write the decoded frame and the
// measured timing (the same keys as `rastsim scanout --stats`).
#include <cstdio>
#include <iostream>

#include "common.h"
#include "display/dac.h"
#include "ref/framebuffer.h"
#include "display/monitor.h"
#include "display/signal_reader.h"
#include "config/video_timing.h"
#include "image/image_io.h"
#include "video_json.h"

namespace rastsim::app {

void run_monitor_command(const MonitorOptions& o) {
  const Config cfg = load_config(o.config);
  const DisplayParams display = DisplayParams::resolve(cfg);
  const VideoTiming& t = display.video;
  const Dac dac(display.dac);
  Monitor mon(t, dac.config());
  const SignalReadInfo info =
      read_video_signal(o.signal_path, t, dac, [&](const VideoSample& s) { mon.push(s); }, {o.clock});
  const MonitorResult r = mon.finish();
  std::vector<std::string> errors = info.problems;
  errors.insert(errors.end(), r.errors.begin(), r.errors.end());
  if (!o.out_path.empty() && r.locked) write_image(r.image, o.out_path);

  const VideoTiming& m = r.measured;
  nlohmann::json j = measured_json(r);
  j.update({{"config", cfg.source_name()}, {"signal", o.signal_path}, {"monitor_errors", errors},
            {"notes", info.notes}, {"samples", info.samples},
            {"sample_clock", info.clock.empty() ? "expected pixel clock" : info.clock},
            {"sample_clock_hz", info.sample_clock_hz}, {"timescale", info.timescale},
            {"levels_from", info.levels_from}, {"variables", info.variables}, {"configured", timing_json(t)}});
  j["provenance"] = provenance(o.config, cfg, "");
  if (!o.stats_path.empty()) write_json(o.stats_path, j);
  std::ostream& out = summary_stream(o.stats_path, o.quiet);
  const std::string mode = describe_timing(t).substr(0, describe_timing(t).find(':'));
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "monitor: %s, configured line %.3f kHz, frame %.2f Hz; measured %dx%d total, hsync %d px, "
                "vsync %d lines -> line %.3f kHz, frame %.2f Hz; decoded %d frame%s from %lld samples of ",
                mode.c_str(), t.line_rate_hz() / 1e3, t.frame_rate_hz(), m.h_total, m.v_total, m.h_sync, m.v_sync,
                r.line_rate_hz / 1e3, r.frame_rate_hz, r.frames_decoded, r.frames_decoded == 1 ? "" : "s",
                info.samples);
  if (r.locked) out << buf << o.signal_path << "\n";
  else out << "monitor: " << mode << ": no complete frame in " << info.samples << " samples of " << o.signal_path << "\n";
  for (const auto& n : info.notes) out << "monitor: note: " << n << "\n";
  out.flush();  // the summary first, then the monitor's messages
  for (const auto& e : errors) std::cerr << "monitor: " << e << "\n";
  if (!r.locked && r.frames_decoded == 0)
    std::cerr << "monitor: a frame lies between two vsync leading edges: record at least two frames "
                 "(rastsim scanout --signal-frames 2)\n";
  if (!errors.empty())
    throw std::runtime_error("virtual monitor: " + std::to_string(errors.size()) +
                             (errors.size() == 1 ? " error in " : " errors in ") + o.signal_path + " (above)");
}

void register_monitor(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "monitor", "Decode a recorded video signal (.vcd/.fst) with the virtual monitor set to the config's timing");
  static MonitorOptions o;
  add_config_options(cmd, o.config);
  cmd->add_option("--signal", o.signal_path,
                  "Recorded signal: .vcd (rastsim scanout --signal, or an RTL trace) or .fst (needs gtkwave's fst2vcd); "
                  "at least two vsync pulses (rastsim scanout --signal-frames 2)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", o.out_path, "Decoded frame to write: .png or .ppm");
  cmd->add_option("--stats", o.stats_path, "Write configured and measured timing as JSON ('-' for stdout)");
  cmd->add_option("--clock", o.clock,
                  "Clock variable to sample on (default: one named clk, clk_i, pclk, pixel_clk or clk_pixel if "
                  "present); 'none' samples at the config's pixel clock");
  add_quiet_flag(cmd, o.quiet, "the summary and notes");
  cmd->callback([] { run_monitor_command(o); });
}

}  // namespace rastsim::app
