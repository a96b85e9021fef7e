// SPDX-License-Identifier: Apache-2.0
// The ROP (rtl/rast_rop.sv) against the reference's rop_write (model/ref/rop.h) at each
// verilated parameter set (rop_sets.h), with a byte-addressed memory in C++ behind its
// port. A run streams random tile batches (distinct pixels, depths from a few values so
// that ties happen, full and partial sample masks) and markers (both pass codes, colour
// and depth clears) through the ROP and the same stream through rop_write and Framebuffer's
// clears; at the end every sample's colour and depth word in memory must equal the
// reference framebuffer's. Every depth function, depth write on and off, one, two and
// the set's MaxSamples samples a pixel.
//
// Without stalls (memory always ready, read data the next cycle, beats offered at once)
// the cycles are checked against TimingParams' equations: each batch's reads go out in
// rop_fragment_cycles(A) consecutive cycles (A the sum of rop_accesses over its
// fragments) and each clear writes in rop_clear_cycles(W H) consecutive cycles. With
// stalls (random ready lows on both memory ports, read latency 1..4, gaps between beats,
// lanes left empty) only the image is checked. The seed is printed;
// RASTSIM_ROP_SEED=<n> replays a run, RASTSIM_ROP_SEED=random draws a new one.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <deque>
#include <optional>
#include <random>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "common/rtl_unit_test.h"
#include "config/timing_params.h"
#include "ref/framebuffer.h"
#include "ref/rop.h"
#include "rop_sets.h"

