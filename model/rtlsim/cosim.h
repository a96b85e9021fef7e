// SPDX-License-Identifier: Apache-2.0
// Co-simulation of the Verilog raster pipeline (rtl/rast_top.sv, verilated per config
// into rastsim_verilated) against the reference model, fragment for fragment, with a
// cycle count comparable to the SystemC model's.
//
// - The testbench plays the stages the RTL does not have, with the SystemC model's
//   cost equations (TimingParams, config/timing_params.h): command fetch and primitive
//   assembly in front of the RTL's triangle FIFO. Behind the interpolator the RTL's
//   fragment FIFO and ROP (rtl/rast_rop.sv) work on their own; the testbench feeds the
//   ROP's command port (one command a marker, in stream order) and serves its memory
//   port from a framebuffer (memory.model = "fixed": requests taken at once, read data
//   the next cycle). Vertices are snapped by the reference model's setup (the RTL takes
//   snapped fixed-point vertices); state commands travel as markers.
// - Multisampling (raster.samples, msaa): the RTL takes the sample count and the snapped
//   offsets as run-time inputs; every fragment's sample mask is compared too, the RTL
//   ROP tests and writes each sample, and an end-of-frame marker (fetched like a command
//   header, through the RTL like a state command, as in the SystemC model) costs the ROP
//   the resolve pass, which the testbench plays (TimingParams::resolve_cycles after the
//   marker's command); the CRC is of the resolved image. raster.aa_mode = ssaa has no
//   RTL (an error naming the key).
// - Every fragment is compared bit for bit (x, y, depth, r, g, b, mask) IN ORDER with the
//   reference model's stream for the same tile size (tiles row-major, pixels row-major
//   within a tile, triangles in order); the first mismatch is reported with its
//   triangle (scene file:line and index) and pixel.
// - Optional random backpressure on the ROP's memory port and gaps in the triangle and 2D
//   operation valids (seeded, replayable), FST waveform.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "config/arch_params.h"
#include "rtlsim/rtl_params.h"
#include "ref/framebuffer.h"
#include "ref/memory/rop_memory.h"
#include "ref/scene.h"

namespace rastsim {
// The functional memory counts as JSON fields (the on-demand runner's answer, CosimResult).
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(MemoryClientStats, accesses, hits, misses, evictions, writebacks,
                                                bytes_read, bytes_written, fast_clear_blocks, clear_fill_bytes,
                                                compressed_blocks, compressed_bytes)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(MemoryStats, enabled, rop_color, rop_depth)
}  // namespace rastsim

