// SPDX-License-Identifier: Apache-2.0
// The DRAM model against figures worked by hand from its timing parameters
// (docs/memory.md, "Timing equations"). The core clock equals the DRAM clock unless a
// test says otherwise, so a cycle is a DRAM clock.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "timing/dram.h"
#include "timing/dram_trace.h"

namespace rastsim {
namespace {

// Distinct round numbers, so a wrong term shows in the sum. Bursts are 64 bytes (64-bit
// bus, BL8) over 4 clocks.
DramParams test_params() {
  DramParams p;
  p.preset = "test";
  p.core_khz = p.dram_khz = 1'000'000;
  p.channels = 1, p.bank_groups = 2, p.banks_per_group = 4, p.rows = 1024, p.columns = 1024;
  p.bus_bits = 64, p.burst_length = 8, p.transfers_per_clock = 2;
  p.page_policy = PagePolicy::Open;
  p.queue_depth = 32;
  p.address_map = parse_address_map("ro:ba:co:bg:ch");
  p.tCL = 11, p.tCWL = 9, p.tRCD = 13, p.tRCD_WR = 13, p.tRP = 17, p.tRAS = 30, p.tRC = 47;
  p.tCCD_S = 4, p.tCCD_L = 6, p.tRRD_S = 5, p.tRRD_L = 7, p.tFAW = 30, p.t32AW = 30;
  p.tWR = 15, p.tWTR_S = 3, p.tWTR_L = 8, p.tRTP = 7, p.tREFI = 1'000'000, p.tRFC = 300;
  return p;
}

// The byte address of a burst under "ro:ba:co:bg:ch" with the fields above: 6 offset
// bits, 1 bank-group bit, 7 column bits (128 bursts a row), 2 bank bits, then the row.
uint64_t address(int64_t row, int bank, int bank_group, int64_t column) {
  return ((((uint64_t(row) << 2 | uint64_t(bank)) << 7 | uint64_t(column)) << 1 | uint64_t(bank_group)) << 6);
}

// Runs the model until it has nothing left to do; returns every completion.
std::vector<DramCompletion> drain(DramModel& m) {
  std::vector<DramCompletion> all;
  for (uint64_t at = m.next_event(); at != DramModel::kNoEvent; at = m.next_event()) {
    m.advance_to(at);
    for (const DramCompletion& c : m.take_completions()) all.push_back(c);
  }
  return all;
}

// The latency of one 64-byte read at `cycle` after `before` (completed first).
uint64_t read_latency(DramModel& m, uint64_t addr, uint64_t cycle) {
  m.enqueue({addr, false, 64, 0, 7}, cycle);
  const auto done = drain(m);
  EXPECT_EQ(done.size(), 1u);
  return done.empty() ? 0 : done[0].cycle - cycle;
}

TEST(Dram, AddressMapPlacesFieldsMsbFirst) {
  const DramParams p = test_params();
  const DramAddress a = decode_address(p, address(37, 3, 1, 101) + 17);
  EXPECT_EQ(a.row, 37);
  EXPECT_EQ(a.bank, 3);
  EXPECT_EQ(a.bank_group, 1);
  EXPECT_EQ(a.column, 101);
  EXPECT_EQ(a.channel, 0);
  EXPECT_EQ(address_map_name(p.address_map), "ro:ba:co:bg:ch");
  EXPECT_THROW(parse_address_map("ro:ba:co:bg"), std::invalid_argument);
  EXPECT_THROW(parse_address_map("ro:ba:co:bg:bg"), std::invalid_argument);
}

TEST(Dram, ClockConversionRoundsUpBothWays) {
  DramParams p = test_params();
  p.core_khz = 500'000, p.dram_khz = 1'200'000;  // 500 MHz core, DDR4-2400 CK
  DramModel m(p);
  EXPECT_EQ(m.to_dram(5), 12u);  // 5 * 2.4 = 12 exactly
  EXPECT_EQ(m.to_dram(6), 15u);  // 14.4 -> 15
  EXPECT_EQ(m.to_core(12), 5u);
  EXPECT_EQ(m.to_core(13), 6u);  // 5.42 -> 6
}

TEST(Dram, RowMissCostsRcdPlusClPlusBurst) {
  DramModel m(test_params());
  EXPECT_EQ(read_latency(m, address(5, 0, 0, 0), 100), 13u + 11u + 4u);
  EXPECT_EQ(m.stats().clients[0].row_misses, 1u);
}

TEST(Dram, DrainEndCycleIsTheLastCompletionAndLeavesTheModelAsItWas) {
  DramModel m(test_params());
  EXPECT_EQ(m.drain_end_cycle(), 0u);  // idle
  // One read to a closed row at 100: tRCD + tCL + the burst, by hand.
  m.enqueue({address(5, 0, 0, 0), false, 64, 0, 2}, 100);
  EXPECT_EQ(m.drain_end_cycle(), 100u + 13u + 11u + 4u);
  // A conflicting read and a posted write behind it: the copy's answer is the last of the
  // completions the model itself reports when it is drained afterwards (asking did not
  // advance it: a second ask gives the same, and the first completion is still 128).
  m.enqueue({address(6, 0, 0, 0), false, 64, 0, 4}, 100);
  m.enqueue({address(7, 1, 0, 0), true, 256, 1, 5}, 100);
  const uint64_t end = m.drain_end_cycle();
  EXPECT_EQ(m.drain_end_cycle(), end);
  const auto done = drain(m);
  ASSERT_EQ(done.size(), 3u);
  EXPECT_EQ(done[0].cycle, 128u);
  uint64_t last = 0;
  for (const DramCompletion& c : done) last = std::max(last, c.cycle);
  EXPECT_EQ(end, last);
  EXPECT_GT(end, 128u + 17u);  // the conflict's precharge at least
  EXPECT_EQ(m.drain_end_cycle(), 0u);  // idle again
}

TEST(Dram, RowHitCostsClPlusBurst) {
  DramModel m(test_params());
  read_latency(m, address(5, 0, 0, 0), 100);
  EXPECT_EQ(read_latency(m, address(5, 0, 0, 9), 1000), 11u + 4u);
  EXPECT_EQ(m.stats().clients[0].row_hits, 1u);
}

TEST(Dram, RowConflictCostsRpPlusRcdPlusClPlusBurst) {
  DramModel m(test_params());
  read_latency(m, address(5, 0, 0, 0), 100);
  EXPECT_EQ(read_latency(m, address(6, 0, 0, 0), 1000), 17u + 13u + 11u + 4u);
  EXPECT_EQ(m.stats().clients[0].row_conflicts, 1u);
  EXPECT_EQ(m.stats().activates, 2u);
}

// 256 bytes over both bank groups (4 bursts): ACT bg0 at 0, ACT bg1 at tRRD_S = 5; reads
// at 13 (bg0), 18 (bg1: 5 + tRCD), 22 (bg0: 18 + tCCD_S beats 13 + tCCD_L), 26 (bg1);
// the last data beat ends at 26 + CL + burst = 41.
TEST(Dram, MultiBurstRequestCompletesWithItsLastBurst) {
  DramModel m(test_params());
  m.enqueue({address(5, 0, 0, 0), false, 256, 0, 3}, 0);
  const auto done = drain(m);
  ASSERT_EQ(done.size(), 1u);
  EXPECT_EQ(done[0].cycle, 41u);
  EXPECT_EQ(done[0].tag, 3u);
  EXPECT_EQ(m.stats().clients[0].bytes_read, 256u);
}

// A read after a write waits for the write data and tWTR: ACT at 0, WR at tRCD = 13, RD
// at 13 + CWL + burst + tWTR_L = 34 in the same bank group, 13 + 9 + 4 + 3 = 29 in the
// other one.
TEST(Dram, WriteToReadTurnaroundIsAtLeastTwtr) {
  for (int other_group : {0, 1}) {
    SCOPED_TRACE(other_group);
    DramModel m(test_params());
    std::vector<DramCommand> log;
    m.log_commands(&log);
    m.enqueue({address(5, 0, 0, 0), true, 64, 0, 1}, 0);
    m.enqueue({address(5, 0, other_group, 1), false, 64, 0, 2}, 0);
    drain(m);
    auto at = [&](DramCommand::Kind k) {
      auto it = std::find_if(log.begin(), log.end(), [&](const DramCommand& c) { return c.kind == k; });
      return it == log.end() ? int64_t{-1} : it->clock;
    };
    EXPECT_EQ(at(DramCommand::Write), 13);
    EXPECT_EQ(at(DramCommand::Read), other_group ? 29 : 34);
    EXPECT_GE(at(DramCommand::Read) - (at(DramCommand::Write) + 9 + 4), other_group ? 3 : 8);
  }
}

// FR-FCFS: an older conflicting burst waits while a younger one hits the open row.
TEST(Dram, RowHitOvertakesOlderConflict) {
  DramModel m(test_params());
  read_latency(m, address(5, 0, 0, 0), 0);
  m.enqueue({address(6, 0, 0, 0), false, 64, 0, 1}, 1000);  // conflict, older
  m.enqueue({address(5, 0, 0, 1), false, 64, 0, 2}, 1000);  // hit, younger
  const auto done = drain(m);
  ASSERT_EQ(done.size(), 2u);
  EXPECT_EQ(done[0].tag, 2u);
  EXPECT_EQ(done[0].cycle, 1000u + 11 + 4);
  EXPECT_EQ(done[1].tag, 1u);
}

// The starvation cap (dram.starvation_cycles): row 5 open in bank 0 (a read at 0: ACT 0,
// RD 13); at 1000 a conflict C (row 6) and then eight younger hits H1..H8 (row 5), all one
// bank group, so column commands are tCCD_L = 6 apart.
// Off: the hits read at 1000, 1006, ..., 1042; C's PRE at 1042 + tRTP = 1049, ACT 1066,
// RD 1079, done 1079 + CL + burst = 1094, last.
// Cap 20: C starves from 1020. H1..H4 read at 1000..1018 (done 1015..1033); H5 could
// read at 1024 >= 1020, so C's PRE goes first, at 1018 + tRTP = 1025; ACT 1042, RD 1055,
// done 1070. H5..H8 (now starving too, row 6 open) then PRE at ACT + tRAS = 1072, ACT
// 1089 (= 1042 + tRC), RD 1102, 1108, 1114, 1120: done 1117 .. 1135.
// Row 5 opened at 0; at core cycle 1000 the conflict C (tag 100, row 6) and then `hits`
// younger hits (tags 1..hits, row 5) in bank 0: every completion.
std::vector<DramCompletion> conflict_behind_hits(const DramParams& p, int hits) {
  DramModel m(p);
  read_latency(m, address(5, 0, 0, 0), 0);
  m.enqueue({address(6, 0, 0, 0), false, 64, 0, 100}, 1000);
  for (int k = 1; k <= hits; ++k) m.enqueue({address(5, 0, 0, k), false, 64, 0, uint64_t(k)}, 1000);
  return drain(m);
}

TEST(Dram, StarvationCapServesTheOldestBurst) {
  for (const uint64_t cap : {uint64_t{0}, uint64_t{20}}) {
    SCOPED_TRACE(cap);
    DramParams p = test_params();
    p.starvation_cycles = cap;
    const auto done = conflict_behind_hits(p, 8);
    ASSERT_EQ(done.size(), 9u);
    std::vector<uint64_t> tags, cycles;
    for (const DramCompletion& c : done) tags.push_back(c.tag), cycles.push_back(c.cycle);
    if (cap == 0) {
      EXPECT_EQ(tags, (std::vector<uint64_t>{1, 2, 3, 4, 5, 6, 7, 8, 100}));
      EXPECT_EQ(cycles, (std::vector<uint64_t>{1015, 1021, 1027, 1033, 1039, 1045, 1051, 1057, 1094}));
    } else {
      EXPECT_EQ(tags, (std::vector<uint64_t>{1, 2, 3, 4, 100, 5, 6, 7, 8}));
      EXPECT_EQ(cycles, (std::vector<uint64_t>{1015, 1021, 1027, 1033, 1070, 1117, 1123, 1129, 1135}));
    }
  }
}

// The cap counts core cycles: at a 500 MHz core and a 1200 MHz DRAM clock, 20 cycles are
// 48 DRAM clocks, so C (arriving at core cycle 1000, DRAM clock 2400) starves from DRAM
// clock 2448, and the hits that read before it (from 2400, 6 apart) are 2400 .. 2442: 8.
TEST(Dram, StarvationCapCountsCoreCycles) {
  DramParams p = test_params();
  p.core_khz = 500'000, p.dram_khz = 1'200'000;
  p.starvation_cycles = 20;
  const auto done = conflict_behind_hits(p, 12);
  ASSERT_EQ(done.size(), 13u);
  size_t before = 0;
  while (before < done.size() && done[before].tag != 100) ++before;
  EXPECT_EQ(before, 8u);
}

TEST(Dram, ClosedPageMakesEveryAccessAMiss) {
  DramParams p = test_params();
  p.page_policy = PagePolicy::Closed;
  DramModel m(p);
  for (int i = 0; i < 16; ++i) m.enqueue({address(5, 0, 0, i), false, 64, 0, uint64_t(i)}, 0);
  EXPECT_EQ(drain(m).size(), 16u);
  const DramClientStats& s = m.stats().clients[0];
  EXPECT_EQ(s.row_misses, 16u);
  EXPECT_EQ(s.row_hits + s.row_conflicts, 0u);
  EXPECT_EQ(m.stats().activates, 16u);
}

// The activates of 3000 random reads (every one a miss or a conflict), in order.
std::vector<DramCommand> random_activates(const DramParams& p) {
  DramModel m(p);
  std::vector<DramCommand> log;
  m.log_commands(&log);
  uint64_t seed = 12345, x = seed;
  std::printf("seed %llu\n", static_cast<unsigned long long>(seed));
  for (int i = 0; i < 3000; ++i) {
    x = x * 6364136223846793005ull + 1442695040888963407ull;
    const uint64_t r = x >> 33;
    m.enqueue({address(int64_t(r % 1024), int(r >> 10) & 3, int(r >> 12) & 1, int64_t(r >> 13) & 127), false, 64, 0,
               uint64_t(i)},
              0);
  }
  EXPECT_EQ(drain(m).size(), 3000u);
  std::vector<DramCommand> acts;
  std::copy_if(log.begin(), log.end(), std::back_inserter(acts),
               [](const DramCommand& c) { return c.kind == DramCommand::Activate; });
  EXPECT_GT(acts.size(), 2000u);
  return acts;
}

// The shortest span of `n` + 1 consecutive activates.
int64_t tightest(const std::vector<DramCommand>& acts, size_t n) {
  int64_t t = INT64_MAX;
  for (size_t i = 0; i + n < acts.size(); ++i) t = std::min(t, acts[i + n].clock - acts[i].clock);
  return t;
}

// Consecutive activates are tRRD_S apart (other group) or tRRD_L (same group); no five
// inside tFAW. With tFAW = 30 > 4 * tRRD_S = 20 and 8 banks, tFAW is the binding limit:
// some window is exactly full.
TEST(Dram, TfawAndTrrdBoundRandomActivates) {
  const std::vector<DramCommand> acts = random_activates(test_params());
  int64_t tightest_pair = INT64_MAX;
  for (size_t i = 0; i + 1 < acts.size(); ++i) {
    const int64_t gap = acts[i + 1].clock - acts[i].clock;
    EXPECT_GE(gap, acts[i + 1].bank_group == acts[i].bank_group ? 7 : 5) << "activate " << i;
    if (acts[i + 1].bank_group != acts[i].bank_group) tightest_pair = std::min(tightest_pair, gap);
  }
  EXPECT_EQ(tightest(acts, 4), 30);  // five activates span at least tFAW; some exactly
  EXPECT_EQ(tightest_pair, 5);
}

// GDDR6's t32AW: with 400 clocks > 7 tFAW, no 33 activates inside it, some exactly.
TEST(Dram, T32awBoundsRandomActivates) {
  DramParams p = test_params();
  p.t32AW = 400;
  const std::vector<DramCommand> acts = random_activates(p);
  EXPECT_EQ(tightest(acts, 32), 400);
  EXPECT_GE(tightest(acts, 4), 30);
}

// A long sequential read stream on DDR4-2400 (JESD79-4B: CL 17, tRCD 17, tRP 17, tRAS 39,
// tCCD_S 4, tCCD_L 6, tRRD_S 7, tRRD_L 8, tFAW 36, tREFI 9360, tRFC 420 for 8 Gb; 64-bit
// channel): bank groups alternate burst by burst, so tCCD_S = BL/2 = 4 and the bus could
// carry 16 bytes a clock but for refresh, (1 - tRFC/tREFI) of the time.
TEST(Dram, SequentialStreamReachesPeakLessRefresh) {
  DramParams p = test_params();
  p.rows = 65536;
  p.tCL = 17, p.tCWL = 12, p.tRCD = p.tRCD_WR = 17, p.tRP = 17, p.tRAS = 39, p.tRC = 55;
  p.tCCD_S = 4, p.tCCD_L = 6, p.tRRD_S = 7, p.tRRD_L = 8, p.tFAW = 36, p.t32AW = 36, p.tWR = 18, p.tWTR_S = 3, p.tWTR_L = 9;
  p.tRTP = 9, p.tREFI = 9360, p.tRFC = 420;
  DramModel m(p);
  const int kBursts = 100'000;  // 6.4 MB, 42 refresh intervals
  for (int i = 0; i < kBursts; ++i) m.enqueue({uint64_t(i) * 64, false, 64, 0, uint64_t(i)}, 0);
  const auto done = drain(m);
  ASSERT_EQ(done.size(), size_t(kBursts));
  const double clocks = double(done.back().cycle);
  const double bytes_per_clock = double(kBursts) * 64 / clocks;
  const double expected = 16.0 * (1.0 - 420.0 / 9360.0);
  std::printf("stream: %.4f bytes/clock, peak less refresh %.4f (%.2f %%), %llu refreshes, row hit rate %.4f\n",
              bytes_per_clock, expected, 100 * (bytes_per_clock / expected - 1),
              static_cast<unsigned long long>(m.stats().refreshes), m.stats().total().row_hit_rate());
  EXPECT_NEAR(bytes_per_clock / expected, 1.0, 0.02);
  EXPECT_NEAR(m.bandwidth_utilisation(m.stats().total().data_bus_clocks, done.back().cycle), bytes_per_clock / 16,
              1e-9);
}

TEST(Dram, RefreshBlocksActivatesForTrfc) {
  DramParams p = test_params();
  p.tREFI = 1000, p.tRFC = 300;
  DramModel m(p);
  std::vector<DramCommand> log;
  m.log_commands(&log);
  // A read arriving just after refresh fell due at tREFI = 1000 waits for REF + tRFC.
  m.enqueue({address(5, 0, 0, 0), false, 64, 0, 1}, 1001);
  const auto done = drain(m);
  ASSERT_EQ(done.size(), 1u);
  EXPECT_EQ(m.stats().refreshes, 1u);
  // REF at 1000 (all banks closed), ACT at 1300, RD at 1313, data ends 1328.
  EXPECT_EQ(done[0].cycle, 1000u + 300 + 13 + 11 + 4);
  ASSERT_GE(log.size(), 2u);
  EXPECT_EQ(log[0].kind, DramCommand::Refresh);
  EXPECT_EQ(log[0].clock, 1000);
}

TEST(DramTrace, WritesOneLineABurstAndReadsItBack) {
  const DramParams p = test_params();
  std::stringstream s;
  write_dram_trace(s, p, {0x1000 + 32, true, 64, 0, 0}, 12);  // straddles two bursts
  write_dram_trace(s, p, {0x2000, false, 8, 0, 0}, 40);
  EXPECT_EQ(s.str(), "0x1000 WRITE 12\n0x1040 WRITE 12\n0x2000 READ 40\n");
  const auto lines = read_dram_trace(s, "t");
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_TRUE(lines[1].write);
  EXPECT_EQ(lines[1].address, 0x1040u);
  EXPECT_EQ(lines[2].clock, 40u);
  std::istringstream bad("0x10 READ 5\n\n0x20 FETCH 6\n");
  try {
    read_dram_trace(bad, "bad.trace");
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.trace:3:"), std::string::npos) << e.what();
  }
  std::istringstream backwards("0x10 READ 5\n0x20 READ 4\n");
  EXPECT_THROW(read_dram_trace(backwards, "b"), std::runtime_error);
}

}  // namespace
}  // namespace rastsim