namespace {

using rastsim::DepthFunc;
using rastsim::Fragment;
using rastsim::Framebuffer;
using rastsim::TimingParams;

uint64_t seed() {
  static const uint64_t s = rastsim::test::seed_from_env("RASTSIM_ROP_SEED", 27);
  return s;
}

// Bits [lsb, lsb + w) of a Verilator port (an integer up to 64 bits, VlWide beyond), w <= 32.
template <class T>
uint32_t get_bits(const T& v, int lsb, int w) {
  if constexpr (std::is_integral_v<T>) {
    return uint32_t((uint64_t(v) >> lsb) & ((uint64_t{1} << w) - 1));
  } else {
    uint32_t r = 0;
    for (int i = 0; i < w; ++i)
      if ((v[size_t(lsb + i) / 32] >> ((lsb + i) % 32)) & 1) r |= uint32_t{1} << i;
    return r;
  }
}
template <class T>
void set_bits(T& v, int lsb, int w, uint32_t x) {
  if constexpr (std::is_integral_v<T>) {
    const uint64_t m = ((uint64_t{1} << w) - 1) << lsb;
    v = T((uint64_t(v) & ~m) | ((uint64_t(x) << lsb) & m));
  } else {
    for (int i = 0; i < w; ++i) {
      auto& word = v[size_t(lsb + i) / 32];
      const uint32_t bit = uint32_t{1} << ((lsb + i) % 32);
      word = ((x >> i) & 1) ? (word | bit) : (word & ~bit);
    }
  }
}
template <class T>
void clear_bits(T& v, int bits) {
  for (int lsb = 0; lsb < bits; lsb += 32) set_bits(v, lsb, std::min(32, bits - lsb), 0);
}

struct RopSet {
  const char* name;
  int pixel_w, depth_w, max_samples, lanes, ppc, clear_ppc;
};

// One beat offered to the ROP: up to `lanes` fragments (an empty optional: a lane left
// empty), or a marker with its command.
struct Beat {
  std::vector<std::optional<Fragment>> lanes;
  bool last = false;
  bool marker = false;
  int op = 0;          // 0 pass, 1 clear colour, 2 clear depth, 3 pass
  uint32_t value = 0;  // the clear's word
};

// The stream and what it should do: the beats, each batch's accesses (rop_accesses
// summed), and the reference framebuffer after the whole stream.
struct Stream {
  std::vector<Beat> beats;
  std::vector<uint64_t> batch_accesses;
  int clears = 0;
};

constexpr int kW = 21, kH = 13;  // framebuffer, px: tiles clipped at the right and bottom
constexpr int kTile = 8;
constexpr uint32_t kColorBase = 0x100;

struct Run {
  int samples = 1;
  DepthFunc func = DepthFunc::Less;
  bool depth_write = true;
  bool stalls = false;
};

// Random batches and markers, applied to `fb` (the reference) as they are made.
Stream make_stream(const RopSet& set, const Run& run, Framebuffer& fb, std::mt19937_64& rng) {
  Stream st;
  const int S = run.samples;
  const uint32_t full = S == 1 ? 1u : (1u << S) - 1;
  const uint32_t zmax = uint32_t((uint64_t{1} << set.depth_w) - 1);
  auto z_of = [&] { return rng() % 4 == 0 ? zmax : uint32_t(rng() % 5) * (zmax / 4); };
  for (int b = 0; b < 40; ++b) {
    if (rng() % 6 == 0) {  // a marker
      Beat m;
      m.marker = true;
      m.op = int(rng() % 4);
      if (m.op == 1) {
        const uint8_t r = uint8_t(rng()), g = uint8_t(rng()), bl = uint8_t(rng());
        m.value = 0xff000000u | uint32_t(bl) << 16 | uint32_t(g) << 8 | r;
        fb.clear_color(r, g, bl);
      } else if (m.op == 2) {
        m.value = z_of();
        fb.clear_depth(m.value);
      }
      st.clears += m.op == 1 || m.op == 2;
      st.beats.push_back(m);
      continue;
    }
    // A batch: distinct pixels of one tile, in raster order.
    const int tx = int(rng() % ((kW + kTile - 1) / kTile)) * kTile, ty = int(rng() % ((kH + kTile - 1) / kTile)) * kTile;
    std::vector<Fragment> frags;
    for (int y = ty; y < std::min(kH, ty + kTile); ++y)
      for (int x = tx; x < std::min(kW, tx + kTile); ++x) {
        if (rng() % 3 == 0) continue;
        Fragment f;
        f.x = x, f.y = y, f.z = z_of();
        f.r = uint8_t(rng()), f.g = uint8_t(rng()), f.b = uint8_t(rng());
        f.samples = uint8_t(S);
        f.mask = uint16_t(S == 1 || rng() % 2 ? full : 1 + rng() % full);
        frags.push_back(f);
      }
    if (frags.empty()) continue;
    uint64_t acc = 0;
    for (const Fragment& f : frags) {
      acc += TimingParams::rop_accesses(f.mask, S);
      rastsim::rop_write(fb, f, run.func, run.depth_write);
    }
    st.batch_accesses.push_back(acc);
    // Beats of up to `lanes` fragments; with stalls, some lanes left empty.
    for (size_t i = 0; i < frags.size();) {
      Beat beat;
      for (int j = 0; j < set.lanes; ++j) {
        if (i < frags.size() && !(run.stalls && rng() % 4 == 0)) beat.lanes.push_back(frags[i++]);
        else beat.lanes.push_back(std::nullopt);
      }
      beat.last = i == frags.size();
      st.beats.push_back(beat);
    }
  }
  return st;
}

// The ROP of `set` on the stream of `run`, a memory behind its port; the memory
// afterwards against the reference framebuffer.
template <class Model>
class Bench {
 public:
  Bench(const RopSet& set, const Run& run, uint64_t salt)
      : set_(set), run_(run), rng_(seed() ^ salt), S_(run.samples), P_(set.ppc), MS_(set.max_samples),
        len_w_(std::bit_width(unsigned(set.clear_ppc * set.max_samples))), surface_(uint32_t(kW * kH * S_ * 4)),
        depth_base_(kColorBase + surface_ + 0x40), zfar_(uint32_t((uint64_t{1} << set.depth_w) - 1)), fb_(kW, kH, S_) {
    fb_.clear_depth(zfar_);  // as render_scene
    // The memory starts as the reference does: opaque black, depth at the far value.
    mem_.assign(depth_base_ + surface_, 0);
    for (uint32_t i = 0; i < uint32_t(kW * kH * S_); ++i) {
      mem_[kColorBase + 4 * i + 3] = 255;
      for (uint32_t b = 0; b < 4; ++b) mem_[depth_base_ + 4 * i + b] = uint8_t(zfar_ >> (8 * b));
    }
    st_ = make_stream(set, run, fb_, rng_);
    tp_.rop_pixels_per_cycle = uint64_t(P_);
    tp_.rop_clear_pixels_per_cycle = uint64_t(set.clear_ppc);
  }

