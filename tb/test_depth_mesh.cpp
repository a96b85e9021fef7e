// SPDX-License-Identifier: Apache-2.0
// The oracle score on a real mesh (docs/depth-culling.md, "Figures"): the Stanford bunny
// of glmark2-data (69,666 triangles, placed by the schema's default view, on
// configs/d3d11.toml: 640 x 480, 16 px tiles) or, where glmark2-data is not installed,
// the torus of scripts/hiz_study (scripts/gen_torus --size 480 --rings 96 --sides 48:
// 9216 triangles; the committed 128 px traces/torus.trace has triangles too small for a
// 16 px tile's bound, 0.73), its triangles drawn front to back: sorted by
// their nearest vertex depth (the smallest z of the three, z 0 nearest), the key of
// scripts/depth_order. Hi-Z alone (depth.hiz = max, 4 px blocks, table on chip, early Z
// off) must remove >= 90 % of the fragments that fail the late depth test; the random
// order's figure is printed (the doc states it); early Z makes the oracle exactly 1; the
// image is the same in every order and with Hi-Z off.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "config/config.h"
#include "config/obj_placement.h"
#include "config/raster_state_config.h"
#include "ref/pipeline.h"
#include "scene/scene_io.h"
#include "util/process.h"

namespace rastsim {
namespace {

namespace fs = std::filesystem;

// The bunny where glmark2-data is installed (RASTSIM_GLMARK2_MODELS, as scripts/workloads).
std::string bunny_path() {
  const char* env = std::getenv("RASTSIM_GLMARK2_MODELS");
  const fs::path p = fs::path(env ? env : "/usr/share/glmark2/models") / "bunny.obj";
  return fs::exists(p) ? p.string() : std::string();
}

using Tri = std::array<SceneVertex, 3>;

// The scene's state commands, then every screen-space triangle in `order`: "f2b" nearest
// vertex depth first (ties in drawing order), "random" a seeded shuffle, else as drawn.
Scene reorder(const Scene& in, const std::string& order) {
  Scene out;
  std::vector<Tri> tris;
  for (const Command& c : in.commands) {
    const auto* p = std::get_if<CmdPrimitives>(&c.body);
    if (!p) {
      out.commands.push_back(c);
      continue;
    }
    const std::vector<SceneVertex>& v = p->vertices;
    for (size_t k = 0; k + 2 < v.size(); k += (p->topology == Topology::List ? 3 : 1)) {
      if (p->topology == Topology::Fan) tris.push_back({v[0], v[k + 1], v[k + 2]});
      else if (p->topology == Topology::Strip && k % 2) tris.push_back({v[k + 1], v[k], v[k + 2]});  // the strip's winding
      else tris.push_back({v[k], v[k + 1], v[k + 2]});
    }
  }
  const auto nearest = [](const Tri& t) { return std::min({t[0].z, t[1].z, t[2].z}); };
  if (order == "f2b")
    std::stable_sort(tris.begin(), tris.end(), [&](const Tri& a, const Tri& b) { return nearest(a) < nearest(b); });
  if (order == "random") std::shuffle(tris.begin(), tris.end(), std::mt19937(29));
  CmdPrimitives all;
  for (const Tri& t : tris) all.vertices.insert(all.vertices.end(), t.begin(), t.end());
  out.commands.push_back({all, {"reordered", 1}});
  return out;
}

RenderStats render(const Scene& scene, const RasterState& st) {
  RenderStats s;
  render_scene(scene, st, s);
  return s;
}

TEST(DepthHizMesh, OracleFrontToBack) {
  Config cfg;
  cfg.load_file(std::string(RASTSIM_SOURCE_DIR) + "/configs/d3d11.toml");
  const std::string bunny = bunny_path();
  Scene mesh;
  if (bunny.empty()) {
    ProcessOptions o;
    o.out = Sink::Capture;
    const ProcessResult t = run_process({std::string(RASTSIM_SOURCE_DIR) + "/scripts/gen_torus", "--size", "480",
                                         "--rings", "96", "--sides", "48"}, o);
    if (!t.ok()) GTEST_SKIP() << "no glmark2-data and scripts/gen_torus failed";
    mesh = parse_trace(t.out, "torus.trace");
  } else {
    mesh = load_obj(bunny, obj_placement_from_config(cfg));
  }
  RasterState st = raster_state_from_config(cfg);
  st.depth_func = DepthFunc::Less;
  st.depth_write = true;
  const RenderStats off = render(reorder(mesh, "trace"), st);
  st.hiz_mode = HizMode::Max;
  st.hiz_block = 4;
  st.hiz_bytes = int64_t{1} << 30;
  for (const char* order : {"f2b", "trace", "random"}) {
    SCOPED_TRACE(order);
    const Scene scene = reorder(mesh, order);
    st.depth_early = false;
    const RenderStats hiz = render(scene, st);
    std::printf("%s, %s: Hi-Z alone (max, 4 px blocks) removes %.4f of the late failures "
                "(%llu tiles culled, %llu fragments passed)\n",
                bunny.empty() ? "torus.trace" : "bunny", order, hiz_culled_fraction(hiz),
                (unsigned long long)hiz.hiz.tiles_culled, (unsigned long long)hiz.fragments_passed);
    EXPECT_EQ(hiz.framebuffer_crc32, off.framebuffer_crc32);
    EXPECT_EQ(hiz_oracle_fraction(hiz), hiz_culled_fraction(hiz));  // early Z off
    if (std::string(order) == "f2b") {
      EXPECT_GE(hiz_culled_fraction(hiz), 0.90);
    }
    st.depth_early = true;
    const RenderStats both = render(scene, st);
    EXPECT_EQ(both.framebuffer_crc32, off.framebuffer_crc32);
    EXPECT_EQ(hiz_oracle_fraction(both), 1.0);
  }
}

// scene.obj_order: the cube's 12 triangles (6 quads, 2 each) front to back have
// non-decreasing nearest corner depth face by face, back to front non-increasing, and
// both are the file's faces, reordered (the same multiset of nearest depths).
TEST(DepthHizMesh, ObjOrderSortsFacesByNearestCorner) {
  std::vector<std::vector<double>> keys;
  for (const char* order : {"file", "front_to_back", "back_to_front"}) {
    Config cfg;
    cfg.apply_override(std::string("scene.obj_order=") + order);
    const Scene s = load_obj(std::string(RASTSIM_SOURCE_DIR) + "/tb/data/cube.obj", obj_placement_from_config(cfg));
    std::vector<double> k;  // a face's nearest corner depth (its two triangles share the face's corners)
    for (const Command& c : s.commands)
      if (const auto* p = std::get_if<CmdPrimitives>(&c.body)) {
        double z = 1;
        for (const SceneVertex& v : p->vertices) z = std::min(z, v.z);
        k.push_back(z);
      }
    keys.push_back(k);
  }
  ASSERT_EQ(keys[0].size(), 6u);  // one command a face (scene.obj_faces_per_command = 1)
  EXPECT_TRUE(std::is_sorted(keys[1].begin(), keys[1].end()));
  EXPECT_TRUE(std::is_sorted(keys[2].rbegin(), keys[2].rend()));
  EXPECT_FALSE(std::is_sorted(keys[0].begin(), keys[0].end()) && std::is_sorted(keys[0].rbegin(), keys[0].rend()));
  for (auto& k : keys) std::sort(k.begin(), k.end());
  EXPECT_EQ(keys[0], keys[1]);
  EXPECT_EQ(keys[0], keys[2]);
}

}  // namespace
}  // namespace rastsim
