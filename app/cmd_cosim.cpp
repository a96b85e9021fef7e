// SPDX-License-Identifier: Apache-2.0
// `rastsim cosim`: the verilated RTL (rtl/rast_top.sv) on one scene, every fragment
// compared with the reference model, and its cycle count next to the SystemC model's.
// Any valid config: a shipped model when one fits, else one built on demand into the
// cache (model/rtlsim/rtl_cache.h; --rtl-build-only builds it and stops).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "common.h"
#include "fidelity/frame_sampled.h"
#include "frame_output.h"
#include "report/stats_json.h"
#include "ref/pipeline.h"
#include "rtlsim/cosim.h"
#include "rtlsim/rtl_cache.h"
#include "rtlsim/stage_compare.h"
#include "sc/raster_pipeline.h"
#include "scene/scene_io.h"
#include "timing/dram_trace.h"

namespace rastsim::app {

namespace {

// `rastsim rtl-cache`: the on-demand RTL models (model/rtlsim/rtl_cache.h), listed or removed.
void register_rtl_cache(CLI::App& app) {
  auto* cmd = app.add_subcommand("rtl-cache", "List (or --clean) the RTL models `cosim` built on demand");
  static bool clean = false, quiet = false;
  cmd->add_flag("--clean", clean,
                "Remove every entry (a model another process is building is left alone); the next cosim of such a "
                "config builds it again");
  add_quiet_flag(cmd, quiet, "the listing or the count removed");
  cmd->callback([] {
    const std::string dir = rastsim_cache_dir("rtl");
    std::ostream& out = summary_stream("", quiet);
    if (clean) {
      out << "rtl-cache: removed " << clean_rtl_cache() << " entries from " << dir << "\n";
      return;
    }
    const auto entries = rtl_cache_entries();
    out << "rtl-cache: " << entries.size() << " entries in " << dir << "\n";
    for (const RtlCacheEntry& e : entries)
      out << e.key << "  built in " << int(e.build_seconds + 0.5) << " s  for " << e.built_for << "\n";
  });
}

// Per stage (docs/microarchitecture.md "Stage statistics"): both sides' busy, stalled and
// starved cycles into the stats and a table on `out`; --trace-diff's CSVs.
void report_stages(const std::vector<rtlsim::StageAgreement>& a, const std::string& trace_dir, nlohmann::json& j,
                   std::ostream& out) {
  // Merged into stages.<name> (with --simulate-stats the SystemC model's own keys are there).
  j["stages"].update(rtlsim::stages_json(a), /*merge_objects=*/true);
  out << "cosim: stage           busy model / RTL   error   stalled model / RTL   starved model / RTL\n";
  for (const rtlsim::StageAgreement& s : a) {
    char line[200];
    std::snprintf(line, sizeof line, "cosim: %-14s %10llu / %-10llu %6.2f %% %9llu / %-9llu %9llu / %llu\n",
                  s.name.c_str(), (unsigned long long)s.model.busy, (unsigned long long)s.rtl.busy,
                  s.busy_error * 100, (unsigned long long)s.model.stalled, (unsigned long long)s.rtl.stalled,
                  (unsigned long long)s.model.starved, (unsigned long long)s.rtl.starved);
    out << line;
  }
  if (const rtlsim::StageAgreement* w = rtlsim::worst_stage(a)) {
    j["stage_worst_busy_error"] = w->busy_error;
    j["stage_worst"] = w->name;
  }
  if (trace_dir.empty()) return;
  const rtlsim::TraceDiff d = rtlsim::write_trace_diff(trace_dir, a);
  j["trace_diff"] = {{"rows_model", d.rows_model}, {"rows_rtl", d.rows_rtl}, {"first", d.first}, {"earliest", d.earliest}};
  out << "cosim: trace-diff " << trace_dir << "/model.csv (" << d.rows_model << " rows), " << trace_dir
            << "/rtl.csv (" << d.rows_rtl << " rows): "
            << (d.differs ? "first difference: " + d.first + "; earliest: " + d.earliest : std::string("identical"))
            << "\n";
}

// --trace-diff with memory.model = "dram": DIR/model_mem.trace and DIR/rtl_mem.trace (every
// DRAM burst in the order it entered, DRAMsim3's format: address, READ/WRITE, DRAM clock)
// and the first burst that differs in address, direction or arrival clock.
void report_mem_traces(const std::string& dir, nlohmann::json& j, std::ostream& out) {
  const auto read = [](const std::string& path) {
    std::ifstream in(path);
    return read_dram_trace(in, path);
  };
  const std::vector<DramTraceLine> m = read(dir + "/model_mem.trace"), r = read(dir + "/rtl_mem.trace");
  const auto line = [](const std::vector<DramTraceLine>& v, size_t k) {
    if (k >= v.size()) return std::string("none");
    char s[80];
    std::snprintf(s, sizeof s, "0x%llx %s at DRAM clock %llu", (unsigned long long)v[k].address,
                  v[k].write ? "WRITE" : "READ", (unsigned long long)v[k].clock);
    return std::string(s);
  };
  size_t k = 0;
  while (k < m.size() && k < r.size() && m[k].address == r[k].address && m[k].write == r[k].write &&
         m[k].clock == r[k].clock)
    ++k;
  const bool same = k == m.size() && k == r.size();
  j["trace_diff"]["mem_bursts_model"] = m.size();
  j["trace_diff"]["mem_bursts_rtl"] = r.size();
  if (!same) j["trace_diff"]["mem_first"] = {{"burst", k}, {"model", line(m, k)}, {"rtl", line(r, k)}};
  out << "cosim: trace-diff " << dir << "/model_mem.trace (" << m.size() << " bursts), " << dir << "/rtl_mem.trace ("
      << r.size() << " bursts): "
      << (same ? std::string("identical")
               : "first difference: burst " + std::to_string(k) + ": model " + line(m, k) + ", RTL " + line(r, k))
      << "\n";
}

// The options of one `rastsim cosim` (register_cosim).
struct CosimCommand {
  ConfigOptions config;
  std::string scene_path, stats_path, trace_diff_dir;
  std::string frames;  // --frames A:B ("" = every frame; frames[] when the scene has more than one)
  rtlsim::CosimOptions run;
  bool no_model = false, build_only = false, simulate_stats = false, quiet = false;
  double max_error = -1;
};

// --rtl-build-only: the config's model, shipped or built into the cache.
void build_rtl_model(const ArchParams& arch, const rtlsim::CosimOptions& co, std::ostream& out) {
  const rtlsim::RtlModelChoice m = rtlsim::prepare_rtl_model(arch, co);
  out << "cosim: RTL model " << m.name
            << (m.dir.empty() ? " (shipped)" : (m.cache_hit ? " (in the cache: " : " (built: ") + m.dir + ")") << "\n";
}

// The RTL run's summary lines; the stress seed whenever a stress was on.
void print_rtl_run(const rtlsim::CosimResult& r, const rtlsim::CosimOptions& co, std::ostream& out) {
  if (!r.rtl_model_dir.empty())
    out << "cosim: on-demand RTL model " << r.rtl_model_dir
              << (r.rtl_cache_hit ? " (cache hit)" : " (built in " + std::to_string(r.rtl_build_seconds) + " s)")
              << "\n";
  out << "cosim: RTL model " << r.rtl_config << ", " << r.triangles << " triangles, " << r.cycles_rtl
            << " cycles (" << r.wall_seconds << " s wall), " << r.fragments_compared << " fragments compared, "
            << r.mismatches << " mismatches";
  if (r.commands_2d) out << ", " << r.commands_2d << " 2D commands (" << r.pixels_2d << " pixels)";
  if (r.hiz) out << ", Hi-Z: " << r.tiles_culled_hiz << " tiles culled, " << r.tiles_accepted_hiz << " accepted";
  if (r.hiz_lagged)
    out << " (lagged: " << r.hiz_lagged_tiles_drawn << " tiles the reference culled drawn, "
        << r.hiz_lagged_fragments_drawn << " fragments)";
  if (r.depth_early) out << ", early Z: " << r.fragments_culled_early << " fragments culled";
  if (r.hiz && r.hiz_dram_bytes_read + r.hiz_dram_bytes_written > 0)
    out << ", spilled entries " << r.hiz_dram_bytes_read << " bytes read, " << r.hiz_dram_bytes_written << " written";
  out << ", crc32 " << crc32_hex(r.crc_rtl)
            << (r.crc_rtl == r.crc_ref ? " (= reference)" : " (reference " + crc32_hex(r.crc_ref) + ")");
  if (co.backpressure > 0 || co.valid_gaps > 0) {
    out << " (backpressure " << co.backpressure;
    if (co.valid_gaps > 0) out << ", valid gaps " << co.valid_gaps;
    out << ", seed " << co.stress_seed << ")";
  }
  out << "\n";
  if (!r.first_mismatch.empty()) out << "cosim: first mismatch: " << r.first_mismatch << "\n";
}

// The SystemC model on the same scene: its cycles and error into `j` (with
// --simulate-stats its whole stats under simulate's names), the per-stage comparison.
// With frames (a multi-frame scene, --frames): it starts from their framebuffer, and
// `frame_cycles` gets each frame's cycles.
void compare_with_model(const Scene& scene, const ArchParams& arch, const CosimCommand& c, const rtlsim::CosimResult& r,
                        const CosimFrames* frames, std::vector<uint64_t>& frame_cycles, nlohmann::json& j,
                        std::ostream& out) {
  sc::SimOptions so;
  so.spans = !c.trace_diff_dir.empty();
  if (!c.run.mem_trace_path.empty()) so.mem_trace_path = c.trace_diff_dir + "/model_mem.trace";
  std::vector<uint64_t> starts;
  if (frames) {
    so.initial_fb = &frames->before;
    so.on_fetch = fidelity::record_command_starts(scene, starts);
  }
  const sc::SimResult m = sc::simulate_scene(scene, arch, so);
  if (frames) frame_cycles = slice_cycles(frames->slice, starts, m.cycles);
  const double err = r.cycles_rtl ? (double(m.cycles) - double(r.cycles_rtl)) / double(r.cycles_rtl) : 0.0;
  j["cycles_model"] = m.cycles;
  j["cycle_error"] = err;
  j["model_wall_seconds"] = m.sim_wall_seconds;
  if (c.simulate_stats) {
    // The SystemC figures under simulate's names, the RTL's beside them (cosim's own
    // names win where both have one: config, scene).
    nlohmann::json s = m.to_json();
    s["fidelity_level"] = "systemc";
    s.update(j);
    j = s;
  }
  out << "cosim: cycles_rtl " << r.cycles_rtl << ", cycles_model " << m.cycles << ", error "
            << std::round(err * 10000) / 100 << " %\n";
  if (r.hiz) {  // the SystemC model's Hi-Z decisions beside the RTL's (lagged: each its own timing's)
    const uint64_t culled = m.render.hiz.tiles_culled, accepted = m.render.hiz.tiles_accepted;
    j["tiles_culled_hiz_model"] = culled;
    j["tiles_accepted_hiz_model"] = accepted;
    out << "cosim: Hi-Z tiles culled / accepted: RTL " << r.tiles_culled_hiz << " / " << r.tiles_accepted_hiz
        << ", SystemC " << culled << " / " << accepted
        << (culled == r.tiles_culled_hiz && accepted == r.tiles_accepted_hiz ? " (equal)" : " (differ)") << "\n";
  }
  report_stages(rtlsim::compare_stages(rtlsim::stage_records(m.stages), r.stages), c.trace_diff_dir, j, out);
  if (!c.run.mem_trace_path.empty()) report_mem_traces(c.trace_diff_dir, j, out);
}

// frames[] of a multi-frame run: each frame's RTL and SystemC cycles and its fragment
// mismatches (the framebuffer check's and any unattributed ones counted on the last
// frame, whose image it checks), and a line a frame on `out`.
void report_frames(CosimFrames& frames, const rtlsim::CosimResult& r, const std::vector<uint64_t>& model,
                   nlohmann::json& j, std::ostream& out) {
  const std::vector<uint64_t> rtl = slice_cycles(frames.slice, r.command_starts, r.cycles_rtl);
  const std::vector<fidelity::FrameSpan> spans = fidelity::frame_spans(frames.slice.scene.commands);
  std::vector<uint64_t> bad(rtl.size(), 0);
  uint64_t attributed = 0;
  for (size_t k = 0, first = spans.size() - rtl.size(); k < rtl.size(); ++k)
    for (size_t i = spans[first + k].begin; i < spans[first + k].end; ++i) {
      bad[k] += r.command_mismatches.at(i);
      attributed += r.command_mismatches[i];
    }
  if (!bad.empty()) bad.back() += r.mismatches - attributed;
  frames.add_to(j, rtl, model, bad);
  uint64_t sum = 0;
  for (const uint64_t v : rtl) sum += v;
  j["cycles_rtl_frames"] = sum;  // the frames' cycles: cycles_rtl less the carried state commands before them
  for (const nlohmann::json& f : j["frames"]) {
    out << "cosim: frame " << f["frame"].get<size_t>() << ": cycles_rtl " << f["cycles_rtl"].get<uint64_t>();
    if (f.contains("cycles_model")) out << ", cycles_model " << f["cycles_model"].get<uint64_t>();
    out << ", " << f["mismatches"].get<uint64_t>() << " mismatches\n";
  }
}

// One `rastsim cosim` run: the RTL against the reference, then (unless --no-model) the
// SystemC model; the stats, and the failures --max-error and a mismatch make.
void run_cosim_command(CosimCommand& c) {
  const ArchParams arch = resolve_arch(c.config, c.scene_path);
  std::ostream& out = summary_stream(c.stats_path, c.quiet);
  if (c.quiet) c.run.progress = [](const std::string&) {};  // an on-demand build's progress lines too
  if (c.build_only) {
    build_rtl_model(arch, c.run, out);
    return;
  }
  if (c.scene_path.empty()) throw std::runtime_error("cosim: --scene is required (unless --rtl-build-only)");
  if (c.simulate_stats && c.no_model)
    throw std::runtime_error("cosim: --simulate-stats needs the SystemC model (drop --no-model)");
  const Scene whole = load_scene(c.scene_path, arch.placement);
  if (!c.trace_diff_dir.empty() && c.no_model)
    throw std::runtime_error("--trace-diff needs the SystemC model (drop --no-model)");
  c.run.record_transactions = !c.trace_diff_dir.empty();
  if (!c.trace_diff_dir.empty() && arch.memory.enabled) {
    std::filesystem::create_directories(c.trace_diff_dir);
    c.run.mem_trace_path = c.trace_diff_dir + "/rtl_mem.trace";
  }
  // A multi-frame scene or --frames: the range's commands, from the framebuffer the
  // frames before it leave (replayed by the reference model), per-frame figures.
  std::unique_ptr<CosimFrames> frames;
  if (!c.frames.empty() || fidelity::frame_spans(whole.commands).size() > 1) {
    frames = std::make_unique<CosimFrames>(whole, arch, c.frames);
    if (frames->out.range.first > 0) c.run.initial_fb = &frames->before;
    c.run.reference_fb = &frames->reference;
  }
  const Scene& scene = frames ? frames->slice.scene : whole;
  const rtlsim::CosimResult r = rtlsim::run_cosim(scene, arch, c.run);
  nlohmann::json j = r.to_json(c.run);
  j["config"] = arch.config.source_name();
  j["scene"] = c.scene_path;
  j["provenance"] = provenance(c.config, arch.config, c.scene_path);
  add_obj_ignored(j, c.scene_path, arch.placement.camera);
  print_rtl_run(r, c.run, out);
  std::vector<uint64_t> model_frames;
  if (!c.no_model) compare_with_model(scene, arch, c, r, frames.get(), model_frames, j, out);
  if (frames) report_frames(*frames, r, model_frames, j, out);
  if (!c.stats_path.empty()) write_json(c.stats_path, j);
  if (!c.no_model && c.max_error >= 0 && std::abs(j["cycle_error"].get<double>()) > c.max_error)
    throw std::runtime_error("cycle error of the SystemC model exceeds " + std::to_string(c.max_error));
  if (r.mismatches) throw std::runtime_error(std::to_string(r.mismatches) + " mismatches (fragments or framebuffer)");
}

// The stress and waveform options of the RTL run.
void add_rtl_run_options(CLI::App* cmd, rtlsim::CosimOptions& co) {
  cmd->add_option("--fst", co.fst_path, "Write an FST waveform of the RTL");
  cmd->add_option("--backpressure", co.backpressure,
                  "Probability that the memory refuses the ROP's or the 2D engine's request (rd_ready_i, wr_ready_i low) in a "
                  "cycle, and delays the 2D engine's read response a cycle (random, seeded by --seed; changes cycles_rtl)")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--valid-gaps", co.valid_gaps,
                  "Probability that the testbench holds an offered triangle (tri_valid_i) or 2D operation "
                  "(in_valid_i) back in a cycle (random, seeded by --seed; changes cycles_rtl)")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--seed", co.stress_seed,
                  "Seed of every random choice of the run: the backpressure and valid gaps (printed; the same seed "
                  "replays the run)")
      ->capture_default_str();
  cmd->add_option("--rtl-model", co.rtl_model,
                  "Run this verilated model: a shipped config's name (default, d3d11, embedded, desktop) or "
                  "default_circuit, the default config with rast_divider as the circuit Yosys synthesises instead "
                  "of the simulation form the other models use (docs/rtl.md); it must fit the config");
}

}  // namespace

