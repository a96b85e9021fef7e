// SPDX-License-Identifier: Apache-2.0
// The ROP's cache (rtl/rast_rop_cache.sv) against the reference's SetAssocCache
// (model/ref/memory/cache.h, the one source of the policy) and, independently, a
// brute-force LRU list a set, at each verilated parameter set (rop_cache_sets.h).
//
// A run is many random streams, each from reset over a random memory image: reads and
// writes (random byte enables) to addresses drawn from a window a few times the cache
// (so lines are reused and evicted) or from the whole surface, with flushes and
// invalidates among them. For every request the test checks:
// - hit or miss, and a miss's victim (valid, dirty, its line address) as SetAssocCache
//   and the LRU lists decide;
// - the memory side: a dirty victim written back (its address, and its data: the bytes
//   the core last wrote to it) and then the missed line's fill; nothing on a hit;
// - a read's word against the core's view of memory (every write applied in order);
// - a flush's write-backs in SetAssocCache::write_back_all's order (set by set, ways in
//   order) and the lists' dirty lines;
// - after the stream's last flush, the memory behind the RTL equals the reference's.
// Half the streams stall every handshake at random (ready low, fill latency 0..3); the
// other half check each request's cycles (unstalled_cycles).
// The seed is printed; RASTSIM_ROP_CACHE_SEED=<n> replays a run, =random draws a new one.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <optional>
#include <random>
#include <vector>

#include "common/rtl_unit_test.h"
#include "ref/memory/cache.h"
#include "ref/memory/surface_client.h"
#include "rop_cache_sets.h"
#include "rtlsim/port_bits.h"

namespace {

using rastsim::CacheParams;
using rastsim::FbLayout;
using rastsim::SurfaceClient;
using rastsim::SurfaceLayout;
using rastsim::SetAssocCache;
using rastsim::rtlsim::port_bits;
using rastsim::rtlsim::set_port_bits;

uint64_t seed() {
  static const uint64_t s = rastsim::test::seed_from_env("RASTSIM_ROP_CACHE_SEED", 27);
  return s;
}

struct CacheSet {
  int addr_w, cache_bytes, ways, line_bytes, word_bytes;
  int sets() const { return cache_bytes / (ways * line_bytes); }
};

enum Op { kRead = 0, kWrite = 1, kFlush = 2, kInvalidate = 3 };

// The independent check: a set's lines in recency order (front: most recent), at most
// `ways` of them, each with its dirty flag. A miss in a full set evicts the back.
class LruLists {
 public:
  struct Line {
    uint64_t line;
    bool dirty;
  };
  struct Result {
    bool hit = false;
    std::optional<Line> victim;
  };
  explicit LruLists(const CacheSet& c) : c_(c), sets_(size_t(c.sets())) {}

  Result access(uint64_t line, bool write) {
    std::vector<Line>& s = sets_[size_t(line % uint64_t(c_.sets()))];
    Result r;
    auto it = std::find_if(s.begin(), s.end(), [&](const Line& l) { return l.line == line; });
    Line now{line, write};
    if (it != s.end()) {
      r.hit = true;
      now.dirty = it->dirty || write;
      s.erase(it);
    } else if (int(s.size()) == c_.ways) {
      r.victim = s.back();
      s.pop_back();
    }
    s.insert(s.begin(), now);
    return r;
  }
  // The dirty lines of set k, sorted, and every line clean after.
  std::vector<uint64_t> flush_set(size_t k) {
    std::vector<uint64_t> out;
    for (Line& l : sets_[k])
      if (l.dirty) out.push_back(l.line), l.dirty = false;
    std::sort(out.begin(), out.end());
    return out;
  }
  void invalidate() {
    for (auto& s : sets_) s.clear();
  }

 private:
  CacheSet c_;
  std::vector<std::vector<Line>> sets_;
};

// What the RTL did for one request.
struct Observed {
  bool hit = false, evict = false, evict_dirty = false;
  uint64_t victim_addr = 0, rdata = 0;
  struct Transfer {
    bool write;  // a write-back (else a fill request)
    uint64_t addr;
  };
  std::vector<Transfer> transfers;
};

// The RTL with a memory behind its ports and the handshakes' randomness.
template <class Model>
class Bench {
 public:
  Bench(const CacheSet& c, std::vector<uint8_t>& mem, std::mt19937_64& rng, bool stalls)
      : c_(c), mem_(mem), rng_(rng), stalls_(stalls) {
    m_.req_valid_i = 0, m_.rsp_ready_i = 0, m_.fill_req_ready_i = 0, m_.fill_rsp_valid_i = 0, m_.wb_ready_i = 0;
    m_.clk_i = 0;
    m_.rst_ni = 1, m_.eval();  // a falling edge of the reset, whatever the initial value
    m_.rst_ni = 0, m_.eval();
    m_.rst_ni = 1, m_.eval();
  }
  uint64_t cycles() const { return cycles_; }

