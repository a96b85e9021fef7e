// SPDX-License-Identifier: Apache-2.0
// Virtual monitor: capture, lock, measure, decode (see monitor.h).
#include "display/monitor.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace rastsim {

namespace {

DacConfig ideal(DacConfig c) {
  c.inl_lsb = c.dnl_lsb = 0;
  return c;
}

// One timing quantity over many lines: the most common value and the lines that
// disagree with the expected value.
struct Tally {
  std::map<int, long long> counts;
  long long seen = 0, bad = 0;
  int first_bad_value = 0;
  std::string first_bad_where;
  void add(int v, int expected, const std::string& where) {
    ++counts[v];
    ++seen;
    if (v != expected && bad++ == 0) first_bad_value = v, first_bad_where = where;
  }
  int mode() const {
    int best = 0;
    long long n = -1;
    for (auto [v, c] : counts)
      if (c > n) best = v, n = c;
    return best;
  }
};

struct Pulse {
  long long lead = 0, trail = -1;  // trail -1: still asserted at the end of the capture
};

std::string where_line(int frame, long long line_after_vsync) {
  return "frame " + std::to_string(frame) + ", line " + std::to_string(line_after_vsync) +
         " after the vsync leading edge";
}

using Errors = std::vector<std::string>;

// The capture finish() reads: the expected mode, the sample count, the BLANK wire,
// the per-sample words (R | G << 10 | B << 20 | DE << 30) and the inverse palette.
struct Capture {
  const VideoTiming& exp;
  long long n;
  const Monitor::Runs& de;
  const std::vector<uint32_t>& px;
  const Dac& palette;
};

// The sync pulses of one wire; its polarity is measured (the shorter mean run is the
// pulse) and checked against the expected one.
std::vector<Pulse> sync_pulses(const Monitor::Runs& w, bool expected_positive, const char* name, long long n,
                               Errors& errors) {
  std::vector<Pulse> out;
  if (w.start.size() < 2) {
    errors.push_back(std::string("no ") + name + ": the " + name + " wire stays " +
                     (w.level.empty() || w.level[0] ? "high" : "low") + " for all " + std::to_string(n) +
                     " pixel clocks");
    return out;
  }
  // Mean length of the complete runs (not the first or the last) of each level.
  double sum[2] = {0, 0};
  long long cnt[2] = {0, 0};
  for (size_t k = 1; k + 1 < w.start.size(); ++k) sum[w.level[k]] += w.start[k + 1] - w.start[k], ++cnt[w.level[k]];
  bool positive = expected_positive;
  if (cnt[0] && cnt[1]) positive = sum[1] / cnt[1] < sum[0] / cnt[0];
  if (positive != expected_positive)
    errors.push_back(std::string(name) + " polarity: measured " + (positive ? "positive" : "negative") +
                     ", expected " + (expected_positive ? "positive" : "negative"));
  for (size_t k = 1; k < w.start.size(); ++k)
    if (w.level[k] == (positive ? 1 : 0)) out.push_back({w.start[k], k + 1 < w.start.size() ? w.start[k + 1] : -1});
  return out;
}

// Horizontal measurements of one complete line, in pixel clocks.
struct LineMeas {
  int h_total = 0, h_sync = 0, de_runs = 0, bp = 0, active = 0, fp = 0;
};

// The lines of the capture: starts (hsync leading edges) and measurements of the
// complete ones (between two leading edges).
struct Lines {
  std::vector<long long> start;
  long long complete = 0;
  std::vector<LineMeas> meas;
  long long line_of(long long t) const {
    return static_cast<long long>(std::upper_bound(start.begin(), start.end(), t) - start.begin()) - 1;
  }
};

Lines measure_lines(const Capture& c, const std::vector<Pulse>& hp) {
  Lines g;
  for (const auto& p : hp) g.start.push_back(p.lead);
  const auto& E = g.start;
  g.complete = static_cast<long long>(E.size()) - 1;
  g.meas.resize(std::max<long long>(g.complete, 0));
  size_t k = 0;  // DE run index
  for (long long i = 0; i < g.complete; ++i) {
    LineMeas& m = g.meas[i];
    m.h_total = static_cast<int>(E[i + 1] - E[i]);
    m.h_sync = static_cast<int>(hp[i].trail - E[i]);
    while (k < c.de.start.size() && c.de.start[k] < E[i]) ++k;
    for (size_t j = k; j < c.de.start.size() && c.de.start[j] < E[i + 1]; ++j) {
      if (!c.de.level[j]) continue;
      const long long end = j + 1 < c.de.start.size() ? c.de.start[j + 1] : c.n;
      if (m.de_runs++ == 0) {
        m.bp = static_cast<int>(c.de.start[j] - hp[i].trail);
        m.active = static_cast<int>(end - c.de.start[j]);
        m.fp = static_cast<int>(E[i + 1] - end);
      }
    }
  }
  return g;
}

// One frame: lines [first, end) between two vsync leading edges; vsync ends at sync_end.
struct FrameLines {
  long long first = 0, end = 0, sync_end = 0;
  int index = 0;  // frames decoded before this one
  Tally h_total, h_sync, h_bp, h_act, h_fp;
  long long first_de = -1, last_de = -1;  // lines with an active run
  long long multi_de = 0, multi_first = -1;  // lines with more than one active run
};

void tally_lines(const Capture& c, const Lines& g, FrameLines& f) {
  for (long long L = f.first; L < f.end; ++L) {
    const LineMeas& m = g.meas[L];
    const std::string w = where_line(f.index, L - f.first);
    f.h_total.add(m.h_total, c.exp.h_total, w);
    f.h_sync.add(m.h_sync, c.exp.h_sync, w);
    if (!m.de_runs) continue;
    if (f.first_de < 0) f.first_de = L;
    f.last_de = L;
    if (m.de_runs > 1 && f.multi_de++ == 0) f.multi_first = L - f.first;
    f.h_bp.add(m.bp, c.exp.h_back_porch, w);
    f.h_act.add(m.active, c.exp.h_active, w);
    f.h_fp.add(m.fp, c.exp.h_front_porch, w);
  }
}

// The frame's timing: horizontal values the most common over its lines, vertical ones
// from the vsync pulse and the lines with an active run.
VideoTiming measured_timing(const VideoTiming& exp, const FrameLines& f) {
  VideoTiming meas = exp;
  meas.name = "measured";
  meas.h_total = f.h_total.mode(), meas.h_sync = f.h_sync.mode();
  meas.h_back_porch = f.h_bp.mode(), meas.h_active = f.h_act.mode(), meas.h_front_porch = f.h_fp.mode();
  meas.v_total = static_cast<int>(f.end - f.first), meas.v_sync = static_cast<int>(f.sync_end - f.first);
  meas.v_back_porch = f.first_de < 0 ? 0 : static_cast<int>(f.first_de - f.sync_end);
  meas.v_active = f.first_de < 0 ? 0 : static_cast<int>(f.last_de - f.first_de + 1);
  meas.v_front_porch = f.first_de < 0 ? 0 : static_cast<int>(f.end - f.last_de - 1);
  return meas;
}

// The active region decoded where the expected mode puts it; pixels with BLANK high
// are counted (and their bounding box kept) as missing data.
struct ActiveArea {
  Framebuffer img;
  std::vector<std::array<uint16_t, 3>> codes;
  uint64_t no_data = 0;
  int nx0, nx1 = -1, ny0, ny1 = -1;  // bounding box of the missing pixels
  bool complete = true;              // false: the capture ends inside the active region
};

ActiveArea decode_active(const Capture& c, const Lines& g, long long sync_end) {
  const VideoTiming& exp = c.exp;
  const int bits_mask = (1 << 10) - 1;
  ActiveArea a{Framebuffer(exp.h_active, exp.v_active),
               std::vector<std::array<uint16_t, 3>>(size_t(exp.h_active) * exp.v_active), 0, exp.h_active, -1,
               exp.v_active, -1, true};
  for (int y = 0; y < exp.v_active && a.complete; ++y) {
    const long long L = sync_end + exp.v_back_porch + y;
    if (L < 0 || L >= g.complete) { a.complete = false; break; }
    for (int x = 0; x < exp.h_active; ++x) {
      const long long t = g.start[L] + exp.h_sync + exp.h_back_porch + x;
      if (t >= c.n) { a.complete = false; break; }
      const uint32_t w = c.px[t];
      uint8_t* p = a.img.pixel(x, y);
      if (!(w >> 30 & 1)) {
        ++a.no_data;
        a.nx0 = std::min(a.nx0, x), a.nx1 = std::max(a.nx1, x), a.ny0 = std::min(a.ny0, y), a.ny1 = std::max(a.ny1, y);
        continue;
      }
      auto& code = a.codes[size_t(y) * exp.h_active + x];
      for (int ch = 0; ch < 3; ++ch) {
        code[ch] = static_cast<uint16_t>(w >> (10 * ch) & bits_mask);
        p[ch] = c.palette.inverse(code[ch]);
      }
    }
  }
  return a;
}

// One message a quantity that differs from the expected mode.
void report_frame(const VideoTiming& exp, const FrameLines& f, const VideoTiming& meas, const ActiveArea& a,
                  Errors& errors) {
  auto err = [&](const std::string& m) { errors.push_back(m); };
  auto check_h = [&](const Tally& t, int expected, const char* name, const char* scope) {
    if (!t.bad) return;
    err(std::string(name) + ": measured " + std::to_string(t.first_bad_value) + " px, expected " +
        std::to_string(expected) + " (" + std::to_string(t.bad) + " of " + std::to_string(t.seen) + " " + scope +
        "; first on " + t.first_bad_where + ")");
  };
  check_h(f.h_total, exp.h_total, "h_total", "lines");
  check_h(f.h_sync, exp.h_sync, "h_sync", "lines");
  check_h(f.h_bp, exp.h_back_porch, "h_back_porch", "lines with data");
  check_h(f.h_act, exp.h_active, "h_active", "lines with data");
  check_h(f.h_fp, exp.h_front_porch, "h_front_porch", "lines with data");
  if (f.multi_de)
    err("BLANK toggles more than once within " + std::to_string(f.multi_de) + " lines (first on " +
        where_line(f.index, f.multi_first) + "): expected one active run a line");
  auto check_v = [&](int measured, int expected, const char* name) {
    if (measured != expected)
      err(std::string(name) + ": measured " + std::to_string(measured) + " lines, expected " +
          std::to_string(expected) + " (frame " + std::to_string(f.index) + ")");
  };
  check_v(meas.v_total, exp.v_total, "v_total");
  check_v(meas.v_sync, exp.v_sync, "v_sync");
  if (f.first_de < 0) {
    err("no active video in frame " + std::to_string(f.index) + ": BLANK never goes low between two vsync pulses");
  } else if (!a.no_data) {  // with missing data, BLANK-derived vertical values follow the gap
    check_v(meas.v_back_porch, exp.v_back_porch, "v_back_porch");
    check_v(meas.v_active, exp.v_active, "v_active");
    check_v(meas.v_front_porch, exp.v_front_porch, "v_front_porch");
  }
  if (a.no_data)
    err("no pixel data (BLANK high) at " + std::to_string(a.no_data) + " of " +
        std::to_string(int64_t(exp.h_active) * exp.v_active) + " active pixels of frame " + std::to_string(f.index) +
        ", columns " + std::to_string(a.nx0) + ".." + std::to_string(a.nx1) + " of lines " + std::to_string(a.ny0) +
        ".." + std::to_string(a.ny1) +
        ": a scan-out underrun (line buffer empty) or a framebuffer smaller than the active area");
}

// Only the first message of each kind (the text before ':') matters: drop repeats from later frames.
void keep_first_of_each_kind(Errors& errors) {
  Errors uniq;
  for (auto& e : errors) {
    const std::string kind = e.substr(0, e.find(':'));
    if (std::none_of(uniq.begin(), uniq.end(), [&](const std::string& u) { return u.substr(0, u.find(':')) == kind; }))
      uniq.push_back(e);
  }
  errors = std::move(uniq);
}

}  // namespace

