// SPDX-License-Identifier: Apache-2.0
// The reciprocal unit (rtl/rast_recip.sv) against the reference's recip_newton (model/ref/
// recip.h) at each verilated parameter set (SEED_BITS, ITERATIONS): the first and the last
// divisor of every seed table interval (so every entry, and both ends of the range, 2^39
// and 2^40 - 1), then kRandom random divisors in [2^39, 2^40). Results must be equal bit
// for bit and leave in the order they entered, none lost or made up.
//
// The handshake: half the blocks of divisors run without stalls, where every result must
// leave exactly 1 + 2 * ITERATIONS cycles after its divisor entered; the other half with
// random gaps on in_valid_i and random stalls on out_ready_i. The seed is printed;
// RASTSIM_RECIP_SEED=<n> replays a run, RASTSIM_RECIP_SEED=random draws a new one.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <deque>
#include <random>
#include <vector>

#include "Vrast_recip_12_1.h"
#include "Vrast_recip_1_0.h"
#include "Vrast_recip_8_2.h"
#include "common/rtl_unit_test.h"
#include "ref/recip.h"

namespace {

constexpr int kRandom = 1'000'000;   // random divisors a parameter set
constexpr int kBlock = 1000;         // divisors a block (stalls on or off for the block)
constexpr uint64_t kLow = uint64_t{1} << 39;  // the smallest normalised divisor

uint64_t seed() {
  static const uint64_t s = rastsim::test::seed_from_env("RASTSIM_RECIP_SEED", 26);
  return s;
}

// The first and last divisor of each of the 2^b seed intervals, then random ones.
std::vector<uint64_t> divisors(int seed_bits, uint64_t salt) {
  std::vector<uint64_t> v;
  const int shift = 39 - seed_bits;  // the interval's width, log2
  for (uint64_t i = 0; i < (uint64_t{1} << seed_bits); ++i) {
    v.push_back(kLow | i << shift);
    v.push_back((kLow | i << shift) + (uint64_t{1} << shift) - 1);
  }
  std::mt19937_64 rng(seed() ^ salt);
  for (int i = 0; i < kRandom; ++i) v.push_back(kLow | (rng() & (kLow - 1)));
  return v;
}

struct Result {
  int checked = 0, mismatches = 0, latency_errors = 0;
  long cycles = 0;
};

// Streams `ds` through the model; every result is compared with recip_newton.
template <class Model>
Result run(int seed_bits, int iterations, const std::vector<uint64_t>& ds, uint64_t salt) {
  Model m;
  std::mt19937_64 rng(seed() ^ salt ^ 0x5eed);
  const long latency = 1 + 2 * iterations;
  auto tick = [&] { rastsim::test::clock_cycle(m); };
  rastsim::test::reset_stream(m);
  struct InFlight {
    uint64_t d;
    long entered;
  };
  std::deque<InFlight> queue;
  Result r;
  bool stalls = false, block_open = false;  // a block opens with the pipeline empty
  size_t next = 0;
  long& cycle = r.cycles;
  auto check_out = [&] {
    if (queue.empty()) {
      ADD_FAILURE() << "a result out that never went in, cycle " << cycle;
      return;
    }
    const InFlight f = queue.front();
    queue.pop_front();
    const uint64_t want = rastsim::recip_newton(f.d, seed_bits, iterations);
    if (m.y_o != want && ++r.mismatches <= 10)
      ADD_FAILURE() << "d = 0x" << std::hex << f.d << ": RTL 0x" << m.y_o << ", recip_newton 0x" << want;
    r.latency_errors += !stalls && cycle - f.entered != latency;
    ++r.checked;
  };
  while (next < ds.size() || !queue.empty()) {
    if (!block_open && next < ds.size() && queue.empty()) stalls = (next / kBlock) % 2 == 1, block_open = true;
    const bool have = block_open && next < ds.size();
    m.in_valid_i = have && (!stalls || rng() % 4 != 0);
    m.out_ready_i = !stalls || rng() % 3 != 0;
    m.d_i = have ? ds[next] : kLow;
    m.eval();
    if (m.out_valid_o && m.out_ready_i) check_out();
    if (m.in_valid_i && m.in_ready_o) {
      queue.push_back({ds[next++], cycle});
      block_open = next % kBlock != 0;
    }
    tick(), ++cycle;
  }
  EXPECT_FALSE(m.out_valid_o);
  return r;
}

template <class Model>
void check_set(int seed_bits, int iterations, uint64_t salt) {
  const std::vector<uint64_t> ds = divisors(seed_bits, salt);
  const Result r = run<Model>(seed_bits, iterations, ds, salt);
  EXPECT_EQ(r.mismatches, 0) << "of " << r.checked;
  EXPECT_EQ(r.latency_errors, 0);
  EXPECT_EQ(size_t(r.checked), ds.size());  // none lost
  std::printf("SEED_BITS %d, ITERATIONS %d: %d divisors in %ld cycles, %d mismatches\n", seed_bits, iterations,
              r.checked, r.cycles, r.mismatches);
}

TEST(RtlRecip, Seed8Steps2) { check_set<Vrast_recip_8_2>(8, 2, 1); }
TEST(RtlRecip, Seed12Steps1) { check_set<Vrast_recip_12_1>(12, 1, 3); }
TEST(RtlRecip, Seed1Steps0) { check_set<Vrast_recip_1_0>(1, 0, 5); }

// Hand-worked, independent of the reference: with 1 index bit the seed table is
// {round(2^5 / 5), round(2^5 / 7)} = {6, 5} (6.4 and 4.57) in units of 2^-2, so with no
// step y = 6 * 2^38 for d in [2^39, 2^39 + 2^38) and 5 * 2^38 above; latency 1 cycle.
TEST(RtlRecip, HandWorkedSeedOnly) {
  Vrast_recip_1_0 m;
  m.clk_i = 0, m.rst_ni = 0, m.in_valid_i = 0, m.out_ready_i = 1;
  m.eval();
  m.rst_ni = 1;
  const uint64_t ds[] = {kLow, kLow + (uint64_t{1} << 38) - 1, kLow + (uint64_t{1} << 38), (kLow << 1) - 1};
  const uint64_t want[] = {6ull << 38, 6ull << 38, 5ull << 38, 5ull << 38};
  for (int i = 0; i < 4; ++i) {
    m.in_valid_i = 1, m.d_i = ds[i];
    m.eval();
    ASSERT_TRUE(m.in_ready_o);
    m.clk_i = 1, m.eval();
    m.clk_i = 0, m.in_valid_i = 0, m.eval();
    ASSERT_TRUE(m.out_valid_o);
    EXPECT_EQ(m.y_o, want[i]) << "d = 0x" << std::hex << ds[i];
  }
}

}  // namespace
