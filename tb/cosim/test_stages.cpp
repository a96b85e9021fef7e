// SPDX-License-Identifier: Apache-2.0
// Stage-by-stage agreement of the SystemC model and the RTL (label "cosim";
// docs/microarchitecture.md "Stage statistics"). Its own binary (stages_main.cpp):
// SystemC owns main(), and each SystemC run is in a forked child.
//
// - On a random 2,000-triangle scene (seeded, printed) per shipped config, without
//   backpressure (the model has none on the memory port): every stage's busy cycles
//   agree within 2 % (the bound), busy + stalled + starved = cycles on each side,
//   both sides take the same number of transactions, every fragment matches; the 2D
//   stages are idle on both sides.
// - The same on every 2D scene (traces/2d/*.trace) per shipped config, where the 2D front
//   end and engine work: nine stages, busy within 2 %, equal transactions (so
//   --trace-diff's CSVs have equal rows: the ROP's 2D marker is one transaction on both
//   sides).
// - The same on every clip-space scene (traces/3d/*.trace) per shipped config, with the
//   SystemC model's CRC equal to the RTL's and its cycles within 2 % of them.
// - --trace-diff: two RTL runs, one with the memory answering the ROP 7 cycles late on
//   one transaction (CosimOptions::perturb_rop_*): the CSVs have equal row counts, and the
//   first difference is that transaction, its start equal and its end 7 cycles later.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

#include "scene/scene_io.h"

#include "cosim_test_util.h"
#include "fidelity/run_child.h"
#include "rtlsim/stage_compare.h"
#include "sc/raster_pipeline.h"
#include "timing/stage_table.h"

