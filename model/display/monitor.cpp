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

  // ---- sync polarity and pulses ----
  auto pulses = [&](const Runs& w, bool expected_positive, const char* name, std::vector<Pulse>& out) {
    if (w.start.size() < 2) {
      err(std::string("no ") + name + ": the " + name + " wire stays " + (w.level.empty() || w.level[0] ? "high" : "low") +
          " for all " + std::to_string(n_) + " pixel clocks");
      return;
    }
    // Mean length of the complete runs (not the first or the last) of each level.
    double sum[2] = {0, 0};
    long long cnt[2] = {0, 0};
    for (size_t k = 1; k + 1 < w.start.size(); ++k) sum[w.level[k]] += w.start[k + 1] - w.start[k], ++cnt[w.level[k]];
    bool positive = expected_positive;
    if (cnt[0] && cnt[1]) positive = sum[1] / cnt[1] < sum[0] / cnt[0];
    if (positive != expected_positive)
      err(std::string(name) + " polarity: measured " + (positive ? "positive" : "negative") + ", expected " +
          (expected_positive ? "positive" : "negative"));
    for (size_t k = 1; k < w.start.size(); ++k)
      if (w.level[k] == (positive ? 1 : 0))
        out.push_back({w.start[k], k + 1 < w.start.size() ? w.start[k + 1] : -1});
  };
  std::vector<Pulse> hp, vp;
  pulses(hs_, exp_.h_sync_positive, "hsync", hp);
  pulses(vs_, exp_.v_sync_positive, "vsync", vp);
  if (hp.size() < 2 || vp.size() < 2) {
    if (!hp.empty() && !vp.empty())
      err("no complete frame: saw " + std::to_string(hp.size()) + " hsync and " + std::to_string(vp.size()) +
          " vsync pulses in " + std::to_string(n_) + " pixel clocks; a frame lies between two vsync pulses (feed two frames)");
    return r;
  }
  std::vector<long long> E;  // line starts: hsync leading edges
  for (const auto& p : hp) E.push_back(p.lead);
  const long long lines = static_cast<long long>(E.size()) - 1;  // complete lines
  auto line_of = [&](long long t) { return static_cast<long long>(std::upper_bound(E.begin(), E.end(), t) - E.begin()) - 1; };

  // ---- per-line horizontal measurements (complete lines only) ----
  struct LineMeas {
    int h_total = 0, h_sync = 0, de_runs = 0, bp = 0, active = 0, fp = 0;
  };
  std::vector<LineMeas> lm(std::max<long long>(lines, 0));
  {
    size_t k = 0;  // DE run index
    for (long long i = 0; i < lines; ++i) {
      LineMeas& m = lm[i];
      m.h_total = static_cast<int>(E[i + 1] - E[i]);
      m.h_sync = static_cast<int>(hp[i].trail - E[i]);
      while (k < de_.start.size() && de_.start[k] < E[i]) ++k;
      for (size_t j = k; j < de_.start.size() && de_.start[j] < E[i + 1]; ++j) {
        if (!de_.level[j]) continue;
        const long long end = j + 1 < de_.start.size() ? de_.start[j + 1] : n_;
        if (m.de_runs++ == 0) {
          m.bp = static_cast<int>(de_.start[j] - hp[i].trail);
          m.active = static_cast<int>(end - de_.start[j]);
          m.fp = static_cast<int>(E[i + 1] - end);
        }
      }
    }
  }

  // ---- frames: between consecutive vsync leading edges ----
  const int bits_mask = (1 << 10) - 1;
  for (size_t j = 0; j + 1 < vp.size(); ++j) {
    const long long L0 = line_of(vp[j].lead), L1 = line_of(vp[j + 1].lead);
    if (L0 < 0 || vp[j].trail < 0 || L1 > lines) continue;  // not a complete frame
    const long long Ls = line_of(vp[j].trail);
    const int f = r.frames_decoded;
    Tally h_total, h_sync, h_bp, h_act, h_fp;
    long long first_de = -1, last_de = -1, multi_de = 0, multi_first = -1;
    for (long long L = L0; L < L1; ++L) {
      const LineMeas& m = lm[L];
      const std::string w = where_line(f, L - L0);
      h_total.add(m.h_total, exp_.h_total, w);
      h_sync.add(m.h_sync, exp_.h_sync, w);
      if (!m.de_runs) continue;
      if (first_de < 0) first_de = L;
      last_de = L;
      if (m.de_runs > 1 && multi_de++ == 0) multi_first = L - L0;
      h_bp.add(m.bp, exp_.h_back_porch, w);
      h_act.add(m.active, exp_.h_active, w);
      h_fp.add(m.fp, exp_.h_front_porch, w);
    }
    VideoTiming meas = exp_;
    meas.name = "measured";
    meas.h_total = h_total.mode(), meas.h_sync = h_sync.mode();
    meas.h_back_porch = h_bp.mode(), meas.h_active = h_act.mode(), meas.h_front_porch = h_fp.mode();
    meas.v_total = static_cast<int>(L1 - L0), meas.v_sync = static_cast<int>(Ls - L0);
    meas.v_back_porch = first_de < 0 ? 0 : static_cast<int>(first_de - Ls);
    meas.v_active = first_de < 0 ? 0 : static_cast<int>(last_de - first_de + 1);
    meas.v_front_porch = first_de < 0 ? 0 : static_cast<int>(L1 - last_de - 1);

    // Decode the active region where the expected mode puts it.
    Framebuffer img(exp_.h_active, exp_.v_active);
    std::vector<std::array<uint16_t, 3>> codes(size_t(exp_.h_active) * exp_.v_active);
    uint64_t no_data = 0;
    int nx0 = exp_.h_active, nx1 = -1, ny0 = exp_.v_active, ny1 = -1;
    bool complete = true;
    for (int y = 0; y < exp_.v_active && complete; ++y) {
      const long long L = Ls + exp_.v_back_porch + y;
      if (L < 0 || L >= lines) { complete = false; break; }
      for (int x = 0; x < exp_.h_active; ++x) {
        const long long t = E[L] + exp_.h_sync + exp_.h_back_porch + x;
        if (t >= n_) { complete = false; break; }
        const uint32_t w = px_[t];
        uint8_t* p = img.pixel(x, y);
        if (!(w >> 30 & 1)) {
          ++no_data;
          nx0 = std::min(nx0, x), nx1 = std::max(nx1, x), ny0 = std::min(ny0, y), ny1 = std::max(ny1, y);
          continue;
        }
        auto& c = codes[size_t(y) * exp_.h_active + x];
        for (int ch = 0; ch < 3; ++ch) {
          c[ch] = static_cast<uint16_t>(w >> (10 * ch) & bits_mask);
          p[ch] = palette_.inverse(c[ch]);
        }
      }
    }
    if (!complete) continue;

    // Report: one message a quantity (first frame with a fault for each).
    auto check_h = [&](const Tally& t, int expected, const char* name, const char* scope) {
      if (!t.bad) return;
      err(std::string(name) + ": measured " + std::to_string(t.first_bad_value) + " px, expected " +
          std::to_string(expected) + " (" + std::to_string(t.bad) + " of " + std::to_string(t.seen) + " " + scope +
          "; first on " + t.first_bad_where + ")");
    };
    check_h(h_total, exp_.h_total, "h_total", "lines");
    check_h(h_sync, exp_.h_sync, "h_sync", "lines");
    check_h(h_bp, exp_.h_back_porch, "h_back_porch", "lines with data");
    check_h(h_act, exp_.h_active, "h_active", "lines with data");
    check_h(h_fp, exp_.h_front_porch, "h_front_porch", "lines with data");
    if (multi_de)
      err("BLANK toggles more than once within " + std::to_string(multi_de) + " lines (first on " +
          where_line(f, multi_first) + "): expected one active run a line");
    auto check_v = [&](int measured, int expected, const char* name) {
      if (measured != expected)
        err(std::string(name) + ": measured " + std::to_string(measured) + " lines, expected " +
            std::to_string(expected) + " (frame " + std::to_string(f) + ")");
    };
    check_v(meas.v_total, exp_.v_total, "v_total");
    check_v(meas.v_sync, exp_.v_sync, "v_sync");
    if (first_de < 0) {
      err("no active video in frame " + std::to_string(f) + ": BLANK never goes low between two vsync pulses");
    } else if (!no_data) {  // with missing data, BLANK-derived vertical values follow the gap
      check_v(meas.v_back_porch, exp_.v_back_porch, "v_back_porch");
      check_v(meas.v_active, exp_.v_active, "v_active");
      check_v(meas.v_front_porch, exp_.v_front_porch, "v_front_porch");
    }
    if (no_data)
      err("no pixel data (BLANK high) at " + std::to_string(no_data) + " of " +
          std::to_string(int64_t(exp_.h_active) * exp_.v_active) + " active pixels of frame " + std::to_string(f) +
          ", columns " + std::to_string(nx0) + ".." + std::to_string(nx1) + " of lines " + std::to_string(ny0) +
          ".." + std::to_string(ny1) +
          ": a scan-out underrun (line buffer empty) or a framebuffer smaller than the active area");

    if (r.frames_decoded == 0) {
      r.measured = meas;
      r.line_rate_hz = exp_.pixel_clock_hz / meas.h_total;
      r.frame_rate_hz = r.line_rate_hz / meas.v_total;
    }
    r.no_data_pixels += no_data;
    r.image = std::move(img);
    r.codes = std::move(codes);
    ++r.frames_decoded;
  }
  // Only the first message of each kind matters: drop repeats from later frames.
  std::vector<std::string> uniq;
  for (auto& e : r.errors) {
    const std::string kind = e.substr(0, e.find(':'));
    if (std::none_of(uniq.begin(), uniq.end(), [&](const std::string& u) { return u.substr(0, u.find(':')) == kind; }))
      uniq.push_back(e);
  }
  r.errors = std::move(uniq);
  if (r.frames_decoded == 0 && r.errors.empty())
    err("no complete frame: " + std::to_string(vp.size()) + " vsync pulses in " + std::to_string(n_) +
        " pixel clocks, but the lines of none of the frames between them were all captured");
  r.locked = r.frames_decoded > 0;
  return r;
}

}  // namespace rastsim
