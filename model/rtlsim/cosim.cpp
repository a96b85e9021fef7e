// SPDX-License-Identifier: Apache-2.0
#include "rtlsim/cosim.h"

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include "rtlsim/testbench.h"
#include "rtlsim/cosim_setup.h"
#include "report/stats_json.h"
#include "rtlsim/rtl_cache.h"
#include "util/atomic_file.h"

namespace rastsim::rtlsim {

namespace {

// The config as a user names it: its file and every --set that changed it.
std::string config_label(const ArchParams& arch) {
  const Config& cfg = arch.config;
  std::string s = cfg.source_name();
  for (const auto& [key, v] : cfg.values())
    if (cfg.origin(key).rfind("--set", 0) == 0) s += " --set " + key + "=" + to_string(v);
  return s;
}

// The first shipped model that runs `wanted`, or -1; with opts.rtl_model, that model,
// which must exist and run `wanted`.
int shipped_model(const RtlParams& wanted, const CosimOptions& opts) {
  const auto& reg = rtl_registry();
  if (!opts.rtl_model.empty()) {
    std::string names;
    for (size_t i = 0; i < reg.size(); ++i) {
      if (reg[i].name != opts.rtl_model) {
        names += (names.empty() ? "" : ", ") + std::string(reg[i].name);
        continue;
      }
      std::string why;  // the first differing parameter, its config key and both values
      if (!rtl_params_compatible(reg[i].params, wanted, &why))
        throw std::runtime_error("--rtl-model " + opts.rtl_model + ": this config does not fit that model: " + why);
      return static_cast<int>(i);
    }
    throw std::runtime_error("--rtl-model " + opts.rtl_model + ": no such verilated model (there are: " + names + ")");
  }
  for (size_t i = 0; i < reg.size(); ++i)
    if (rtl_params_compatible(reg[i].params, wanted)) return static_cast<int>(i);
  return -1;
}

// Verilator 5.006 under -Wall (rtl/rast_verilate.cmake) stops on a replication wider than
// this (WIDTHCONCAT, e.g. a tile's sample mask cleared with '0 in rtl/rast_fine_raster.sv):
// the RTL's tile pixels x MaxSamples must stay within it.
constexpr int64_t kMaxMaskBits = 8192;

RtlCacheEntry on_demand_model(const ArchParams& arch, const CosimOptions& opts, const RtlParams& wanted) {
  const Config& cfg = arch.config;  // its name and --set overrides label the build
  // Built with the config's parameters; the tile size as the larger of the config's and
  // the one asked for (a run-time input up to the built maximum); the sample count (also
  // a run-time input) as large as the sample mask allows, up to the schema's maximum
  // (rtl_params_from_config), at least 2 (the RTL's minimum): the config's other tile sizes
  // and sample counts below these find the entry too.
  RtlParams build = rtl_params(arch);
  build.tile_log2_max = std::max(build.tile_log2_max, wanted.tile_log2_max);
  const int64_t tile_pixels = int64_t{1} << (2 * build.tile_log2_max);
  const int64_t needed = std::max(2, wanted.max_samples);
  if (tile_pixels * needed > kMaxMaskBits) {
    const std::string tile = opts.tile_size ? "a tile size of " + std::to_string(opts.tile_size) + " px"
                                            : "raster.tile_size = " + std::to_string(cfg.get_int("raster.tile_size")) +
                                                  " (" + cfg.origin("raster.tile_size") + ")";
    throw ConfigError(config_label(arch) + ": no RTL model for this config: " + tile + " with raster.samples = " +
                      std::to_string(wanted.max_samples) + " needs a " + std::to_string(tile_pixels * needed) +
                      "-bit sample mask a tile (pixels x max(2, samples)), above the " +
                      std::to_string(kMaxMaskBits) + " bits Verilator builds the RTL with (rtl/rast_fine_raster.sv); "
                      "co-simulate with a smaller tile or fewer samples");
  }
  while (build.max_samples > needed && tile_pixels * build.max_samples > kMaxMaskBits) build.max_samples /= 2;
  RtlBuildOptions bo;
  bo.label = config_label(arch);
  bo.progress = opts.progress;
  try {
    return find_or_build_rtl_model(wanted, build, bo);
  } catch (const std::exception& e) {
    throw std::runtime_error(bo.label + ": no RTL model for this config: " + e.what());
  }
}

}  // namespace

nlohmann::json CosimResult::to_json(const CosimOptions& opts) const {
  nlohmann::json j = {{"rtl_model", rtl_config},
          {"rtl_model_dir", rtl_model_dir},
          {"rtl_cache_hit", rtl_cache_hit},
          {"rtl_build_seconds", rtl_build_seconds},
          {"cycles_rtl", cycles_rtl},
          {"fragments_expected", fragments_expected},
          {"fragments_compared", fragments_compared},
          {"mismatches", mismatches},
          {"commands_2d", commands_2d},
          {"pixels_2d", pixels_2d},
          {"samples", samples},
          {"rop_accesses", rop_accesses},
          {"resolve_cycles", resolve_cycles},
          {"framebuffer_crc32_rtl", crc32_hex(crc_rtl)},
          {"framebuffer_crc32_ref", crc32_hex(crc_ref)},
          {"first_mismatch", first_mismatch},
          {"backpressure", opts.backpressure},
          {"valid_gaps", opts.valid_gaps},
          {"seed", opts.stress_seed},
          {"rtl_wall_seconds", wall_seconds},
          {"rtl_cycles_per_second", wall_seconds > 0 ? double(cycles_rtl) / wall_seconds : 0.0}};
  if (texel_fetches > 0) {  // render --stats' texture keys
    j["helper_pixels"] = helper_pixels;
    j["texel_fetches"] = texel_fetches;
    j["texture_cache_hits"] = texture_cache_hits;
    j["texture_cache_misses"] = texture_cache_misses;
  }
  if (hiz) {  // render --stats' Hi-Z keys the RTL counts
    j["tiles_culled_hiz"] = tiles_culled_hiz;
    j["tiles_accepted_hiz"] = tiles_accepted_hiz;
    j["hiz_dram_bytes_read"] = hiz_dram_bytes_read;
    j["hiz_dram_bytes_written"] = hiz_dram_bytes_written;
    if (hiz_lagged) {
      j["hiz_lagged_tiles_drawn"] = hiz_lagged_tiles_drawn;
      j["hiz_lagged_fragments_drawn"] = hiz_lagged_fragments_drawn;
    }
  }
  if (depth_early) j["fragments_culled_early"] = fragments_culled_early;  // render --stats' key
  if (memory.enabled) {  // render's memory keys, then the DRAM's (simulate --stats' names)
    add_memory(j, memory);
    j.merge_patch(dram);
  }
  return j;
}

std::vector<RtlModelInfo> rtl_models() {
  std::vector<RtlModelInfo> v;
  for (const RegistryEntry& e : rtl_registry()) v.push_back({e.name, e.config, e.params});
  return v;
}

RtlModelChoice prepare_rtl_model(const ArchParams& arch, const CosimOptions& opts) {
  const RtlParams wanted = cosim_wanted_params(arch, opts);
  if (const int i = shipped_model(wanted, opts); i >= 0) return {rtl_registry()[size_t(i)].name, "", false, 0};
  const RtlCacheEntry e = on_demand_model(arch, opts, wanted);
  return {"cache:" + e.key, e.dir, e.hit, e.hit ? 0 : e.build_seconds};
}

namespace {

CosimResult run_rtl(const Scene& scene, const ArchParams& arch, const CosimOptions& opts) {
  const RtlParams wanted = cosim_wanted_params(arch, opts);
  if (const int i = shipped_model(wanted, opts); i >= 0) {
    const RegistryEntry& m = rtl_registry()[size_t(i)];
    TbSetup s;
    CosimResult r;
    r.rtl_config = m.name;
    cosim_setup(scene, arch, opts, m.params, s, r);
    m.run(s, r);
    return r;
  }
  // No shipped model: an on-demand one, run as a child process that reads the scene
  // again from its file (checked first, before a build).
  if (opts.initial_fb || opts.reference_fb)
    throw std::runtime_error(config_label(arch) + ": no shipped RTL model fits this config, and a range of frames "
                             "(--frames) runs on a shipped model only (the on-demand runner reads the whole scene "
                             "from its file)");
  std::error_code ec;
  if (!std::filesystem::is_regular_file(scene.source, ec))
    throw std::runtime_error(config_label(arch) + ": no shipped RTL model fits this config, and an on-demand model "
                             "reads the scene from its file, but scene '" + scene.source +
                             "' is not a file (co-simulate a scene from a file)");
  const RtlCacheEntry e = on_demand_model(arch, opts, wanted);
  CosimResult r = run_rtl_runner(e, runner_request(scene, arch, opts)).get<CosimResult>();
  r.rtl_config = "cache:" + e.key;
  r.rtl_model_dir = e.dir;
  r.rtl_cache_hit = e.hit;
  r.rtl_build_seconds = e.hit ? 0 : e.build_seconds;
  return r;
}

}  // namespace

CosimResult run_cosim(const Scene& scene, const ArchParams& arch, const CosimOptions& opts) {
  // Verilator writes the waveform at a temporary name, renamed into place once the run
  // has completed (util/atomic_file.h).
  std::unique_ptr<PendingFile> fst;
  CosimOptions o = opts;
  if (!o.fst_path.empty()) {
    fst = std::make_unique<PendingFile>(o.fst_path);
    o.fst_path = fst->path();
  }
  CosimResult r = run_rtl(scene, arch, o);
  if (fst) fst->commit();
  return r;
}

}  // namespace rastsim::rtlsim
