// SPDX-License-Identifier: Apache-2.0
#include "sim_harness.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <random>

#include "fidelity/run_child.h"
#include "ref/prim_assembly.h"
#include "report/stats_json.h"
#include "config/memory_config.h"
#include "config/raster_state_config.h"

namespace rastsim::sctest {

nlohmann::json run_isolated(const std::function<nlohmann::json()>& fn) {
  return fidelity::run_in_child_or_error(fn);
}

nlohmann::json diff_render_stats_with_memory(const Scene& scene, const Config& cfg) {
  RenderStats ref;
  render_scene(scene, raster_state_from_config(cfg), ref, {}, Framebuffer::kDefaultTileLog2, 1,
               memory_params_from_config(cfg));
  const sc::SimResult sim = sc::simulate_scene(scene, ArchParams::resolve(cfg), {});
  nlohmann::json a = to_json(ref), b = to_json(sim.render), diff = nlohmann::json::object();
  for (const auto& [k, v] : a.items())
    if (k != "wall_seconds" && b[k] != v) diff[k] = {v, b[k]};
  return {{"diff", diff}, {"ref", a}};
}

nlohmann::json compare_with_reference(const Scene& scene, const Config& cfg, const sc::SimOptions& opts) {
  std::vector<std::string> ref_frags, sim_frags;
  RenderStats ref_stats;
  const Framebuffer ref_fb = render_scene(scene, raster_state_from_config(cfg), ref_stats,
                                          [&](const Fragment& f) { ref_frags.push_back(fragment_trace_line(f)); });
  sc::SimOptions o = opts;
  o.on_fragment = [&](const Fragment& f) { sim_frags.push_back(fragment_trace_line(f)); };
  const sc::SimResult r = sc::simulate_scene(scene, ArchParams::resolve(cfg), o);
  int64_t first = -1;
  const size_t n = std::min(ref_frags.size(), sim_frags.size());
  for (size_t i = 0; i < n && first < 0; ++i)
    if (ref_frags[i] != sim_frags[i]) first = int64_t(i);
  if (first < 0 && ref_frags.size() != sim_frags.size()) first = int64_t(n);
  std::string mismatch;
  if (first >= 0) {
    auto at = [&](const std::vector<std::string>& v) { return size_t(first) < v.size() ? v[first] : "(end)"; };
    mismatch = "ref '" + at(ref_frags) + "' vs sim '" + at(sim_frags) + "'";
  }
  nlohmann::json ref_json = to_json(ref_stats), sim_json = to_json(r.render);
  ref_json.erase("wall_seconds");
  sim_json.erase("wall_seconds");
  return {{"crc_ref", ref_fb.color_crc32()},
          {"crc_sim", r.fb.color_crc32()},
          {"depth_equal", ref_fb.same_depth(r.fb)},
          {"render_stats_equal", ref_json == sim_json},
          {"fragments_ref", ref_frags.size()},
          {"fragments_sim", sim_frags.size()},
          {"first_mismatch", first},
          {"mismatch", mismatch},
          {"stats", r.to_json()}};
}

void expect_matches_reference(const nlohmann::json& r) {
  ASSERT_FALSE(r.contains("error")) << r["error"];
  EXPECT_EQ(r["crc_sim"], r["crc_ref"]);
  EXPECT_TRUE(r["depth_equal"].get<bool>());
  EXPECT_TRUE(r["render_stats_equal"].get<bool>()) << r["stats"].dump();
  EXPECT_EQ(r["fragments_sim"], r["fragments_ref"]);
  EXPECT_EQ(r["first_mismatch"], -1) << "first differing fragment #" << r["first_mismatch"] << ": "
                                     << r["mismatch"].get<std::string>();
  const auto& s = r["stats"];
  const uint64_t cycles = s["cycles"];
  EXPECT_GE(cycles, s["cycles_lower_bound"].get<uint64_t>());
  for (const auto& [name, st] : s["stages"].items()) {
    SCOPED_TRACE(name);
    EXPECT_EQ(st["busy"].get<uint64_t>() + st["stalled"].get<uint64_t>() + st["starved"].get<uint64_t>(), cycles);
  }
}

nlohmann::json render_and_simulate(const Scene& scene, const Config& cfg) {
  const ArchParams a = ArchParams::resolve(cfg);
  RenderStats ref;
  render_scene(scene, a.raster, ref, {}, Framebuffer::kDefaultTileLog2, 1, a.memory);
  const sc::SimResult r = sc::simulate_scene(scene, a);
  nlohmann::json rj = rastsim::to_json(ref), sj = rastsim::to_json(r.render);
  rj.erase("wall_seconds");
  sj.erase("wall_seconds");
  return {{"ref", rj}, {"sim", sj}, {"stats", r.to_json()}};
}

nlohmann::json simulate_stats(const Scene& scene, const Config& cfg, const sc::SimOptions& opts) {
  return sc::simulate_scene(scene, ArchParams::resolve(cfg), opts).to_json();
}

namespace {
SceneVertex random_vertex(std::mt19937_64& rng, int w, int h) {
  // Up to a quarter of the viewport outside it on each side (clipping, guard band),
  // some vertices exactly on pixel centres or corners.
  std::uniform_real_distribution<double> ux(-0.25 * w, 1.25 * w), uy(-0.25 * h, 1.25 * h), u01(0, 1);
  std::uniform_int_distribution<int> c(0, 255);
  SceneVertex v;
  double x = ux(rng), y = uy(rng);
  if (u01(rng) < 0.2) {
    x = std::floor(x) + 0.5;
    y = std::floor(y);
  }
  v.x = Q64::from_double(x);
  v.y = Q64::from_double(y);
  v.z = u01(rng);
  v.r = uint8_t(c(rng));
  v.g = uint8_t(c(rng));
  v.b = uint8_t(c(rng));
  return v;
}
}  // namespace

Scene random_scene(uint64_t seed, int w, int h, int triangles) {
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int> pick(0, 99);
  Scene s;
  s.source = "random-" + std::to_string(seed);
  auto add = [&](CommandBody b) { s.commands.push_back({std::move(b), {s.source, int(s.commands.size() + 1)}}); };
  add(CmdViewport{w, h});
  add(CmdClear{uint8_t(seed), 32, 64});
  add(CmdClearDepth{1.0});
  int made = 0;
  while (made < triangles) {
    const int r = pick(rng);
    if (r < 3) {
      add(CmdClear{uint8_t(pick(rng)), uint8_t(pick(rng)), 7});
    } else if (r < 6) {
      add(CmdScissor{pick(rng) < 50, w / 8, h / 8, w / 2, h / 2});
    } else if (r < 8) {
      add(CmdViewport{w - w / 4 + pick(rng) % (w / 4 + 1), h});
    } else {
      CmdPrimitives p;
      p.topology = r < 60 ? Topology::List : r < 80 ? Topology::Strip : Topology::Fan;
      const int n = 3 + pick(rng) % 6;
      for (int i = 0; i < n; ++i) p.vertices.push_back(random_vertex(rng, w, h));
      made += int(triangle_count(p));
      add(std::move(p));
    }
  }
  return s;
}

Scene repeat_scene(const Scene& s, int copies) {
  Scene out;
  out.source = s.source + " x" + std::to_string(copies);
  for (int i = 0; i < copies; ++i) out.commands.insert(out.commands.end(), s.commands.begin(), s.commands.end());
  return out;
}

std::vector<std::string> shipped_traces() {
  std::vector<std::string> out;
  for (const auto& e : std::filesystem::recursive_directory_iterator(std::string(RASTSIM_SOURCE_DIR) + "/traces"))
    if (e.path().extension() == ".trace") out.push_back(e.path().string());
  std::sort(out.begin(), out.end());
  return out;
}

Config make_config(const std::vector<std::string>& overrides) {
  Config cfg;
  for (const auto& o : overrides) cfg.apply_override(o);
  cfg.validate();
  return cfg;
}

}  // namespace rastsim::sctest