namespace rastsim::rtlsim {
namespace {

nlohmann::json records_json(const std::vector<StageRecord>& v) {
  nlohmann::json j = nlohmann::json::array();
  for (const StageRecord& r : v)
    j.push_back({{"name", r.name}, {"busy", r.busy}, {"stalled", r.stalled}, {"starved", r.starved},
                 {"transactions", r.transactions}});
  return j;
}

// The SystemC model's stages on `scene`, in a child (one elaboration per process); its
// cycles and framebuffer CRC.
std::vector<StageRecord> model_stages(const Scene& scene, const Config& cfg, uint64_t& cycles, uint32_t* crc = nullptr) {
  const nlohmann::json j = fidelity::run_in_child([&] {
    const sc::SimResult m = sc::simulate_scene(scene, ArchParams::resolve(cfg));
    return nlohmann::json{{"cycles", m.cycles}, {"crc", m.render.framebuffer_crc32},
                          {"stages", records_json(stage_records(m.stages))}};
  });
  cycles = j.at("cycles").get<uint64_t>();
  if (crc) *crc = j.at("crc").get<uint32_t>();
  std::vector<StageRecord> v;
  for (const auto& s : j.at("stages"))
    v.push_back(StageRecord{s.at("name").get<std::string>(), s.at("busy").get<uint64_t>(),
                            s.at("stalled").get<uint64_t>(), s.at("starved").get<uint64_t>(),
                            s.at("transactions").get<uint64_t>(), {}});
  return v;
}

// A stage's name in both sides' records (timing/stage_table.h).
std::string name_of(StageId id) { return std::string(stage_name(id)); }

// Every stage's figures agree on `scene`: busy within `bound` (with `busy_nonzero` the
// stages that must have worked), the three states add up to each side's cycles, and
// both sides take the same number of transactions.
// With `same_image`, the SystemC model's framebuffer CRC equals the RTL's and the
// reference's, and its cycles are within `bound` of the RTL's.
void expect_stages_agree(const Scene& scene, const Config& cfg, const std::set<std::string>& busy_nonzero,
                         const std::set<std::string>& idle, bool same_image = false) {
  const CosimResult r = run_cosim(scene, ArchParams::resolve(cfg));
  expect_clean(r);
  uint64_t cycles_model = 0;
  uint32_t crc_model = 0;
  const std::vector<StageRecord> model = model_stages(scene, cfg, cycles_model, &crc_model);
  if (same_image) {
    EXPECT_EQ(r.crc_rtl, r.crc_ref);
    EXPECT_EQ(crc_model, r.crc_rtl);
    EXPECT_LE(std::abs(double(cycles_model) - double(r.cycles_rtl)), 0.02 * double(r.cycles_rtl))
        << "cycles: model " << cycles_model << ", RTL " << r.cycles_rtl;
  }
  const std::vector<StageAgreement> a = compare_stages(model, r.stages);
  ASSERT_EQ(a.size(), kStageCount) << "every stage of the table is counted by the RTL co-simulation and the SystemC model";
  for (size_t k = 0; k < a.size(); ++k) {
    const StageAgreement& s = a[k];
    SCOPED_TRACE(s.name);
    EXPECT_EQ(s.name, kStages[k].name);
    std::cout << s.name << ": busy model " << s.model.busy << ", RTL " << s.rtl.busy << "; transactions model "
              << s.model.transactions << ", RTL " << s.rtl.transactions << "\n";
    if (busy_nonzero.count(s.name)) {
      EXPECT_GT(s.rtl.busy, 0u);
    }
    if (idle.count(s.name)) {
      EXPECT_EQ(s.rtl.busy, 0u);
      EXPECT_EQ(s.model.busy, 0u);
    }
    EXPECT_LE(std::abs(s.busy_error), 0.02);
    EXPECT_EQ(s.model.transactions, s.rtl.transactions);
    EXPECT_EQ(s.rtl.busy + s.rtl.stalled + s.rtl.starved, r.cycles_rtl);
    EXPECT_EQ(s.model.busy + s.model.stalled + s.model.starved, cycles_model);
  }
}

class StageAgreementTest : public ::testing::TestWithParam<const char*> {};

TEST_P(StageAgreementTest, RandomSceneBusyWithinTwoPercent) {
  // memory.model = fixed for CI time (2000 triangles over the DRAM took 15-66 s a config on
  // 2 loaded cores, desktop's 1080p the most); ClipSpaceScenesBusyWithinTwoPercent checks
  // every stage with the configs' dram.
  Config cfg = load_shipped_config_fixed_memory(GetParam());
  cfg.apply_override("raster.out_of_range=cull");  // some vertices leave the guard band
  const uint64_t seed = 0x57a9e000u;
  std::cout << "seed " << seed << "\n";
  const Scene scene = random_scene(cfg, seed, 2000);
  std::set<std::string> triangle, idle;  // idle: the 2D path, and the front end (no clip space)
  for (const StageInfo& st : kStages) (st.path == StagePath::Triangle ? triangle : idle).insert(std::string(st.name));
  expect_stages_agree(scene, cfg, triangle, idle);
}

TEST_P(StageAgreementTest, TwoDScenesBusyWithinTwoPercent) {
  // memory.model = fixed: the per-stage figures without DRAM stalls (the test card with
  // the configs' dram: the ctest cosim.dram.2d.test_card).
  const Config cfg = load_shipped_config_fixed_memory(GetParam());
  const std::filesystem::path dir = std::filesystem::path(RASTSIM_SOURCE_DIR) / "traces" / "2d";
  int scenes = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    if (e.path().extension() != ".trace") continue;
    SCOPED_TRACE(e.path().string());
    ++scenes;
    expect_stages_agree(load_trace(e.path().string()), cfg,
                        {name_of(StageId::CommandFetch), name_of(StageId::Rop), name_of(StageId::Draw2dSetup),
                         name_of(StageId::Engine2d)},
                        {});
  }
  EXPECT_GT(scenes, 0) << "no 2D scene in " << dir;
}

// The clip-space scenes (traces/3d: the testbench runs the reference front end, the RTL
// interpolates perspective-correctly): stages within 2 %, the RTL's fragments (texture
// coordinates included) the reference's, and the SystemC model's image and cycles the RTL's.
TEST_P(StageAgreementTest, ClipSpaceScenesBusyWithinTwoPercent) {
  const Config cfg = load_shipped_config(GetParam());
  const std::filesystem::path dir = std::filesystem::path(RASTSIM_SOURCE_DIR) / "traces" / "3d";
  int scenes = 0;
  std::set<std::string> triangle, idle;  // idle: the 2D path, and the texture stage (untextured scenes)
  for (const StageInfo& st : kStages)
    (st.path == StagePath::TwoD || st.path == StagePath::Texture ? idle : triangle).insert(std::string(st.name));
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    if (e.path().extension() != ".trace") continue;
    SCOPED_TRACE(e.path().string());
    ++scenes;
    expect_stages_agree(load_trace(e.path().string()), cfg, triangle, idle, true);
  }
  EXPECT_GT(scenes, 0) << "no clip-space scene in " << dir;
}