  void simulate() {
    reset();
    long t = 0;
    for (; t < kMaxCycles; ++t) {
      drive(t);
      m_.clk_i = 0;
      m_.eval();
      // The handshakes of this cycle: the response consumed, the write, then the read
      // (which sees the write: the memory orders writes first).
      if (m_.rd_rvalid_i) responses_.pop_front();
      if (m_.wr_valid_o && m_.wr_ready_i) write(t);
      if (m_.rd_valid_o && m_.rd_ready_i) read(t);
      if (m_.in_valid_i && m_.in_ready_o) {
        if (st_.beats[next_beat_].marker) EXPECT_TRUE(m_.cmd_ready_o) << "cycle " << t << ": a marker without its command";
        ++next_beat_;
      }
      m_.clk_i = 1;
      m_.eval();
      if (next_beat_ == st_.beats.size() && responses_.empty() && m_.idle_o) break;
    }
    EXPECT_LT(t, kMaxCycles) << "the ROP did not finish";
    EXPECT_EQ(batch_, st_.batch_accesses.size()) << "batches whose reads all went out";
    EXPECT_EQ(clears_seen_, st_.clears) << "clears written whole";
    check_image();
  }

 private:
  static constexpr long kMaxCycles = 20000;  // a run is a few thousand
  struct Response {
    std::vector<uint32_t> words;  // lane k word i at k MaxSamples + i
    long ready = 0;               // the first cycle it may return
  };

  void reset() {
    m_.samples_log2_i = uint8_t(std::countr_zero(unsigned(S_)));
    m_.fb_width_i = kW, m_.fb_height_i = kH;
    m_.color_base_i = kColorBase, m_.depth_base_i = depth_base_;
    m_.depth_func_i = uint8_t(run_.func), m_.depth_write_i = run_.depth_write;
    m_.in_valid_i = 0, m_.cmd_valid_i = 0, m_.rd_ready_i = 0, m_.wr_ready_i = 0, m_.rd_rvalid_i = 0;
    m_.rst_ni = 0, m_.clk_i = 0;
    m_.eval();
    rastsim::test::clock_cycle(m_);  // the reset cycle loads the static inputs' registers
    m_.rst_ni = 1;
    m_.eval();
  }

  // The next beat (unless a stall gap), the memory's readies and its oldest response.
  void drive(long t) {
    const bool offer = next_beat_ < st_.beats.size() && !(run_.stalls && rng_() % 4 == 0);
    m_.in_valid_i = offer;
    m_.cmd_valid_i = 0;
    if (offer) {
      const Beat& b = st_.beats[next_beat_];
      m_.in_marker_i = b.marker, m_.in_last_i = b.last;
      m_.cmd_valid_i = b.marker, m_.cmd_op_i = uint8_t(b.op), m_.cmd_value_i = b.value;
      m_.in_lanes_i = 0;
      for (int j = 0; j < set_.lanes && !b.marker; ++j) {
        if (!b.lanes[size_t(j)]) continue;
        const Fragment& f = *b.lanes[size_t(j)];
        const int pw = set_.pixel_w;
        set_bits(m_.in_lanes_i, j, 1, 1);
        set_bits(m_.in_x_i, j * pw, pw, uint32_t(f.x));
        set_bits(m_.in_y_i, j * pw, pw, uint32_t(f.y));
        set_bits(m_.in_z_i, j * set_.depth_w, set_.depth_w, f.z);
        set_bits(m_.in_rgb_i, j * 24, 24, uint32_t(f.b) << 16 | uint32_t(f.g) << 8 | f.r);
        set_bits(m_.in_mask_i, j * MS_, MS_, f.mask);
      }
    }
    m_.rd_ready_i = !(run_.stalls && rng_() % 3 == 0);
    m_.wr_ready_i = !(run_.stalls && rng_() % 3 == 0);
    m_.rd_rvalid_i = !responses_.empty() && responses_.front().ready <= t;
    if (m_.rd_rvalid_i)
      for (int w = 0; w < P_ * MS_; ++w) set_bits(m_.rd_rdata_i, 32 * w, 32, responses_.front().words[size_t(w)]);
  }