namespace rastsim::rtlsim {

struct CosimOptions {
  int tile_size = 0;               // 0: raster.tile_size of the config
  // Random stress on the RTL's valid/ready inputs, each input its own generator seeded by
  // stress_seed (testbench.cpp): the same seed replays the same run.
  uint64_t stress_seed = 0;
  double backpressure = 0;         // probability that the ROP's or the 2D engine's memory refuses a request (rd_ready_i, wr_ready_i low) in a cycle, or delays the engine's read response (0 = off)
  double valid_gaps = 0;           // probability that an offered tri_valid_i or 2D in_valid_i is held low in a cycle
  std::string fst_path;            // write an FST waveform ("" = none)
  uint64_t max_cycles = 2'000'000'000;
  // Lines of progress while an on-demand model builds (rtl_cache.h); empty: printed on
  // stderr (one updating line on a terminal). Not sent to the runner.
  std::function<void(const std::string&)> progress;
  bool record_transactions = false;  // fill StageRecord::spans (--trace-diff)
  // memory.model = "dram": write every DRAM request of the run here in DRAMsim3's format
  // (timing/dram_trace.h: address, READ/WRITE, the DRAM clock it enters at; --trace-diff's
  // rtl_mem.trace); "" = none.
  std::string mem_trace_path;
  // Test-only perturbation: the memory returns the first read of the ROP's transaction
  // number `perturb_rop_transaction` this many cycles late (0 = off), so a test can check that
  // --trace-diff names it as the first difference.
  uint64_t perturb_rop_cycles = 0;
  uint64_t perturb_rop_transaction = 0;
  // A verilated model by name (rtl_registry: a shipped config, or <cfg>_circuit with the
  // divider as its circuit); "" = the first that fits, else an on-demand one.
  std::string rtl_model;
  // `cosim --frames A:B` (app/frame_output.h): the framebuffer the ROP's memory starts
  // from (the reference model's after frames 0..A-1; null: the initial one), and the
  // reference image the run must end with (the reference model's after frame B-1, its
  // frames run from the start; null: render_scene of the scene). In-process only (not
  // sent to the on-demand runner, which refuses them): a shipped model runs them.
  const Framebuffer* initial_fb = nullptr;
  const Framebuffer* reference_fb = nullptr;
};
// The options as the on-demand runner gets them (progress stays behind).
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(CosimOptions, tile_size, stress_seed, backpressure, valid_gaps, fst_path,
                                                max_cycles, record_transactions, mem_trace_path, perturb_rop_cycles,
                                                perturb_rop_transaction)

// One stage's cycles on one side of the comparison (docs/microarchitecture.md "Stage
// statistics"): every cycle of the run is exactly one of busy, stalled, starved.
struct StageSpan {
  uint64_t start = 0, end = 0;  // cycles [start, end): from its first cycle of work to its last
};
struct StageRecord {
  std::string name;  // the SystemC stage's name (command_fetch, ..., rop)
  uint64_t busy = 0, stalled = 0, starved = 0;  // cycles
  uint64_t transactions = 0;                     // input transactions taken
  std::vector<StageSpan> spans;                  // per transaction, in order (record_transactions)
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(StageSpan, start, end)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(StageRecord, name, busy, stalled, starved, transactions, spans)

struct CosimResult {
  std::string rtl_config;          // which verilated model ran: a shipped config's name, or "cache:<key>"
  std::string rtl_model_dir;       // on-demand: the model's cache entry ("" for a shipped model)
  bool rtl_cache_hit = false;      // on-demand: the entry was there (or another process built it)
  double rtl_build_seconds = 0;    // on-demand: the build this call waited for (0 on a hit)
  uint64_t cycles_rtl = 0;         // first command to the ROP's last busy cycle
  uint64_t fragments_expected = 0; // from the reference model
  uint64_t fragments_compared = 0; // fragments the RTL produced and were compared
  uint64_t mismatches = 0;         // differing or missing/extra fragments
  std::string first_mismatch;      // "" when none
  uint64_t triangles = 0, markers = 0;
  uint64_t commands_2d = 0;        // 2D commands run through the 2D engine
  uint64_t pixels_2d = 0;          // pixels the 2D engine wrote
  uint32_t crc_rtl = 0, crc_ref = 0;  // colour CRC of the testbench framebuffer and the reference (resolved)
  int samples = 1;                 // raster.samples driven on the RTL
  uint64_t rop_accesses = 0;       // ROP accesses of the fragments (TimingParams::rop_accesses)
  uint64_t resolve_cycles = 0;     // the frame-end resolve pass (end-of-frame marker), included in cycles_rtl
  // The texture stage (textured scenes): helper pixels the RTL dropped (render's
  // helper_pixels) and the texel fetch port's fetches through the reference's texture
  // cache model (testbench: tb_texture.h).
  uint64_t helper_pixels = 0, texel_fetches = 0, texture_cache_hits = 0, texture_cache_misses = 0;
  // Hi-Z in rast_top (hiz_applies): tiles coarse raster culled and accepted (render's
  // tiles_culled_hiz, tiles_accepted_hiz; a difference from the reference's is a mismatch).
  bool hiz = false;
  uint64_t tiles_culled_hiz = 0, tiles_accepted_hiz = 0;
  // depth.hiz_sync = lagged: the tiles the reference culled that the RTL drew (its table
  // lagging the ROP) and their fragments (each checked to write no depth).
  bool hiz_lagged = false;
  uint64_t hiz_lagged_tiles_drawn = 0, hiz_lagged_fragments_drawn = 0;
  // Its spilled entries' bytes through the hiz port (render's hiz_dram_bytes_read,
  // hiz_dram_bytes_written; tb_hiz.h: unlike the reference's, a mismatch).
  uint64_t hiz_dram_bytes_read = 0, hiz_dram_bytes_written = 0;
  // depth.early (rtl/rast_early_z.sv): fragments the RTL culled early (render's
  // fragments_culled_early; each fragment's flag is compared with the reference's).
  bool depth_early = false;
  uint64_t fragments_culled_early = 0;
  // memory.model = "dram": the ROP's functional memory counts (render --stats' keys) and
  // the DRAM's figures (add_memory_system_json's keys: dram_row_hit_rate, memory.dram.*,
  // memory.clients.<client>.bursts_read, ...); memory.enabled false and {} with fixed.
  MemoryStats memory;
  nlohmann::json dram = nlohmann::json::object();
  double wall_seconds = 0;         // the RTL simulation (testbench included)
  // Per stage, every row of the stage table in its order (timing/stage_table.h, kStages):
  // the RTL's stages from its handshakes (rast_top's dbg_*_o ports), the others from the
  // testbench's own accounting (command fetch, assembly, ROP, the 2D front end and engine).
  std::vector<StageRecord> stages;
  // Per command of the scene (by index): the cycle command fetch started its first item
  // (UINT64_MAX: never), as the SystemC model's on_fetch (fidelity::record_command_starts),
  // for per-frame cycles; and the fragment mismatches of its triangles (the others, e.g.
  // the framebuffer check's, counted in `mismatches` only).
  std::vector<uint64_t> command_starts, command_mismatches;