  // One request to completion (its response taken).
  Observed request(Op op, uint64_t addr, uint32_t be, uint64_t wdata) {
    Observed o;
    m_.req_valid_i = 1;
    m_.req_op_i = uint8_t(op);
    m_.req_addr_i = uint32_t(addr);
    m_.req_be_i = uint8_t(be);
    m_.req_wdata_i = uint32_t(wdata);
    bool done = false;
    for (int guard = 0; !done; ++guard) {
      if (guard > 100000) ADD_FAILURE() << "no response";
      if (guard > 100000) break;
      m_.rsp_ready_i = ready();
      m_.wb_ready_i = ready();
      m_.fill_req_ready_i = ready() && !fill_pending_;
      m_.fill_rsp_valid_i = fill_pending_ && fill_wait_ == 0;
      m_.clk_i = 0, m_.eval();
      const bool req_taken = m_.req_valid_i && m_.req_ready_o;
      if (m_.fill_req_valid_o && m_.fill_req_ready_i) {
        const uint64_t a = uint64_t(m_.fill_req_addr_o);
        o.transfers.push_back({false, a});
        for (int b = 0; b < c_.line_bytes; ++b) set_port_bits(m_.fill_rsp_data_i, 8 * b, 8, mem_.at(size_t(a) + size_t(b)));
        fill_pending_ = true;
        fill_wait_ = stalls_ ? int(rng_() % 4) : 0;
      } else if (fill_pending_ && m_.fill_rsp_valid_i && m_.fill_rsp_ready_o) {
        fill_pending_ = false;
      } else if (fill_pending_ && fill_wait_ > 0) {
        --fill_wait_;
      }
      if (m_.wb_valid_o && m_.wb_ready_i) {
        const uint64_t a = uint64_t(m_.wb_addr_o);
        o.transfers.push_back({true, a});
        for (int b = 0; b < c_.line_bytes; ++b) mem_.at(size_t(a) + size_t(b)) = uint8_t(port_bits(m_.wb_data_o, 8 * b, 8));
      }
      if (m_.rsp_valid_o && m_.rsp_ready_i) {
        o.hit = m_.rsp_hit_o, o.evict = m_.rsp_evict_o, o.evict_dirty = m_.rsp_evict_dirty_o;
        o.victim_addr = m_.rsp_victim_addr_o, o.rdata = m_.rsp_rdata_o;
        done = true;
      }
      m_.clk_i = 1, m_.eval();
      ++cycles_;
      if (req_taken) m_.req_valid_i = 0;
    }
    return o;
  }

 private:
  bool ready() { return !stalls_ || rng_() % 3 != 0; }