  uint32_t word(uint32_t addr) const {
    uint32_t v = 0;
    for (uint32_t b = 0; b < 4; ++b) v |= uint32_t(mem_[addr + b]) << (8 * b);
    return v;
  }
  bool in_memory(uint32_t addr, uint32_t words, long t) {
    if (uint64_t(addr) + 4 * uint64_t(words) <= mem_.size() && addr >= kColorBase) return true;
    ADD_FAILURE() << "cycle " << t << ": access at " << addr << " of " << words << " words outside the surfaces";
    return false;
  }

  // Each lane's data word into the words of its burst under their byte enables (a fill:
  // word 0's enables for all); a clear's writes counted.
  void write(long t) {
    const bool fill = m_.wr_fill_o;
    for (int k = 0; k < 2 * P_; ++k) {
      if (!get_bits(m_.wr_lanes_o, k, 1)) continue;
      const uint32_t addr = get_bits(m_.wr_addr_o, 32 * k, 32), len = get_bits(m_.wr_len_o, k * len_w_, len_w_);
      const uint32_t data = get_bits(m_.wr_data_o, 32 * k, 32);
      if (!fill && len > uint32_t(MS_)) ADD_FAILURE() << "cycle " << t << ": a burst of " << len << " words";
      if (!in_memory(addr, len, t)) continue;
      for (uint32_t i = 0; i < len; ++i) {
        const uint32_t be = get_bits(m_.wr_be_o, (k * MS_ + (fill ? 0 : int(i))) * 4, 4);
        for (uint32_t b = 0; b < 4; ++b)
          if ((be >> b) & 1) mem_[addr + 4 * i + b] = uint8_t(data >> (8 * b));
      }
      if (fill) clear_pixels_ += len / uint32_t(S_);
    }
    if (!fill) return;
    if (clear_first_ < 0) clear_first_ = t;
    ++clear_writes_;
    if (clear_pixels_ < uint32_t(kW * kH)) return;
    ++clears_seen_;
    if (!run_.stalls) {
      EXPECT_EQ(uint64_t(clear_writes_), tp_.rop_clear_cycles(uint64_t(kW * kH))) << "clear " << clears_seen_;
      EXPECT_EQ(t - clear_first_ + 1, clear_writes_) << "clear " << clears_seen_ << ": writes not consecutive";
    }
    clear_first_ = -1, clear_writes_ = 0, clear_pixels_ = 0;
  }

  // The read's data now (after this cycle's write), returned 1 cycle later (with stalls
  // 1 to 4); its accesses counted against the current batch.
  void read(long t) {
    Response r{std::vector<uint32_t>(size_t(P_ * MS_), 0), t + (run_.stalls ? 1 + long(rng_() % 4) : 1)};
    uint64_t n = 0;
    for (int k = 0; k < P_; ++k) {
      if (!get_bits(m_.rd_lanes_o, k, 1)) continue;
      ++n;
      const uint32_t addr = get_bits(m_.rd_addr_o, 32 * k, 32), len = get_bits(m_.rd_len_o, k * len_w_, len_w_);
      if (len > uint32_t(MS_)) ADD_FAILURE() << "cycle " << t << ": a read burst of " << len << " words";
      if (!in_memory(addr, len, t)) continue;
      for (uint32_t i = 0; i < len && i < uint32_t(MS_); ++i) r.words[size_t(k * MS_) + i] = word(addr + 4 * i);
    }
    responses_.push_back(r);
    if (batch_ >= st_.batch_accesses.size()) {
      ADD_FAILURE() << "cycle " << t << ": a read after the last batch";
      return;
    }
    const uint64_t want = st_.batch_accesses[batch_];
    if (batch_first_ < 0) batch_first_ = t;
    ++batch_reads_;
    batch_done_ += n;
    if (batch_done_ > want) ADD_FAILURE() << "batch " << batch_ << ": a group holds the next batch's accesses";
    if (batch_done_ < want) return;
    if (!run_.stalls) {
      EXPECT_EQ(uint64_t(batch_reads_), tp_.rop_fragment_cycles(want)) << "batch " << batch_ << " of " << want << " accesses";
      EXPECT_EQ(t - batch_first_ + 1, batch_reads_) << "batch " << batch_ << ": reads not consecutive";
    }
    ++batch_;
    batch_first_ = -1, batch_reads_ = 0, batch_done_ = 0;
  }