// The testbench's geometry front end against a hand-worked schedule: a viewport, then
// one clip-space fan of two unclipped triangles (4 vertices, w = 1), with front_end.
// cycles_per_primitive = 2, vertices_per_cycle = 1, latency_cycles = 4 and 3 vertices a
// fetch cycle. Fetch: the viewport's header in cycle 0, the command whole in cycles 1-3
// (header + ceil(4 / 3)), pushed in cycle 3. The front end takes it in cycle 4 and charges
// each triangle (a fan triangle is a primitive: 3 vertices) 2 + 3 = 5 cycles (cycles 4-8
// and 9-13), the end 0; the first triangle,
// pushed in cycle 8, reaches assembly 1 + 4 cycles later, in cycle 13. Assembly: the
// viewport (1 cycle), the marker, the two triangles (1 cycle each), the end.
TEST(TestbenchFrontEnd, ClipSpaceCommandFollowsTheHandWorkedSchedule) {
  Config cfg = load_shipped_config("default");
  for (const char* kv : {"front_end.cycles_per_primitive=2", "front_end.clip_cycles_per_vertex=2",
                         "front_end.vertices_per_cycle=1", "front_end.latency_cycles=4", "fetch.cycles_per_command=1",
                         "fetch.vertices_per_cycle=3", "assembly.cycles_per_triangle=1"})
    cfg.apply_override(kv);
  const Scene scene = parse_trace(
      "viewport 64 64\n"
      "fan\n"
      "v4 -0.5 -0.5 0.5 1 255 0 0\nv4 0.5 -0.5 0.5 1 0 255 0\nv4 0.5 0.5 0.5 1 0 0 255\n"
      "v4 -0.5 0.5 0.5 1 255 255 0\n"
      "end\n",
      "two.trace");
  CosimOptions o;
  o.record_transactions = true;
  const CosimResult r = run_cosim(scene, ArchParams::resolve(cfg), o);
  expect_clean(r);
  const auto stage = [&](StageId id) {
    for (const StageRecord& s : r.stages)
      if (s.name == stage_name(id)) return s;
    throw std::runtime_error("no stage " + name_of(id));
  };
  const StageRecord fetch = stage(StageId::CommandFetch), fe = stage(StageId::FrontEnd),
                    pa = stage(StageId::PrimAssembly);
  EXPECT_EQ(fetch.busy, 4u);
  EXPECT_EQ(fetch.transactions, 2u);
  EXPECT_EQ(fe.busy, 10u);
  EXPECT_EQ(fe.transactions, 1u);
  ASSERT_EQ(fe.spans.size(), 1u);
  EXPECT_EQ(fe.spans[0].start, 4u);
  EXPECT_EQ(fe.spans[0].end, 14u);
  EXPECT_EQ(pa.busy, 3u);
  EXPECT_EQ(pa.transactions, 5u);  // viewport, marker, 2 triangles, end
  ASSERT_EQ(pa.spans.size(), 5u);
  EXPECT_EQ(pa.spans[2].start, 13u);  // the first triangle
  EXPECT_EQ(pa.spans[3].start, 18u);  // the second: pushed in cycle 13, + 1 + 4
}

INSTANTIATE_TEST_SUITE_P(ShippedConfigs, StageAgreementTest,
                         ::testing::Values("default", "d3d11", "embedded", "desktop"),
                         [](const auto& info) { return std::string(info.param); });

const StageRecord& rop(const CosimResult& r) {
  for (const StageRecord& s : r.stages)
    if (s.name == stage_name(StageId::Rop)) return s;
  throw std::runtime_error("no rop stage");
}

uint64_t csv_rows(const std::filesystem::path& p) {
  std::ifstream f(p);
  std::string line;
  uint64_t n = 0;
  while (std::getline(f, line)) ++n;
  return n - 1;  // the header
}

TEST(TraceDiff, PerturbedRopTransactionIsTheFirstDifference) {
  // memory.model = fixed: the hand-worked expectation needs ROP transactions that do not
  // overlap (with the config's dram transaction 6 starts one cycle before 5 ends, so its
  // start is the earliest difference).
  Config cfg = load_shipped_config_fixed_memory("default");
  cfg.apply_override("raster.out_of_range=cull");
  const Scene scene = random_scene(cfg, 0x7d1ffu, 200);
  CosimOptions o;
  o.record_transactions = true;
  const CosimResult base = run_cosim(scene, ArchParams::resolve(cfg), o);
  expect_clean(base);
  // Identical runs: identical files.
  const std::string dir = ::testing::TempDir() + "rastsim_trace_diff";
  TraceDiff same = write_trace_diff(dir, compare_stages(base.stages, base.stages));
  EXPECT_FALSE(same.differs) << same.first;
  // Transaction 5 of the ROP 7 cycles longer.
  o.perturb_rop_transaction = 5;
  o.perturb_rop_cycles = 7;
  const CosimResult slow = run_cosim(scene, ArchParams::resolve(cfg), o);
  expect_clean(slow);
  const TraceDiff d = write_trace_diff(dir, compare_stages(base.stages, slow.stages));
  EXPECT_EQ(csv_rows(dir + "/model.csv"), d.rows_model);
  EXPECT_EQ(csv_rows(dir + "/rtl.csv"), d.rows_rtl);
  EXPECT_EQ(d.rows_model, d.rows_rtl);
  EXPECT_GT(d.rows_model, 500u);
  ASSERT_TRUE(d.differs);
  const StageSpan& b = rop(base).spans.at(5);
  const StageSpan& s = rop(slow).spans.at(5);
  EXPECT_EQ(s.start, b.start);
  EXPECT_EQ(s.end, b.end + 7);
  EXPECT_EQ(d.earliest, "rop transaction 5: model [" + std::to_string(b.start) + ", " + std::to_string(b.end) +
                            "), RTL [" + std::to_string(s.start) + ", " + std::to_string(s.end) + ")");
  // The transactions before it are untouched.
  for (size_t k = 0; k < 5; ++k) {
    EXPECT_EQ(rop(base).spans[k].start, rop(slow).spans[k].start);
    EXPECT_EQ(rop(base).spans[k].end, rop(slow).spans[k].end);
  }
}

}  // namespace
}  // namespace rastsim::rtlsim