  CacheSet c_;
  std::vector<uint8_t>& mem_;
  std::mt19937_64& rng_;
  bool stalls_;
  Model m_;
  bool fill_pending_ = false;
  int fill_wait_ = 0;
  uint64_t cycles_ = 0;
};

// The reference side of a stream: SetAssocCache, the LRU lists, the core's view of
// memory (`view`: every write applied) and memory as the policy leaves it (`mem`).
struct Reference {
  SetAssocCache cache;
  LruLists lists;
  std::vector<uint8_t> view, mem;
};

// The line `line`'s bytes of `image`.
std::vector<uint8_t> line_bytes_of(const std::vector<uint8_t>& image, uint64_t line, int line_bytes) {
  const auto first = image.begin() + std::ptrdiff_t(line * uint64_t(line_bytes));
  return {first, first + line_bytes};
}

template <class Model>
void check_access(const CacheSet& c, Reference& ref, const std::vector<uint8_t>& rtl_mem, Op op, uint64_t addr,
                  uint32_t be, uint64_t wdata, const Observed& o) {
  const uint64_t line = addr / uint64_t(c.line_bytes);
  SetAssocCache::Victim victim;
  const bool hit = ref.cache.access(line, op == kWrite, victim);
  const LruLists::Result list = ref.lists.access(line, op == kWrite);
  ASSERT_EQ(hit, list.hit) << "SetAssocCache and the LRU lists disagree at line " << line;
  ASSERT_EQ(victim.valid, list.victim.has_value()) << "line " << line;
  if (victim.valid) ASSERT_EQ(victim.line, list.victim->line);
  if (victim.valid) ASSERT_EQ(victim.dirty, list.victim->dirty);
  ASSERT_EQ(o.hit, hit) << "op " << op << " address " << addr;
  std::vector<Observed::Transfer> want;
  if (!hit) {
    ASSERT_EQ(o.evict, victim.valid) << "address " << addr;
    ASSERT_EQ(o.evict_dirty, victim.dirty) << "address " << addr;
    if (victim.valid) ASSERT_EQ(o.victim_addr, victim.line * uint64_t(c.line_bytes));
    if (victim.dirty) {
      want.push_back({true, victim.line * uint64_t(c.line_bytes)});
      ASSERT_EQ(line_bytes_of(rtl_mem, victim.line, c.line_bytes), line_bytes_of(ref.view, victim.line, c.line_bytes))
          << "the written-back line " << victim.line << "'s data";
      const auto v = line_bytes_of(ref.view, victim.line, c.line_bytes);
      std::copy(v.begin(), v.end(), ref.mem.begin() + std::ptrdiff_t(victim.line * uint64_t(c.line_bytes)));
    }
    want.push_back({false, line * uint64_t(c.line_bytes)});
  }
  ASSERT_EQ(o.transfers.size(), want.size()) << "memory transfers of address " << addr;
  for (size_t i = 0; i < want.size(); ++i) {
    ASSERT_EQ(o.transfers[i].write, want[i].write) << "transfer " << i << " of address " << addr;
    ASSERT_EQ(o.transfers[i].addr, want[i].addr) << "transfer " << i << " of address " << addr;
  }
  const uint64_t word = addr & ~uint64_t(c.word_bytes - 1);
  if (op == kRead) {
    uint64_t expect = 0;
    for (int b = 0; b < c.word_bytes; ++b) expect |= uint64_t(ref.view[size_t(word) + size_t(b)]) << (8 * b);
    ASSERT_EQ(o.rdata, expect) << "read of address " << addr;
  } else {
    for (int b = 0; b < c.word_bytes; ++b)
      if ((be >> b) & 1) ref.view[size_t(word) + size_t(b)] = uint8_t(wdata >> (8 * b));
  }
}

void check_flush(const CacheSet& c, Reference& ref, const std::vector<uint8_t>& rtl_mem, const Observed& o) {
  std::vector<uint64_t> want;
  ref.cache.write_back_all([&](uint64_t line) { want.push_back(line); });
  ASSERT_EQ(o.transfers.size(), want.size()) << "lines a flush writes back";
  std::vector<uint64_t> by_lists;
  for (size_t k = 0; k < size_t(c.sets()); ++k) {
    std::vector<uint64_t> dirty = ref.lists.flush_set(k);
    std::vector<uint64_t> got;  // the policy's lines of set k, sorted
    for (uint64_t l : want)
      if (l % uint64_t(c.sets()) == k) got.push_back(l);
    std::sort(got.begin(), got.end());
    ASSERT_EQ(got, dirty) << "set " << k << "'s dirty lines: SetAssocCache against the LRU lists";
  }
  for (size_t i = 0; i < want.size(); ++i) {
    ASSERT_TRUE(o.transfers[i].write);
    ASSERT_EQ(o.transfers[i].addr, want[i] * uint64_t(c.line_bytes)) << "flush write-back " << i;
    if (i > 0) ASSERT_LE(want[i - 1] % uint64_t(c.sets()), want[i] % uint64_t(c.sets())) << "set by set";
    ASSERT_EQ(line_bytes_of(rtl_mem, want[i], c.line_bytes), line_bytes_of(ref.view, want[i], c.line_bytes));
    const auto v = line_bytes_of(ref.view, want[i], c.line_bytes);
    std::copy(v.begin(), v.end(), ref.mem.begin() + std::ptrdiff_t(want[i] * uint64_t(c.line_bytes)));
  }
}

struct Totals {
  uint64_t requests = 0, hits = 0, evictions = 0, dirty_evictions = 0, flushed = 0, cycles = 0;
};

// A request's cycles, from the one it is offered in to the one its response is taken in,
// when every handshake is ready and a fill answers in the cycle after its request (docs/
// rtl.md "ROP cache"), counted by hand from the sequence: taken, lookup, then a read
// hit's data, a miss's write-back (dirty victim), fill request and fill, a flush's one
// cycle a line and one a written-back line; the response.
uint64_t unstalled_cycles(const CacheSet& c, Op op, const Observed& o) {
  switch (op) {
    case kRead: return o.hit ? 4 : 5 + (o.evict_dirty ? 1 : 0);
    case kWrite: return o.hit ? 3 : 5 + (o.evict_dirty ? 1 : 0);
    case kFlush: return 3 + uint64_t(c.sets() * c.ways) + o.transfers.size();
    case kInvalidate: return 3;
  }
  return 0;
}

// One stream from reset: `n` requests, then a flush; the memories compared at the end.
template <class Model>
void run_stream(const CacheSet& c, std::mt19937_64& rng, bool stalls, int n, Totals& t) {
  const size_t bytes = size_t(1) << c.addr_w;
  Reference ref{SetAssocCache(CacheParams{uint64_t(c.cache_bytes), c.ways, c.line_bytes}), LruLists(c), {}, {}};
  ref.mem.resize(bytes);
  for (uint8_t& b : ref.mem) b = uint8_t(rng());
  ref.view = ref.mem;
  std::vector<uint8_t> rtl_mem = ref.mem;
  Bench<Model> bench(c, rtl_mem, rng, stalls);
  // A window of a few times the cache, placed at random: reuse and conflicts.
  const uint64_t window = std::min<uint64_t>(bytes, uint64_t(c.cache_bytes) * 3);
  const uint64_t window_base = (rng() % (bytes - window + 1)) & ~uint64_t(c.line_bytes - 1);
  for (int i = 0; i <= n; ++i) {
    const int r = int(rng() % 100);
    const Op op = i == n ? kFlush : r < 2 ? kFlush : r < 3 ? kInvalidate : r < 50 ? kRead : kWrite;
    const uint64_t addr = (rng() % 4 ? window_base + rng() % window : rng() % bytes) & ~uint64_t(c.word_bytes - 1);
    const uint32_t be = uint32_t(rng()) & ((1u << c.word_bytes) - 1);
    const uint64_t wdata = rng() & ((uint64_t{1} << (8 * c.word_bytes)) - 1);
    const uint64_t before = bench.cycles();
    const Observed o = bench.request(op, addr, be, wdata);
    ++t.requests;
    if (!stalls) ASSERT_EQ(bench.cycles() - before, unstalled_cycles(c, op, o)) << "cycles of request " << i;
    if (op == kFlush) {
      ASSERT_NO_FATAL_FAILURE(check_flush(c, ref, rtl_mem, o));
      t.flushed += o.transfers.size();
    } else if (op == kInvalidate) {
      ASSERT_TRUE(o.transfers.empty()) << "an invalidate moves no data";
      ref.cache.invalidate_all();
      ref.lists.invalidate();
      ref.view = ref.mem;  // dirty data dropped: the core sees memory again
    } else {
      ASSERT_NO_FATAL_FAILURE(check_access<Model>(c, ref, rtl_mem, op, addr, be, wdata, o)) << "request " << i;
      t.hits += o.hit, t.evictions += o.evict, t.dirty_evictions += o.evict_dirty;
    }
  }
  ASSERT_EQ(rtl_mem, ref.mem) << "memory after the final flush";
  ASSERT_EQ(ref.mem, ref.view) << "the reference's memory holds every write after the flush";
  t.cycles += bench.cycles();
}

template <class Model>
void run_set(const CacheSet& c) {
  std::mt19937_64 rng(seed() + uint64_t(c.cache_bytes) * 131 + uint64_t(c.ways));
  Totals t;
  for (int s = 0; s < 1000; ++s) {
    ASSERT_NO_FATAL_FAILURE(run_stream<Model>(c, rng, s % 2 == 1, 100, t)) << "stream " << s;
  }
  std::printf("%llu requests: %llu hits, %llu evictions (%llu dirty), %llu lines flushed, %llu cycles\n",
              (unsigned long long)t.requests, (unsigned long long)t.hits, (unsigned long long)t.evictions,
              (unsigned long long)t.dirty_evictions, (unsigned long long)t.flushed, (unsigned long long)t.cycles);
  // The streams reach every case (a test that never evicts a dirty line checks nothing).
  EXPECT_GT(t.hits, t.requests / 10);
  EXPECT_GT(t.dirty_evictions, t.requests / 50);
  EXPECT_GT(t.flushed, 1000u);
}

// The ROP's access pattern through SurfaceClient, the class the reference ROP counts
// render --stats with: a surface of the set's whole address space (word_bytes a sample,
// one sample a pixel; square, or 2:1), linear and tiled (4 x 4 px tiles), drawn as random
// rectangles walked tile by tile (tiles row-major, pixels row-major in a tile), each
// pixel a read then (three times in four) a write, as a depth test and its write; a
// clear now and then (the client drops its lines; the RTL invalidates); the frame end's
// write-back (the RTL flushes). The RTL's hits, misses, evictions and write-backs must be
// the client's, and so the bytes it reads and writes through the cache.
template <class Model>
void run_surface(const CacheSet& c, FbLayout layout) {
  std::mt19937_64 rng(seed() + uint64_t(c.cache_bytes) + (layout == FbLayout::Tiled ? 7 : 0));
  const int pixels = (1 << c.addr_w) / c.word_bytes;
  int w = 1;
  while (w * w < pixels) w *= 2;  // square, or twice as wide as high
  const int h = pixels / w;
  const SurfaceLayout lay(layout, 4, 4, 0, w, h, 1, c.word_bytes);
  ASSERT_EQ(lay.footprint_bytes(), uint64_t(1) << c.addr_w);
  SurfaceClient client(lay, CacheParams{uint64_t(c.cache_bytes), c.ways, c.line_bytes}, false, 4, 4);
  std::vector<uint8_t> mem(size_t(1) << c.addr_w, 0);
  Bench<Model> bench(c, mem, rng, true);
  uint64_t hits = 0, misses = 0, evictions = 0, writebacks = 0, clear_bytes = 0;
  const auto count = [&](const Observed& o) {
    hits += o.hit, misses += !o.hit, evictions += o.evict, writebacks += o.evict_dirty;
  };
  for (int r = 0; r < 200; ++r) {
    if (rng() % 10 == 0) {
      client.clear();
      clear_bytes += lay.footprint_bytes();
      bench.request(kInvalidate, 0, 0, 0);
      continue;
    }
    const int x0 = int(rng() % uint64_t(w)), y0 = int(rng() % uint64_t(h));
    const int x1 = std::min(w, x0 + 1 + int(rng() % 12)), y1 = std::min(h, y0 + 1 + int(rng() % 12));
    for (int ty = y0 / 4 * 4; ty < y1; ty += 4)
      for (int tx = x0 / 4 * 4; tx < x1; tx += 4)
        for (int y = std::max(ty, y0); y < std::min(ty + 4, y1); ++y)
          for (int x = std::max(tx, x0); x < std::min(tx + 4, x1); ++x) {
            const uint64_t off = lay.offset_of(x, y, 0);
            client.access(x, y, 0, false);
            count(bench.request(kRead, off, 0, 0));
            if (rng() % 4 == 0) continue;
            client.access(x, y, 0, true);
            count(bench.request(kWrite, off, (1u << c.word_bytes) - 1, rng()));
          }
  }
  client.write_back_all();
  writebacks += bench.request(kFlush, 0, 0, 0).transfers.size();
  const rastsim::MemoryClientStats& st = client.stats();
  EXPECT_EQ(hits, st.hits);
  EXPECT_EQ(misses, st.misses);
  EXPECT_EQ(evictions, st.evictions);
  EXPECT_EQ(writebacks, st.writebacks);
  EXPECT_EQ(misses * uint64_t(c.line_bytes), st.bytes_read);
  EXPECT_EQ(writebacks * uint64_t(c.line_bytes) + clear_bytes, st.bytes_written);
  EXPECT_GT(st.hits, st.accesses / 3);  // the walk reuses lines (a write after its read hits, at least)
  EXPECT_GT(st.writebacks, 10u);
}

#define RAST_ROP_CACHE_TEST(name, addr_w, cache_bytes, ways, line_bytes, word_bytes)                              \
  TEST(RtlRopCache, RandomStreams_##name) {                                                                       \
    run_set<Vrast_rop_cache_##name>(CacheSet{addr_w, cache_bytes, ways, line_bytes, word_bytes});                \
  }                                                                                                               \
  TEST(RtlRopCache, SurfaceClientCounts_##name) {                                                                 \
    for (FbLayout l : {FbLayout::Linear, FbLayout::Tiled})                                                        \
      run_surface<Vrast_rop_cache_##name>(CacheSet{addr_w, cache_bytes, ways, line_bytes, word_bytes}, l);       \
  }
RAST_ROP_CACHE_SETS(RAST_ROP_CACHE_TEST)
#undef RAST_ROP_CACHE_TEST

}  // namespace