  // Every sample's colour and depth word against the reference (the first few misses).
  void check_image() {
    int misses = 0;
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x)
        for (int s = 0; s < S_; ++s) {
          const uint32_t off = uint32_t(((y * kW + x) * S_ + s) * 4);
          const uint8_t* c = std::as_const(fb_).sample(x, y, s);
          const uint32_t want_c = uint32_t(c[0]) | uint32_t(c[1]) << 8 | uint32_t(c[2]) << 16 | uint32_t(c[3]) << 24;
          const uint32_t got_c = word(kColorBase + off), got_z = word(depth_base_ + off);
          if ((got_c != want_c || got_z != fb_.depth_at(x, y, s)) && ++misses <= 5)
            ADD_FAILURE() << "pixel (" << x << ", " << y << ") sample " << s << ": colour " << std::hex << got_c
                          << " depth " << got_z << ", reference " << want_c << " " << fb_.depth_at(x, y, s);
        }
    EXPECT_EQ(misses, 0);
  }

  const RopSet set_;
  const Run run_;
  std::mt19937_64 rng_;
  const int S_, P_, MS_, len_w_;
  const uint32_t surface_, depth_base_, zfar_;
  Framebuffer fb_;
  std::vector<uint8_t> mem_;
  Stream st_;
  TimingParams tp_{};
  Model m_;
  std::deque<Response> responses_;
  size_t next_beat_ = 0;
  size_t batch_ = 0;  // the batch whose reads go out
  long batch_first_ = -1, batch_reads_ = 0;
  uint64_t batch_done_ = 0;
  long clear_first_ = -1, clear_writes_ = 0;
  uint32_t clear_pixels_ = 0;
  int clears_seen_ = 0;
};

// One, two and the set's largest sample count, every depth function, depth write, with and without stalls.
template <class Model>
void run_set(const RopSet& set) {
  uint64_t salt = 0;
  std::vector<int> sample_counts = {1, 2};  // and the set's largest, if larger
  if (set.max_samples > 2) sample_counts.push_back(set.max_samples);
  for (const int S : sample_counts)
    for (int f = 0; f < 8; ++f)
      for (int w = 0; w < 2; ++w)
        for (int stalls = 0; stalls < 2; ++stalls) {
          SCOPED_TRACE(std::string(set.name) + ": samples " + std::to_string(S) + ", depth function " +
                       std::to_string(f) + ", depth write " + std::to_string(w) + (stalls ? ", stalls" : ""));
          Bench<Model>(set, Run{S, DepthFunc(f), w != 0, stalls != 0}, ++salt).simulate();
          if (::testing::Test::HasFailure()) return;
        }
}

#define RAST_ROP_TEST(name, pixel_w, depth_w, max_samples, sample_log2_w, lanes, ppc, clear_ppc) \
  TEST(RtlRop, name) {                                                            \
    run_set<Vrast_rop_##name>(RopSet{#name, pixel_w, depth_w, max_samples, lanes, ppc, clear_ppc}); \
  }
RAST_ROP_SETS(RAST_ROP_TEST)

}  // namespace
