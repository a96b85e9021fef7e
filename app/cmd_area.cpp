// SPDX-License-Identifier: Apache-2.0
// `rastsim area`: the RTL built with a config's exported parameters, synthesised with
// Yosys into generic gates (model/rtlsim/area.h): cells, flip-flops and the CMOS transistor
// estimate of each stage module and of the whole design, cached per parameter set.
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <iomanip>
#include <iostream>

#include "common.h"
#include "rtlsim/area.h"

namespace rastsim::app {

namespace {

// Yosys' progress on stderr: one rewritten status line on a terminal, else one line a pass.
std::function<void(const std::string&)> progress_printer(bool quiet) {
  if (quiet) return {};
  const bool tty = isatty(2);
  return [tty](const std::string& line) {
    if (tty) std::cerr << "\r\033[Karea: " << line << std::flush;
    else std::cerr << "area: " << line << "\n";
  };
}

void print_table(std::ostream& os, const AreaReport& r) {
  os << std::left << std::setw(22) << "module" << std::right << std::setw(6) << "inst" << std::setw(12) << "cells"
     << std::setw(12) << "flip-flops" << std::setw(14) << "transistors" << "\n";
  const auto row = [&](const std::string& name, const AreaCounts& c, bool inst) {
    os << std::left << std::setw(22) << name << std::right << std::setw(6) << (inst ? std::to_string(c.instances) : "")
       << std::setw(12) << c.cells << std::setw(12) << c.flip_flops << std::setw(14) << c.transistors << "\n";
  };
  for (const auto& [name, c] : r.stages) row(name, c, true);
  for (const StorageArray& a : r.storage) {
    const int overflow = std::max(0, int(a.name.size()) - 22);  // a long name takes from the blank columns
    os << std::left << std::setw(22) << a.name << std::right << std::setw(44 - overflow) << a.transistors << "  " << a.bits
       << " bits, " << (a.sram ? "SRAM" : "flip-flops") << " (counted, not synthesised)\n";
  }
  row("total", r.total, false);
  os << "cells by type (total):";
  for (const auto& [type, n] : r.total.cells_by_type) os << " " << type << " " << n;
  os << "\n";
}

}  // namespace

void run_area_command(const AreaCommandOptions& o) {
  const Config cfg = load_config(o.config);
  const ArchParams arch = ArchParams::resolve(cfg);
  const RtlParams p = rtl_params(arch);
  AreaOptions ao;
  ao.top = o.top;
  ao.root_parameters = root_rtl_params(o.top, arch);
  ao.use_cache = !o.no_cache;
  ao.split = !o.one_process;
  ao.jobs = o.jobs;
  ao.progress = progress_printer(o.quiet);
  const bool tty = isatty(2);
  AreaReport r = synthesize_area(p, ao);
  // The memory system's arrays belong to the whole design, not to one module; rast_top
  // and the ROP and texture caches' modules synthesise their tags and state and count
  // their data arrays (blackboxes to Yosys).
  if (o.top.empty()) add_storage(r, design_storage(arch));
  if (o.top == "rast_top") add_storage(r, rast_top_storage(arch));
  if (o.top == "rast_rop_cache") add_storage(r, rop_cache_data_storage(arch));
  if (o.top == "rast_texture_cache") add_storage(r, texture_cache_data_storage(arch));
  if (o.top == "rast_tile_buffer") add_storage(r, tile_buffer_storage(arch));
  if (!o.quiet && tty) std::cerr << "\r\033[K" << std::flush;
  std::ostream& out = summary_stream(o.stats_path, o.quiet);
  out << "area: " << cfg.source_name() << ", " << (r.top.empty() ? "rast_top + rast_engine2d" : r.top) << ", "
      << r.yosys_version << ", "
      << (r.from_cache ? "from the cache (" + r.key + ")"
                       : "synthesised in " + std::to_string(static_cast<int>(r.synth_seconds + 0.5)) + " s")
      << " (" << r.modules << " Yosys processes, " << static_cast<int>(r.cpu_seconds + 0.5) << " CPU s, peak "
      << static_cast<int>(r.peak_mb + 0.5) << " MB a process)\n";
  print_table(out, r);
  if (!o.stats_path.empty()) {
    nlohmann::json j = area_to_json(r);
    j["config"] = cfg.source_name();
    j["provenance"] = provenance(o.config, cfg, "");
    write_json(o.stats_path, j);
  }
}

void register_area(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "area", "Synthesise the RTL with Yosys: cells, flip-flops and transistors per stage module (cached)");
  static AreaCommandOptions o;
  add_config_options(cmd, o.config);
  cmd->add_option("--stats", o.stats_path,
                  "Write cells, flip_flops, transistors, cells_by_type, stages.<module>.* and storage (the memory "
                  "system's counted arrays) as JSON ('-' for stdout)");
  cmd->add_option("--top", o.top,
                  "Synthesise one module only: rast_top (the raster pipeline), rast_engine2d, a binary32 unit of "
                  "the front end (rast_fp32_mul, rast_fp32_add, rast_fp32_recip, rast_front_end_xform), the "
                  "reciprocal unit of perspective-correct interpolation (rast_recip, built with interp.recip_seed_bits and "
                  "interp.recip_iterations), the ROP's cache (rast_rop_cache, built with rop.color_cache_*; its "
                  "data array counted, not synthesised), a unit of the texture unit (rast_texture_lod, "
                  "rast_texture_address, rast_texture_filter, rast_texture_combine; built with "
                  "interp.texcoord_format and texture.weight_bits) or a stage "
                  "module under rast_top such as rast_fine_raster (default: rast_top and rast_engine2d)");
  cmd->add_flag("--one-process", o.one_process,
                "Synthesise rast_top's whole hierarchy in one Yosys process (default: one process a module, its "
                "submodules as blackboxes, summed; one process needs several GB on the wide configs)");
  cmd->add_option("--jobs,-j", o.jobs, "Yosys child processes at once when rast_top is split a module a process")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  cmd->add_flag("--no-cache", o.no_cache, "Synthesise even when the cache holds this parameter set (and do not store)");
  add_quiet_flag(cmd, o.quiet, "progress or the table");
  cmd->footer(
      "Relative area: generic gates with Yosys' CMOS transistor estimate, no cell library, no wires "
      "(docs/area.md). With memory.model other than fixed the total also counts, without synthesis, the ROP "
      "caches' data, tag and state bits and the fast-clear and compression flags: an array of " +
      std::to_string(kSramMinBits) + " bits or more as " + std::to_string(kSramCellTransistors) +
      "T SRAM cells + " + std::to_string(kSramPeripheryPercent) + " % for the periphery, a smaller one as flip-flops at " +
      std::to_string(kFlopBitTransistors) +
      " transistors a bit. Needs Yosys (Debian package yosys). Results are cached per RTL parameter set and RTL source in $RASTSIM_CACHE/area (default ~/.cache/rastsim/area).");
  cmd->callback([] { run_area_command(o); });
}

}  // namespace rastsim::app
