// SPDX-License-Identifier: Apache-2.0
// The cycle loop of the co-simulation, one template instance per verilated config
// (Vrast_<config>, generated registry). Internal to model/rtl.
//
// Timing convention (the same as the RTL's and, shifted by nothing, the SystemC
// model's): a stage that takes an item in cycle u and needs n cycles offers its result
// in cycle u + n - 1; a FIFO entry pushed in cycle v is visible in cycle v + 1 (SystemC
// time v + 1); a push into a full FIFO succeeds when the reader pops in the same cycle.
// The testbench stages below follow model/sc/command_fetch.cpp, prim_assembly.cpp and
// rop.cpp exactly; the cycle count is the ROP's last busy cycle + 1, as the model's.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <deque>
#include <memory>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include <verilated.h>
#include <verilated_fst_c.h>

#include "config/timing_params.h"
#include "rtl/cosim.h"
#include "ref/interpolate.h"
#include "ref/pipeline.h"

namespace rastsim::cosim {

// One transaction of the testbench's command stream.
struct TbItem {
  enum Kind { Triangle, Marker, Null } kind = Triangle;
  uint64_t fetch_cost = 1;     // command fetch cycles (header + vertices)
  uint64_t assembly_cost = 1;  // primitive assembly cycles (1 for a marker)
  uint64_t rop_cost = 1;       // markers: ROP cycles (a clear's fast-clear time, else 1)
  int64_t x[3] = {}, y[3] = {};  // snapped raw coordinates
  uint32_t z[3] = {};
  uint32_t rgb[3] = {};        // {b, g, r} packed as the RTL port
  int clip[4] = {};            // x0, y0, x1, y1
  int origin[2] = {};          // x, y
  int tri = -1;                // triangle index (names in TbSetup::tri_names)
};

struct Expected {
  Fragment f;
  int tri = 0;
};

struct TbSetup {
  RtlParams params;                     // of the verilated model (widths, timing)
  // Run-time raster state of the config being simulated, driven on rast_top's static
  // inputs: log2 tile size, fill rule, cull mode (raster_state.h's enum values), front face.
  int tile_log2 = 0;
  int fill_rule = 0, cull_mode = 0, front_ccw = 1;
  std::vector<TbItem> items;
  std::vector<Expected> expected;
  std::vector<std::string> tri_names;   // "file:line triangle k"
  TimingParams timing;                  // the testbench stages' costs and FIFO depths
  CosimOptions opts;
};

using RunFn = void (*)(const TbSetup&, CosimResult&);
struct RegistryEntry {
  const char* name;  // configs/<name>.toml, as the model was built
  RunFn run;
  RtlParams params;  // what the model was built with (compiled in at configure time)
};
const std::vector<RegistryEntry>& rtl_registry();  // generated: rtl_registry.cpp

// Bits [lsb, lsb + w) of a verilated port (C integer or VlWide), w <= 64.
template <class T>
uint64_t port_bits(const T& v, int lsb, int w) {
  const uint64_t mask = (w >= 64) ? ~uint64_t{0} : ((uint64_t{1} << w) - 1);
  if constexpr (std::is_integral_v<T>) {
    return (static_cast<uint64_t>(v) >> lsb) & mask;
  } else {
    uint64_t r = 0;
    for (int i = 0; i < w; ++i) {
      const int b = lsb + i;
      if ((v[b / 32] >> (b % 32)) & 1u) r |= uint64_t{1} << i;
    }
    return r;
  }
}

// A testbench stage: takes an item, is busy `cost` cycles, offers its output in the
// last of them and holds it until taken.
struct TbStage {
  bool active = false;
  uint64_t left = 0;   // busy cycles left, including the current one
  size_t item = 0;
  bool offering() const { return active && left == 1; }
};

template <class V>
void run_rtl(const TbSetup& s, CosimResult& r) {
  const auto t0 = std::chrono::steady_clock::now();
  const RtlParams& p = s.params;
  auto ctx = std::make_unique<VerilatedContext>();
  ctx->traceEverOn(!s.opts.fst_path.empty());
  auto top = std::make_unique<V>(ctx.get(), "rast_top");
  std::unique_ptr<VerilatedFstC> fst;
  if (!s.opts.fst_path.empty()) {
    fst = std::make_unique<VerilatedFstC>();
    top->trace(fst.get(), 99);
    fst->open(s.opts.fst_path.c_str());
  }
  uint64_t time = 0;
  auto half = [&](int clk) {
    top->clk_i = clk;
    top->eval();
    if (fst) fst->dump(time);
    ++time;
  };
  const uint64_t coord_mask = (uint64_t{1} << p.coord_w) - 1;
  top->tile_log2_i = static_cast<uint8_t>(s.tile_log2);
  top->fill_rule_i = static_cast<uint8_t>(s.fill_rule);
  top->cull_mode_i = static_cast<uint8_t>(s.cull_mode);
  top->front_ccw_i = static_cast<uint8_t>(s.front_ccw);
  top->tri_valid_i = 0;
  top->frag_ready_i = 0;
  top->rst_ni = 0;
  half(0);
  half(1);
  top->rst_ni = 1;

  // ---- testbench state ----
  struct Entry {
    size_t item;
    uint64_t pushed;  // cycle of the push: visible from pushed + 1
  };
  std::deque<Entry> cmd_fifo;
  struct Batch {
    uint64_t fragments = 0;
    bool marker = false;
    size_t marker_item = 0;
    uint64_t pushed = 0;
  };
  std::deque<Batch> frag_fifo;
  std::deque<size_t> markers_in_flight;  // marker items sent to the RTL, in order
  Batch staging;
  bool staging_blocked = false;
  TbStage fetch, assembly;
  size_t next_item = 0;
  uint64_t rop_left = 0, last_busy = 0;  // last cycle any stage worked
  size_t next_expected = 0;
  std::mt19937_64 rng(s.opts.backpressure_seed);
  std::bernoulli_distribution stall(s.opts.backpressure);
  const int lanes = p.interp_fragments_per_cycle;
  auto mismatch = [&](const std::string& what) {
    if (r.first_mismatch.empty()) r.first_mismatch = what;
    ++r.mismatches;
  };

  for (uint64_t t = 0;; ++t) {
    if (t >= s.opts.max_cycles) {
      mismatch("simulation did not finish within " + std::to_string(s.opts.max_cycles) + " cycles");
      break;
    }
    // ROP: start the next batch once visible (model/sc/rop.cpp).
    if (rop_left == 0 && !frag_fifo.empty() && frag_fifo.front().pushed < t) {
      const Batch b = frag_fifo.front();
      frag_fifo.pop_front();
      rop_left = b.marker ? s.items[b.marker_item].rop_cost
                          : s.timing.rop_fragment_cycles(b.fragments);
    }
    if (rop_left > 0) {
      --rop_left;
      last_busy = t;
    }
    // A completed batch waiting for room in the fragment FIFO blocks the interpolator.
    if (staging_blocked && frag_fifo.size() < size_t(s.timing.fragment_fifo_entries())) {
      staging.pushed = t;
      frag_fifo.push_back(staging);
      staging = Batch{};
      staging_blocked = false;
    }
    // Primitive assembly: take a visible command (model/sc/prim_assembly.cpp).
    bool cmd_popped = false;
    if (!assembly.active && !cmd_fifo.empty() && cmd_fifo.front().pushed < t) {
      assembly = TbStage{true, s.items[cmd_fifo.front().item].assembly_cost, cmd_fifo.front().item};
      cmd_fifo.pop_front();
      cmd_popped = true;
    }
    (void)cmd_popped;
    // Drive the RTL.
    const bool tri_valid = assembly.offering();
    top->tri_valid_i = tri_valid;
    if (tri_valid) {
      const TbItem& it = s.items[assembly.item];
      top->tri_marker_i = it.kind == TbItem::Marker;
      top->tri_x0_i = static_cast<uint64_t>(it.x[0]) & coord_mask;
      top->tri_y0_i = static_cast<uint64_t>(it.y[0]) & coord_mask;
      top->tri_x1_i = static_cast<uint64_t>(it.x[1]) & coord_mask;
      top->tri_y1_i = static_cast<uint64_t>(it.y[1]) & coord_mask;
      top->tri_x2_i = static_cast<uint64_t>(it.x[2]) & coord_mask;
      top->tri_y2_i = static_cast<uint64_t>(it.y[2]) & coord_mask;
      top->tri_z0_i = it.z[0];
      top->tri_z1_i = it.z[1];
      top->tri_z2_i = it.z[2];
      top->tri_rgb0_i = it.rgb[0];
      top->tri_rgb1_i = it.rgb[1];
      top->tri_rgb2_i = it.rgb[2];
      top->tri_clip_x0_i = it.clip[0];
      top->tri_clip_y0_i = it.clip[1];
      top->tri_clip_x1_i = it.clip[2];
      top->tri_clip_y1_i = it.clip[3];
      top->tri_origin_x_i = it.origin[0];
      top->tri_origin_y_i = it.origin[1];
    }
    const bool frag_ready = !staging_blocked && !(s.opts.backpressure > 0 && stall(rng));
    top->frag_ready_i = frag_ready;
    half(0);
    const bool tri_taken = tri_valid && top->tri_ready_o;
    if (!top->idle_o || top->frag_valid_o || fetch.active || assembly.active) last_busy = std::max(last_busy, t);
    // Fragments out of the RTL.
    if (top->frag_valid_o && frag_ready) {
      if (top->frag_marker_o) {
        if (markers_in_flight.empty()) {
          mismatch("cycle " + std::to_string(t) + ": a marker the testbench never sent");
        } else {
          staging.marker = true;
          staging.marker_item = markers_in_flight.front();
          markers_in_flight.pop_front();
        }
      } else {
        for (int j = 0; j < lanes; ++j) {
          if (!((port_bits(top->frag_lanes_o, j, 1)) & 1)) continue;
          Fragment f;
          f.x = static_cast<int>(port_bits(top->frag_x_o, j * p.pixel_w, p.pixel_w));
          f.y = static_cast<int>(port_bits(top->frag_y_o, j * p.pixel_w, p.pixel_w));
          f.z = static_cast<uint32_t>(port_bits(top->frag_z_o, j * p.depth_w, p.depth_w));
          f.r = static_cast<uint8_t>(port_bits(top->frag_rgb_o, j * 24, 8));
          f.g = static_cast<uint8_t>(port_bits(top->frag_rgb_o, j * 24 + 8, 8));
          f.b = static_cast<uint8_t>(port_bits(top->frag_rgb_o, j * 24 + 16, 8));
          ++staging.fragments;
          ++r.fragments_compared;
          if (next_expected >= s.expected.size()) {
            mismatch("extra fragment from the RTL: " + fragment_trace_line(f));
            continue;
          }
          const Expected& e = s.expected[next_expected++];
          if (!(e.f == f))
            mismatch("fragment #" + std::to_string(next_expected - 1) + " of " + s.tri_names[e.tri] + ": pixel (" +
                     std::to_string(e.f.x) + ", " + std::to_string(e.f.y) + ") expected '" + fragment_trace_line(e.f) +
                     "', RTL gave '" + fragment_trace_line(f) + "'");
        }
      }
      if (top->frag_marker_o || top->frag_last_o) {
        if (frag_fifo.size() < size_t(s.timing.fragment_fifo_entries())) {
          staging.pushed = t;
          frag_fifo.push_back(staging);
          staging = Batch{};
        } else {
          staging_blocked = true;
        }
      }
    }
    // Assembly: count its busy cycle, hand over on a taken offer.
    if (assembly.active) {
      if (assembly.left > 1) {
        --assembly.left;
      } else if (tri_taken) {
        if (s.items[assembly.item].kind == TbItem::Marker) markers_in_flight.push_back(assembly.item);
        assembly.active = false;
      }
    }
    // Command fetch: the next item of the scene (model/sc/command_fetch.cpp).
    if (!fetch.active && next_item < s.items.size()) fetch = TbStage{true, s.items[next_item].fetch_cost, next_item++};
    if (fetch.active) {
      last_busy = std::max(last_busy, t);
      if (fetch.left > 1) {
        --fetch.left;
      } else if (s.items[fetch.item].kind == TbItem::Null) {
        fetch.active = false;  // an empty primitive command: header only, nothing out
      } else if (cmd_fifo.size() < size_t(s.timing.fifo_command)) {
        cmd_fifo.push_back(Entry{fetch.item, t});
        fetch.active = false;
      }
    }
    half(1);
    // Done: nothing left anywhere (idle_o covers the interpolator's pipeline).
    if (next_item >= s.items.size() && !fetch.active && cmd_fifo.empty() && !assembly.active &&
        top->idle_o && !top->frag_valid_o &&
        !staging_blocked && staging.fragments == 0 && !staging.marker && frag_fifo.empty() && rop_left == 0) {
      r.cycles_rtl = last_busy + 1;
      break;
    }
  }
  if (next_expected < s.expected.size())
    mismatch(std::to_string(s.expected.size() - next_expected) + " fragments missing from the RTL, first: #" +
             std::to_string(next_expected) + " of " + s.tri_names[s.expected[next_expected].tri] + ": '" +
             fragment_trace_line(s.expected[next_expected].f) + "'");
  if (!markers_in_flight.empty()) mismatch(std::to_string(markers_in_flight.size()) + " markers lost in the RTL");
  if (fst) fst->close();
  top->final();
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace rastsim::cosim