  // The run's figures under `rastsim cosim --stats` names (cycles_rtl, mismatches,
  // framebuffer_crc32_rtl, ...), with the stress options it ran under; the caller adds the
  // config, the scene and the SystemC model's figures.
  nlohmann::json to_json(const CosimOptions& opts) const;
};
// Every field, for the on-demand runner's answer (a new field: add it here too).
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(CosimResult, rtl_config, rtl_model_dir, rtl_cache_hit,
                                                rtl_build_seconds, cycles_rtl, fragments_expected, fragments_compared,
                                                mismatches, first_mismatch, triangles, markers, commands_2d, pixels_2d,
                                                crc_rtl, crc_ref, samples, rop_accesses, resolve_cycles, helper_pixels,
                                                texel_fetches, texture_cache_hits, texture_cache_misses, hiz,
                                                tiles_culled_hiz, tiles_accepted_hiz, hiz_lagged, hiz_lagged_tiles_drawn,
                                                hiz_lagged_fragments_drawn, hiz_dram_bytes_read,
                                                hiz_dram_bytes_written, depth_early, fragments_culled_early, memory, dram,
                                                wall_seconds, stages, command_starts, command_mismatches)

// The verilated configs linked into this binary, and the parameters each was built with
// (compiled in at configure time: no config file is read).
struct RtlModelInfo {
  std::string name;    // the model: a config's name, or <config>_circuit
  std::string config;  // configs/<config>.toml, whose parameters it was built with
  RtlParams params;
};
std::vector<RtlModelInfo> rtl_models();

// The model a config runs on: a shipped one compatible with it (rtl_params_compatible),
// else an on-demand one from the cache (rtl_cache.h), built now when missing (cmake and
// Verilator, about a minute; concurrent callers build it once). Throws naming the config
// and the key when the RTL cannot run it, or with the build's error and log.
struct RtlModelChoice {
  std::string name;        // CosimResult::rtl_config
  std::string dir;         // on-demand: the cache entry; "" for a shipped model
  bool cache_hit = false;  // on-demand: found in the cache
  double build_seconds = 0;
};
RtlModelChoice prepare_rtl_model(const ArchParams& arch, const CosimOptions& opts = {});

// Runs `scene` through the RTL model prepare_rtl_model chooses: a shipped model in this
// process, an on-demand one as a child process (the cache entry's runner, which reads
// the scene again from its file, Scene::source: an in-memory scene needs a shipped model).
CosimResult run_cosim(const Scene& scene, const ArchParams& arch, const CosimOptions& opts = {});

}  // namespace rastsim::rtlsim
