// SPDX-License-Identifier: Apache-2.0
#include "report/stats_json.h"

#include "ref/traverse.h"
#include "scene/scene_io.h"

#include <cstdio>
#include <utility>

namespace rastsim {

std::string crc32_hex(uint32_t crc) {
  char hex[9];
  std::snprintf(hex, sizeof hex, "%08x", crc);
  return hex;
}

std::string triangles_summary(const RenderStats& s) {
  // Triangle setup's outcomes other than "accepted" (ref/tri_setup.h), one counter each.
  const std::pair<uint64_t, const char*> reasons[] = {{s.triangles_facing_culled, "culled by facing"},
                                                      {s.triangles_zero_area, "zero area"},
                                                      {s.triangles_out_of_range, "out of range"},
                                                      {s.triangles_outside_clip, "outside the clip"}};
  uint64_t not_drawn = 0;
  std::string why;
  for (const auto& [n, reason] : reasons) {
    if (n == 0) continue;
    not_drawn += n;
    why += (why.empty() ? "" : ", ") + std::to_string(n) + " " + reason;
  }
  const FrontEndStats& f = s.front_end;
  // Clip-space input: what the front end culled before those triangles (front_end.h).
  const std::string front = !f.any() ? "" : std::to_string(f.clip_triangles_in) + " clip-space triangles (" +
                                                std::to_string(f.triangles_clipped) + " clipped, " +
                                                std::to_string(f.triangles_behind) + " behind the eye, " +
                                                std::to_string(f.triangles_culled_outside) + " outside) -> ";
  const std::string total = front + std::to_string(s.triangles_in) + " triangles";
  if (not_drawn == 0) return total + (s.triangles_in ? " (all drawn)" : "");
  return total + " (" + std::to_string(not_drawn) + " not drawn: " + why + ")";
}

void add_front_end(nlohmann::json& j, const FrontEndStats& f) {
  const std::pair<const char*, uint64_t> keys[] = {
      {"clip_triangles_in", f.clip_triangles_in},   {"triangles_behind", f.triangles_behind},
      {"triangles_culled_outside", f.triangles_culled_outside}, {"triangles_clipped", f.triangles_clipped},
      {"clip_vertices_made", f.clip_vertices_made}, {"triangles_nonfinite", f.triangles_nonfinite},
      {"clip_triangles_out", f.clip_triangles_out}, {"points_in", f.points_in},
      {"points_culled", f.points_culled},           {"lines_in", f.lines_in},
      {"lines_culled", f.lines_culled},             {"lines_clipped", f.lines_clipped},
  };
  for (const auto& [key, n] : keys) j[key] = n;
}

namespace {
nlohmann::json client_json(const MemoryClientStats& c) {
  return {{"accesses", c.accesses},           {"hits", c.hits},
          {"misses", c.misses},               {"evictions", c.evictions},
          {"writebacks", c.writebacks},       {"bytes_read", c.bytes_read},
          {"bytes_written", c.bytes_written}, {"fast_clear_blocks", c.fast_clear_blocks},
          {"clear_fill_bytes", c.clear_fill_bytes}, {"compressed_blocks", c.compressed_blocks},
          {"compressed_bytes", c.compressed_bytes}};
}
}  // namespace

void add_memory(nlohmann::json& j, const MemoryStats& m) {
  const MemoryClientStats& c = m.rop_color;
  const MemoryClientStats& d = m.rop_depth;
  j["dram_bytes_read"] = c.bytes_read + d.bytes_read;
  j["dram_bytes_written"] = c.bytes_written + d.bytes_written;
  j["rop_color_cache_hits"] = c.hits;
  j["rop_color_cache_misses"] = c.misses;
  j["rop_depth_cache_hits"] = d.hits;
  j["rop_depth_cache_misses"] = d.misses;
  j["fast_clear_blocks"] = c.fast_clear_blocks + d.fast_clear_blocks;
  j["depth_compressed_bytes"] = d.compressed_bytes;
  j["memory"]["clients"][kRopColorClient] = client_json(c);
  j["memory"]["clients"][kRopDepthClient] = client_json(d);
  if (!m.binned) return;  // pipeline.mode = binned: its clients (docs/binning.md)
  j["dram_bytes_read"] = c.bytes_read + d.bytes_read + m.binning.bytes_read + m.tile_store.bytes_read;
  j["dram_bytes_written"] = c.bytes_written + d.bytes_written + m.binning.bytes_written + m.tile_store.bytes_written;
  j["memory"]["clients"][kBinningClient] = client_json(m.binning);
  j["memory"]["clients"][kTileStoreClient] = client_json(m.tile_store);
}

namespace {
void add_hiz(nlohmann::json& j, const RenderStats& s) {
  const HizStats& h = s.hiz;
  j["tiles_culled_hiz"] = h.tiles_culled;
  j["tiles_accepted_hiz"] = h.tiles_accepted;
  j["fragments_culled_hiz"] = h.fragments_culled;
  j["hiz_tiles_tested"] = h.tiles_tested;
  j["hiz_layer_completions"] = h.layer_completions;
  j["hiz_dram_bytes_read"] = h.bytes_read;
  j["hiz_dram_bytes_written"] = h.bytes_written;
  j["hiz_culled_fraction"] = hiz_culled_fraction(s);
  if (s.memory.enabled) {  // the spilled table is a memory client too
    j["dram_bytes_read"] = j["dram_bytes_read"].get<uint64_t>() + h.bytes_read;
    j["dram_bytes_written"] = j["dram_bytes_written"].get<uint64_t>() + h.bytes_written;
    j["memory"]["clients"][kHizClient].update({{"accesses", h.dram_reads + h.dram_writes},
                                      {"bytes_read", h.bytes_read},
                                      {"bytes_written", h.bytes_written}});
  }
}

// The binned pipeline's keys (pipeline.mode = binned, docs/binning.md).
void add_binned(nlohmann::json& j, const BinStats& b) {
  j["bins"] = b.bins;
  j["primitives_per_bin_mean"] = b.primitives_per_bin_mean();
  j["bin_overflows"] = b.bin_overflows;
  j["dram_bytes_geometry"] = b.dram_bytes_geometry();
  j["dram_bytes_framebuffer"] = b.dram_bytes_framebuffer();
  j["bin"] = {{"bins_rendered", b.bins_rendered},
              {"geometry_bytes_written", b.geometry_bytes_written},
              {"geometry_bytes_read", b.geometry_bytes_read},
              {"framebuffer_bytes_written", b.framebuffer_bytes_written},
              {"framebuffer_bytes_read", b.framebuffer_bytes_read}};
}

// The texture unit's keys (docs/texture.md).
void add_texture(nlohmann::json& j, const TextureStats& t) {
  j["texel_fetches"] = t.texel_fetches;
  j["texture_cache_hits"] = t.cache_hits;
  j["texture_cache_misses"] = t.cache_misses;
  j["texture_dram_bytes"] = t.dram_bytes;
  j["helper_pixels"] = t.helper_pixels;
  for (int f = 0; f < kTexFilters; ++f) j["texture_samples"][to_string(TexFilter(f))] = t.samples[f];
}

// The keys every render has.
nlohmann::json base_json(const RenderStats& s) {
  return {
      {"triangles_in", s.triangles_in},
      {"triangles_culled", s.triangles_culled},
      {"triangles_zero_area", s.triangles_zero_area},
      {"triangles_facing_culled", s.triangles_facing_culled},
      {"triangles_out_of_range", s.triangles_out_of_range},
      {"triangles_outside_clip", s.triangles_outside_clip},
      {"triangles_rasterized", s.triangles_rasterized},
      {"tiles_visited", s.traversal.tiles_visited},
      {"tiles_rejected", s.traversal.tiles_rejected},
      {"tiles_accepted", s.traversal.tiles_accepted},
      {"tiles_partial", s.traversal.tiles_partial},
      {"pixel_tests", s.traversal.pixel_tests},
      {"fragments", s.traversal.fragments},
      {"samples", s.samples},
      {"sample_tests", s.traversal.sample_tests},
      {"samples_covered", s.traversal.samples_covered},
      {"pixels_partially_covered", s.traversal.pixels_partially_covered},
      {"samples_passed", s.samples_passed},
      {"fragments_shaded", s.fragments_shaded},
      {"color_buffer_bytes", s.color_buffer_bytes},
      {"depth_buffer_bytes", s.depth_buffer_bytes},
      {"resolve_bytes", s.resolve_bytes},
      {"fragments_passed", s.fragments_passed},
      {"depth_writes", s.depth_writes},
      {"max_attr_error_lsb", s.max_attr_error_lsb},
      {"mean_attr_error_lsb", s.traversal.fragments ? double(s.attr_error_sum) / double(3 * s.traversal.fragments) : 0.0},
      {"max_depth_error_lsb", s.max_depth_error_lsb},
      {"mean_depth_error_lsb", s.traversal.fragments ? double(s.depth_error_sum) / double(s.traversal.fragments) : 0.0},
      {"primitives_2d", s.draw2d.primitives},
      {"primitives_2d_culled", s.draw2d.primitives_culled},
      {"pixels_2d", s.draw2d.pixels},
      {"framebuffer_crc32", crc32_hex(s.framebuffer_crc32)},
      {"wall_seconds", s.wall_seconds},
  };
}
}  // namespace

nlohmann::json to_json(const RenderStats& s) {
  nlohmann::json j = base_json(s);
  // Keys of the other traversal methods only where they apply, so that a tiled run's
  // stats are the same as before raster.traversal existed.
  if (s.traversal_method != Traversal::Tiled) j["traversal"] = to_string(s.traversal_method);
  if (s.traversal_method == Traversal::Scanline) j["spans"] = s.traversal.spans;
  // The early depth test's keys only with depth.early on (docs/depth.md).
  if (s.depth_early) {
    j["fragments_culled_early"] = s.fragments_culled_early;
    j["interpolations_saved"] = s.interpolations_saved;
    j["texture_samples_saved"] = s.texture_samples_saved;
  }
  // The binned pipeline's keys only with pipeline.mode = binned (docs/binning.md).
  if (s.bin.enabled) add_binned(j, s.bin);
  if (s.samples > 1) j["aa_mode"] = s.aa_mode == AaMode::Ssaa ? "ssaa" : "msaa";
  // The geometry front end's keys only where a clip-space primitive was drawn, so that a
  // screen-space scene's stats are the same as before clip space existed.
  if (s.front_end.any()) add_front_end(j, s.front_end);
  // The memory system's keys only when it ran, so that memory.model = fixed's stats are
  // the same as before it existed.
  if (s.memory.enabled) add_memory(j, s.memory);
  // Hi-Z's keys only with depth.hiz on; the oracle score with either culling on
  // (docs/depth-culling.md).
  if (s.hiz_mode != HizMode::Off) add_hiz(j, s);
  if (s.hiz_mode != HizMode::Off || s.depth_early) j["hiz_oracle_fraction"] = hiz_oracle_fraction(s);
  // The texture unit's keys only where a texture was sampled (docs/texture.md), so that an
  // untextured scene's stats are the same as before textures existed.
  if (const TextureStats& t = s.texture; t.total_samples() > 0 || t.helper_pixels > 0) add_texture(j, t);
  if (s.coverage.measured) {
    j["pixels_wrong"] = s.coverage.pixels_wrong;
    j["cracks"] = s.coverage.cracks;
    j["overlaps"] = s.coverage.overlaps;
  }
  return j;
}

void add_obj_ignored(nlohmann::json& j, const std::string& scene_path, ObjCamera camera) {
  if (const auto counts = obj_ignored_counts(scene_path, camera)) j["obj_ignored"] = nlohmann::json(*counts);
}

}  // namespace rastsim