Monitor::Monitor(const VideoTiming& expected, const DacConfig& dac)
    : exp_(expected), dac_cfg_(dac), palette_(ideal(dac)),
      half_lsb_(0.5 * dac.full_scale_volts / ((1 << dac.bits) - 1)) {}

void Monitor::push(const VideoSample& s) {
  const long long t = n_++;
  hs_.push(s.hsync, t);
  vs_.push(s.vsync, t);
  de_.push(!s.blank, t);
  uint32_t w = 0;
  if (!s.blank) {
    for (int c = 0; c < 3; ++c)
      w |= uint32_t(level_to_code(s.volts[c], dac_cfg_.bits, dac_cfg_.full_scale_volts)) << (10 * c);
    w |= 1u << 30;
  } else if (std::abs(s.volts[0]) > half_lsb_ || std::abs(s.volts[1]) > half_lsb_ ||
             std::abs(s.volts[2]) > half_lsb_) {
    if (first_blank_violation_ < 0) first_blank_violation_ = t;
    ++blank_level_violations_;
  }
  px_.push_back(w);
}

MonitorResult Monitor::finish() const {
  MonitorResult r;
  auto err = [&](const std::string& m) { r.errors.push_back(m); };
  for (const auto& p : exp_.problems()) err("the expected mode's porches do not add up: " + p);
  r.blank_level_violations = blank_level_violations_;
  if (blank_level_violations_)
    err("levels not at blank (0 V) while BLANK is high at " + std::to_string(blank_level_violations_) +
        " pixel clocks (first at clock " + std::to_string(first_blank_violation_) + ")");

  const std::vector<Pulse> hp = sync_pulses(hs_, exp_.h_sync_positive, "hsync", n_, r.errors);
  const std::vector<Pulse> vp = sync_pulses(vs_, exp_.v_sync_positive, "vsync", n_, r.errors);
  if (hp.size() < 2 || vp.size() < 2) {
    if (!hp.empty() && !vp.empty())
      err("no complete frame: saw " + std::to_string(hp.size()) + " hsync and " + std::to_string(vp.size()) +
          " vsync pulses in " + std::to_string(n_) + " pixel clocks; a frame lies between two vsync pulses (feed two frames)");
    return r;
  }
  const Capture c{exp_, n_, de_, px_, palette_};
  const Lines g = measure_lines(c, hp);
  for (size_t j = 0; j + 1 < vp.size(); ++j) {
    FrameLines f;
    f.first = g.line_of(vp[j].lead), f.end = g.line_of(vp[j + 1].lead);
    if (f.first < 0 || vp[j].trail < 0 || f.end > g.complete) continue;  // not a complete frame
    f.sync_end = g.line_of(vp[j].trail);
    f.index = r.frames_decoded;
    tally_lines(c, g, f);
    const VideoTiming meas = measured_timing(exp_, f);
    ActiveArea a = decode_active(c, g, f.sync_end);
    if (!a.complete) continue;
    report_frame(exp_, f, meas, a, r.errors);
    if (r.frames_decoded == 0) {
      r.measured = meas;
      r.line_rate_hz = exp_.pixel_clock_hz / meas.h_total;
      r.frame_rate_hz = r.line_rate_hz / meas.v_total;
    }
    r.no_data_pixels += a.no_data;
    if (keep_images_) r.images.push_back(a.img);
    r.image = std::move(a.img);
    r.codes = std::move(a.codes);
    ++r.frames_decoded;
  }
  keep_first_of_each_kind(r.errors);
  if (r.frames_decoded == 0 && r.errors.empty())
    err("no complete frame: " + std::to_string(vp.size()) + " vsync pulses in " + std::to_string(n_) +
        " pixel clocks, but the lines of none of the frames between them were all captured");
  r.locked = r.frames_decoded > 0;
  return r;
}

}  // namespace rastsim
