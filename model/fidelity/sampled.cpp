// SPDX-License-Identifier: Apache-2.0
#include "fidelity/sampled.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <map>
#include <random>
#include <stdexcept>

#include "fidelity/student_t.h"
#include "config/timing_params.h"
#include "ref/pipeline.h"
#include "ref/prim_assembly.h"
#include "sc/raster_pipeline.h"

namespace rastsim::fidelity {

namespace {

using Busy = std::array<uint64_t, kStageCount>;

// A stratum with fewer uncertain units than this is simulated whole: a ratio and its
// residual variance need a few units.
constexpr size_t kMinStratumUnits = 4;

// Certain batches needed for a stratum's variance floor (extrapolate).
constexpr size_t kFloorUnits = 3;

// How long a command's cycles can hold the pipeline, in its own busiest stage's cycles
// (plan_units).
constexpr double kSpill = 2.0;

// A primitives command with a triangle: cut into batches; every other command is a unit
// of its own.
bool is_triangle_command(const Command& c) {
  return visit_command(c, Overloaded{
      state_commands([] { return false; }),
      [](const CmdPrimitives& p) { return triangle_count(p) > 0; },
      [](const CmdDraw2d&) { return false; },
  });
}

Busy busy_of(const EstimateResult& r) {
  Busy b{};
  for (size_t s = 0; s < kStageCount; ++s) b[s] = r.stages[s].busy;
  return b;
}

// Triangles [k0, k1) of a primitive command as a command of their own: a list keeps its
// vertices 3k0..3k1, a strip k0..k1+1 (k0 is even, so the winding is the original's),
// a fan its centre and k0+1..k1+1.
Command slice(const Command& c, size_t k0, size_t k1) {
  const auto& p = std::get<CmdPrimitives>(c.body);
  CmdPrimitives out;
  out.topology = p.topology;
  const auto& v = p.vertices;
  switch (p.topology) {
    case Topology::List:
      out.vertices.assign(v.begin() + long(3 * k0), v.begin() + long(3 * k1));
      break;
    case Topology::Strip:
      out.vertices.assign(v.begin() + long(k0), v.begin() + long(k1 + 2));
      break;
    case Topology::Fan:
      out.vertices.push_back(v[0]);
      out.vertices.insert(out.vertices.end(), v.begin() + long(k0 + 1), v.begin() + long(k1 + 2));
      break;
    case Topology::Points:  // clip-space only: plan_units rejects them
    case Topology::Lines:
    case Topology::LineStrip:
    case Topology::LineLoop: break;
  }
  return Command{std::move(out), c.loc};
}

// The analytic walk's busy totals where command fetch starts triangle k of command cmd
// (k = 0 for a command without triangles).
struct Mark {
  size_t cmd, k;
  Busy busy;
};

// A unit's marks [begin, end); whole: one command that is not a triangle batch.
struct MarkRange {
  size_t begin, end;
  bool whole;
};

// The busy totals at mark i, or at the end of the walk past the last.
const Busy& busy_at(const std::vector<Mark>& marks, size_t i, const Busy& end_busy) {
  return i < marks.size() ? marks[i].busy : end_busy;
}

// Cuts the marks into units: each command that is not a triangle command whole, runs of
// triangle commands into batches of `batch` triangles, cut where a strip restarts on an
// even triangle.
std::vector<MarkRange> cut_units(const Scene& scene, const std::vector<Mark>& marks, size_t batch) {
  std::vector<MarkRange> ranges;
  for (size_t i = 0; i < marks.size();) {
    if (!is_triangle_command(scene.commands[marks[i].cmd])) {
      ranges.push_back({i, i + 1, true});
      ++i;
      continue;
    }
    size_t j = i, tris = 0;
    while (j < marks.size() && is_triangle_command(scene.commands[marks[j].cmd])) {
      if (tris >= batch && marks[j].k % 2 == 0) break;  // a strip restarts on an even triangle
      ++tris;
      ++j;
    }
    ranges.push_back({i, j, false});
    i = j;
  }
  return ranges;
}

// The unit of `range`: its stratum (the stage busiest over it) and x (that stage's busy
// cycles), and its pieces (a whole command, or runs of triangles of one command each).
Unit unit_of(const std::vector<Mark>& marks, const MarkRange& range, const Busy& end_busy) {
  Unit unit;
  const Busy& b0 = marks[range.begin].busy;
  const Busy& b1 = busy_at(marks, range.end, end_busy);
  for (size_t s = 0; s < kStageCount; ++s) {
    const double w = double(b1[s] - b0[s]);
    if (w > unit.x || unit.stratum < 0) {
      unit.x = w;
      unit.stratum = int(s);
    }
  }
  if (range.whole) {
    unit.pieces.push_back({marks[range.begin].cmd, 0, 0, true});
    return unit;
  }
  for (size_t m = range.begin; m < range.end; ++m) {
    if (unit.pieces.empty() || unit.pieces.back().command != marks[m].cmd)
      unit.pieces.push_back({marks[m].cmd, marks[m].k, marks[m].k, false});
    unit.pieces.back().k1 = marks[m].k + 1;
    ++unit.triangles;
  }
  return unit;
}

// Certain: other commands, the first batch after one (or the first of all: pipeline
// fill, a clear's ROP time), the last unit (drain, resolve pass). A command's time (a
// clear's or 2D draw's ROP cycles) can outlast the batch after it: command fetch runs
// ahead while the FIFOs fill. Batches after it are certain until every stage has had
// kSpill times the command's busiest stage's cycles of work since it (analytic walk),
// so the spill is measured, not scaled up by a sampled batch.
void mark_certain_around_commands(std::vector<Unit>& units, const std::vector<MarkRange>& ranges,
                                  const std::vector<Mark>& marks, const Busy& end_busy) {
  Busy spill_from{};
  double spill = 0;
  for (size_t u = 0; u < units.size(); ++u) {
    Unit& unit = units[u];
    const bool whole = ranges[u].whole;
    const Busy& b0 = marks[ranges[u].begin].busy;
    unit.certain = whole || u == 0 || ranges[u - 1].whole || u + 1 == ranges.size();
    double since = 0;  // the busiest stage's cycles since the spilling command
    for (size_t s = 0; s < kStageCount; ++s) since = std::max(since, double(b0[s] - spill_from[s]));
    if (whole) {
      if (kSpill * unit.x >= kSpill * spill - since) {  // outlasts the previous command's spill
        spill_from = busy_at(marks, ranges[u].end, end_busy);
        spill = unit.x;
      }
    } else if (spill > 0) {
      if (since < kSpill * spill) unit.certain = true;
      else spill = 0;
    }
  }
}

// Certain head: until every FIFO could have filled (`fill` triangles, one an entry at
// least), command fetch runs ahead of the bottleneck and a batch's measured cycles are
// short. Strata too small to sample are simulated whole.
void mark_certain_head_and_small_strata(std::vector<Unit>& units, uint64_t fill) {
  uint64_t seen = 0;
  for (Unit& u : units) {
    if (seen >= fill) break;
    u.certain = true;
    seen += u.triangles;
  }
  std::map<int, size_t> count;
  for (const Unit& u : units)
    if (!u.certain) ++count[u.stratum];
  for (Unit& u : units)
    if (!u.certain && count[u.stratum] < kMinStratumUnits) u.certain = true;
}

}  // namespace

uint64_t triangle_path_entries(const TimingParams& p) {
  uint64_t entries = 0;
  for (const FifoInfo& f : kFifos)
    if (on_triangle_path(f)) entries += uint64_t(p.fifo_entries(f.id));
  return entries;
}

UnitPlan plan_units(const Scene& scene, const ArchParams& arch, size_t batch) {
  // Units are simulated by the SystemC model, which has no front end: a clip-space
  // command is an error here, before the analytic walk cuts its triangles into marks.
  for (const Command& cmd : scene.commands)
    if (const auto* p = std::get_if<CmdPrimitives>(&cmd.body)) reject_clip_space(*p, cmd.loc);
  std::vector<Mark> marks;
  UnitPlan plan;
  plan.analytic = estimate_scene(scene, arch, [&](size_t c, size_t k, const EstimateResult& r) {
    marks.push_back({c, k, busy_of(r)});
  });
  const uint64_t triangles = plan.analytic.render.triangles_in;
  // The triangle path's FIFO entries: how far (in triangles, one an entry at least)
  // command fetch can run ahead of the bottleneck, so how much of a batch's measured
  // cycles its context (the batch before it in the sampled run) can shift.
  const uint64_t fill = triangle_path_entries(arch.timing);
  if (batch == 0) batch = std::max<size_t>({8, size_t((triangles + 199) / 200), size_t(2 * fill)});
  batch += batch % 2;
  plan.batch = batch;

  const std::vector<MarkRange> ranges = cut_units(scene, marks, batch);
  const Busy end_busy = busy_of(plan.analytic);
  for (const MarkRange& range : ranges) plan.units.push_back(unit_of(marks, range, end_busy));
  mark_certain_around_commands(plan.units, ranges, marks, end_busy);
  plan.head_triangles = fill;
  plan.warm_triangles = size_t(fill);
  mark_certain_head_and_small_strata(plan.units, fill);
  return plan;
}

std::vector<bool> draw_sample(const UnitPlan& plan, double fraction, uint64_t seed) {
  if (!(fraction > 0 && fraction <= 1)) throw std::invalid_argument("sample fraction must be in (0, 1]");
  std::vector<bool> chosen(plan.units.size(), false);
  std::map<int, std::vector<size_t>> strata;
  double x_total = 0;
  size_t n_uncertain = 0;
  for (size_t i = 0; i < plan.units.size(); ++i) {
    if (plan.units[i].certain) {
      chosen[i] = true;
      continue;
    }
    strata[plan.units[i].stratum].push_back(i);
    x_total += plan.units[i].x;
    ++n_uncertain;
  }
  const double n = std::ceil(fraction * double(n_uncertain) - 1e-9);
  std::mt19937_64 rng(seed * 0x9e3779b97f4a7c15ull + 0x5851f42d4c957f2dull);
  for (auto& [h, idx] : strata) {
    double x_h = 0;
    for (size_t i : idx) x_h += plan.units[i].x;
    const double share = x_total > 0 ? x_h / x_total : double(idx.size()) / double(n_uncertain);
    size_t n_h = size_t(std::llround(n * share));
    n_h = std::clamp<size_t>(n_h, std::min<size_t>(2, idx.size()), idx.size());
    if (fraction >= 1) n_h = idx.size();
    for (size_t k = 0; k < n_h; ++k) {  // partial Fisher-Yates
      const size_t j = k + size_t(rng() % (idx.size() - k));
      std::swap(idx[k], idx[j]);
      chosen[idx[k]] = true;
    }
  }
  return chosen;
}

SubScene sub_scene(const Scene& scene, const UnitPlan& plan, const std::vector<bool>& chosen) {
  struct Slice {
    size_t cmd, k0, k1;
    bool whole;
  };
  std::vector<Slice> slices;
  SubScene out;
  // Appends pieces; the first one starts a segment of `unit` (SIZE_MAX: a warm-up).
  auto append = [&](const std::vector<Piece>& pieces, size_t unit) {
    bool first = true;
    for (const Piece& p : pieces) {
      if (!p.whole && !slices.empty() && !slices.back().whole && slices.back().cmd == p.command &&
          slices.back().k1 == p.k0)
        slices.back().k1 = p.k1;
      else
        slices.push_back({p.command, p.k0, p.k1, p.whole});
      if (first) out.segments.push_back({slices.size() - 1, p.k0 - slices.back().k0, unit});
      first = false;
    }
  };
  for (size_t u = 0; u < plan.units.size(); ++u) {
    if (!chosen[u]) continue;
    if (u > 0 && !chosen[u - 1] && plan.warm_triangles > 0 && !plan.units[u - 1].pieces.empty() &&
        !plan.units[u - 1].pieces.front().whole) {
      // The predecessor's last warm_triangles triangles (a strip's slice starts on an even
      // triangle, or where the piece starts).
      std::vector<Piece> warm;
      size_t left = plan.warm_triangles;
      const auto& pieces = plan.units[u - 1].pieces;
      for (size_t i = pieces.size(); i-- > 0 && left > 0;) {
        Piece p = pieces[i];
        const size_t n = p.k1 - p.k0;
        if (n > left) {
          size_t k0 = p.k1 - left;
          const auto& prim = std::get<CmdPrimitives>(scene.commands[p.command].body);
          if (prim.topology == Topology::Strip && k0 % 2 != 0) k0 = k0 - 1 < p.k0 ? p.k0 : k0 - 1;
          p.k0 = std::max(k0, p.k0);
        }
        left -= std::min(left, p.k1 - p.k0);
        out.warm_triangles += p.k1 - p.k0;
        warm.insert(warm.begin(), p);
      }
      append(warm, SIZE_MAX);
    }
    append(plan.units[u].pieces, u);
  }
  out.scene.source = scene.source;
  out.scene.commands.reserve(slices.size());
  for (const Slice& s : slices) {
    const Command& c = scene.commands[s.cmd];
    const bool all = s.whole || (s.k0 == 0 && s.k1 == triangle_count(std::get<CmdPrimitives>(c.body)));
    out.scene.commands.push_back(all ? c : slice(c, s.k0, s.k1));
  }
  return out;
}

namespace {

struct Stratum {
  size_t N = 0, n = 0;
  double X = 0, sx = 0, sy = 0;
  std::vector<size_t> sample;
};

// The units sorted for the estimator: certain units' cycles summed, uncertain ones into
// their strata, and the certain batches' y/x (not the first or last unit nor one right
// after a command, whose cycles carry the fill, drain or a command's time): the spread
// of the ratio that a small sample can miss (two sampled batches with equal ratios by
// chance). Counts units in r.
struct UnitTally {
  std::map<int, Stratum> strata;
  std::map<int, std::vector<double>> certain_ratios;
  std::vector<double> all_ratios;
  double certain = 0;
};

UnitTally tally_units(const UnitPlan& plan, const std::vector<bool>& chosen, const std::vector<double>& y,
                      SampledResult& r) {
  UnitTally t;
  double x_all = 0, x_sim = 0;
  for (size_t u = 0; u < plan.units.size(); ++u) {
    const Unit& unit = plan.units[u];
    x_all += unit.x;
    if (chosen[u]) {
      ++r.units_simulated;
      x_sim += unit.x;
    }
    if (unit.certain) {
      ++r.units_certain;
      t.certain += y[u];
      const bool batch = !unit.pieces.empty() && !unit.pieces.front().whole;
      if (batch && unit.x > 0 && u > 0 && u + 1 < plan.units.size() && !plan.units[u - 1].pieces.front().whole) {
        t.certain_ratios[unit.stratum].push_back(y[u] / unit.x);
        t.all_ratios.push_back(y[u] / unit.x);
      }
      continue;
    }
    Stratum& s = t.strata[unit.stratum];
    ++s.N;
    s.X += unit.x;
    if (!chosen[u]) continue;
    ++s.n;
    s.sx += unit.x;
    s.sy += y[u];
    s.sample.push_back(u);
  }
  r.work_fraction_simulated = x_all > 0 ? x_sim / x_all : 1;
  return t;
}

// Variance floor: the certain batches' ratio spread `rs` (this stratum's if it has
// kFloorUnits of them, else all strata's), at the stratum's mean unit size: a residual
// y - R x of a batch of mean size, were its ratio as spread as the certain batches'.
// Raises s2 to it (with its degrees of freedom) and adds the raise to r.variance_floor.
void apply_variance_floor(const Stratum& s, const std::vector<double>& rs, double& s2, double& df, SampledResult& r) {
  if (rs.size() < kFloorUnits) return;
  double m = 0, q = 0;
  for (double v : rs) m += v;
  m /= double(rs.size());
  for (double v : rs) q += (v - m) * (v - m);
  // The ratio's variance times the stratum's mean x squared.
  const double xbar = s.X / double(s.N);
  const double floor = q / double(rs.size() - 1) * xbar * xbar;
  if (floor > s2) {
    r.variance_floor += double(s.N) * double(s.N) * (1 - double(s.n) / double(s.N)) * (floor - s2) / double(s.n);
    s2 = floor;
    df = double(rs.size() - 1);
  }
}

}  // namespace

SampledResult extrapolate(const UnitPlan& plan, const std::vector<bool>& chosen, const std::vector<double>& y,
                          double confidence) {
  SampledResult r;
  r.confidence = confidence;
  r.analytic = plan.analytic;
  r.units_total = plan.units.size();
  r.batch_triangles = plan.batch;
  const UnitTally tally = tally_units(plan, chosen, y, r);
  double total = tally.certain, var = 0, df_den = 0;
  for (const auto& [h, s] : tally.strata) {
    if (s.n == 0) throw std::logic_error("extrapolate: a stratum without a sampled unit");
    ++r.strata;
    // Ratio estimator on the analytic work; with no analytic work, plain expansion.
    const bool ratio = s.sx > 0;
    const double R = ratio ? s.sy / s.sx : s.sy / double(s.n);
    total += ratio ? R * s.X : R * double(s.N);
    if (s.n == s.N || s.n < 2) continue;
    double ss = 0;
    for (size_t u : s.sample) {
      const double e = y[u] - R * (ratio ? plan.units[u].x : 1.0);
      ss += e * e;
    }
    double s2 = ss / double(s.n - 1), df = double(s.n - 1);
    if (ratio) {
      const auto own = tally.certain_ratios.find(h);
      const bool enough = own != tally.certain_ratios.end() && own->second.size() >= kFloorUnits;
      apply_variance_floor(s, enough ? own->second : tally.all_ratios, s2, df, r);
    }
    const double v = double(s.N) * double(s.N) * (1 - double(s.n) / double(s.N)) * s2 / double(s.n);
    var += v;
    df_den += v * v / df;
  }
  r.cycles = total;
  if (var > 0) {
    r.degrees_of_freedom = var * var / df_den;
    const double t = student_t_quantile(0.5 + 0.5 * confidence, r.degrees_of_freedom);
    const double h = t * std::sqrt(var);
    r.ci_low = total - h;
    r.ci_high = total + h;
  } else {
    r.ci_low = r.ci_high = total;
  }
  return r;
}

SampledResult simulate_sampled(const Scene& scene, const ArchParams& arch, double fraction, uint64_t seed,
                               double confidence) {
  const auto t0 = std::chrono::steady_clock::now();
  const UnitPlan plan = plan_units(scene, arch);
  const std::vector<bool> chosen = draw_sample(plan, fraction, seed);
  const SubScene sub = sub_scene(scene, plan, chosen);
  // Each segment's start: command fetch starting its first triangle (or command).
  std::map<std::pair<size_t, size_t>, size_t> segment_at;
  for (size_t i = 0; i < sub.segments.size(); ++i) segment_at[{sub.segments[i].command, sub.segments[i].triangle}] = i;
  std::vector<double> start(sub.segments.size(), -1.0);
  sc::SimOptions opts;
  const Command* base = sub.scene.commands.data();
  opts.on_fetch = [&](const Command& c, size_t k, uint64_t cycle) {
    const auto it = segment_at.find({size_t(&c - base), k});
    if (it != segment_at.end() && start[it->second] < 0) start[it->second] = double(cycle);
  };
  const sc::SimResult sim = sc::simulate_scene(sub.scene, arch, opts);
  // A unit's cycles: fetch starting it to fetch starting the next segment (or the end).
  // The first segment also carries anything before it.
  std::vector<double> y(plan.units.size(), 0.0);
  for (size_t i = 0; i < sub.segments.size(); ++i) {
    if (start[i] < 0) throw std::logic_error("simulate_sampled: a chosen unit was never fetched");
    const size_t u = sub.segments[i].unit;
    if (u == SIZE_MAX) continue;
    const double end = i + 1 < sub.segments.size() ? start[i + 1] : double(sim.cycles);
    y[u] = end - (i == 0 ? 0.0 : start[i]);
  }
  SampledResult r = extrapolate(plan, chosen, y, confidence);
  r.sample_fraction = fraction;
  r.seed = seed;
  r.cycles_simulated = sim.cycles;
  r.warm_triangles = sub.warm_triangles;
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

nlohmann::json SampledResult::to_json() const {
  return {{"fidelity_level", "sampled"},
          {"cycles", uint64_t(std::llround(cycles))},
          {"cycles_ci_low", ci_low},
          {"cycles_ci_high", ci_high},
          {"confidence", confidence},
          {"sample_fraction", sample_fraction},
          {"sample_seed", seed},
          {"units_total", units_total},
          {"units_simulated", units_simulated},
          {"units_certain", units_certain},
          {"strata", strata},
          {"batch_triangles", batch_triangles},
          {"degrees_of_freedom", degrees_of_freedom},
          {"variance_floor", variance_floor},
          {"warm_triangles", warm_triangles},
          {"work_fraction_simulated", work_fraction_simulated},
          {"cycles_simulated", cycles_simulated},
          {"cycles_lower_bound", analytic.cycles_lower_bound},
          {"cycles_upper_bound", analytic.has_upper_bound() ? nlohmann::json(analytic.cycles_upper_bound)
                                                             : nlohmann::json(nullptr)},  // none with DRAM
          {"core_mhz", analytic.core_mhz},
          {"wall_seconds", wall_seconds}};
}

}  // namespace rastsim::fidelity