void register_cosim(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "cosim", "Co-simulate the Verilog RTL against the reference model (fragments) and the SystemC model (cycles)");
  static CosimCommand c;
  add_config_options(cmd, c.config);
  add_scene_option(cmd, c.scene_path);
  cmd->get_option("--scene")->required(false);  // not with --rtl-build-only (checked below)
  add_rtl_run_options(cmd, c.run);
  add_frames_option(cmd, c.frames);
  cmd->add_option("--stats", c.stats_path,
                  "Write cycles_rtl, cycles_model, cycle_error, fragments_compared, mismatches, per stage "
                  "stages.<name>.{busy,stalled,starved}_{rtl,model} and busy_error, stage_worst_busy_error, ...; "
                  "where a texture was sampled helper_pixels, texel_fetches, texture_cache_hits and "
                  "texture_cache_misses (docs/texture.md \"RTL\"); with memory.model = \"dram\" the RTL run's memory keys under simulate's names (dram_bytes_read, "
                  "dram_bytes_written, rop_*_cache_hits / _misses, fast_clear_blocks, depth_compressed_bytes, "
                  "dram_row_hit_rate, dram_bandwidth_utilisation, memory.dram.*, memory.clients.<client>.*; "
                  "docs/memory.md); a multi-frame trace (or --frames) also frames[].{cycles_rtl, cycles_model, "
                  "cycle_error, mismatches} and cycles_rtl_frames, as JSON ('-' for stdout)");
  cmd->add_option("--max-error", c.max_error,
                  "Fail when |cycles_model - cycles_rtl| / cycles_rtl exceeds this (e.g. 0.05; default: report only)");
  cmd->add_flag("--no-model", c.no_model, "Do not run the SystemC model (fragment check only)");
  cmd->add_flag("--rtl-build-only", c.build_only,
                "Only make sure the config's RTL model exists: a shipped one, else build it into the cache "
                "($RASTSIM_CACHE/rtl, else ~/.cache/rastsim/rtl; docs/rtl.md) and print where; no scene needed");
  cmd->add_flag("--simulate-stats", c.simulate_stats,
                "With --stats: the SystemC model's whole stats (as `simulate --stats`: cycles, stages.*, ...) with "
                "cycles_rtl, mismatches, cycle_error and the RTL model's keys beside them (a `sweep --level cosim` "
                "row)");
  add_quiet_flag(cmd, c.quiet, "the RTL run's summary, the cycle comparison or the stage table");
  cmd->add_option("--trace-diff", c.trace_diff_dir,
                  "Write DIR/model.csv and DIR/rtl.csv: every stage's transactions (stage,transaction,start_cycle,"
                  "end_cycle) on both sides in the same row order, and print the first whose timing differs; with "
                  "memory.model = \"dram\" also DIR/model_mem.trace and DIR/rtl_mem.trace, every DRAM burst as it "
                  "entered (DRAMsim3's format: address, READ/WRITE, DRAM clock), and the first burst that differs");
  cmd->callback([] { run_cosim_command(c); });
  register_rtl_cache(app);  // its cache's listing, next to it in --help
}

}  // namespace rastsim::app
