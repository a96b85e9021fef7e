// SPDX-License-Identifier: Apache-2.0
// The DRAM timing model every memory client shares (docs/memory.md): channels, bank
// groups, banks, rows and columns; open- or closed-page; a request queue a channel with
// FR-FCFS command scheduling; the JEDEC timing constraints in DRAM clocks; all-bank
// refresh. Event-driven: the caller enqueues requests at core cycles and advances the
// model to the next event, never ticking an idle cycle. Deterministic.
//
// Units: a request's arrival and completion are core cycles; everything inside is DRAM
// clocks (the command clock CK). A core cycle c maps to the DRAM clock ceil(c * f_dram /
// f_core) (the first DRAM edge at or after the core edge), a DRAM clock d back to the
// core cycle ceil(d * f_core / f_dram); both clocks are whole kHz, so the ratio is exact
// (kept reduced, so the products fit 64 bits for any cycle below 2^64 / f_dram in kHz).
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <functional>
#include <queue>
#include <string>
#include <utility>
#include <vector>

namespace rastsim {

enum class PagePolicy { Open, Closed };

// The fields of a DRAM address, from the burst offset upward (address_map).
enum class DramField { Row, Channel, Bank, BankGroup, Column };

// Every parameter of the model; times in DRAM clocks unless named otherwise. Built from
// the config's memory.preset and dram.* keys (config/dram_config.h); no defaults here.
struct DramParams {
  std::string preset;             // the preset these came from, for the stats
  uint64_t core_khz = 0;          // clock.core_mhz, whole kHz
  uint64_t dram_khz = 0;          // the command clock CK, whole kHz
  int channels = 0, bank_groups = 0, banks_per_group = 0;  // powers of two
  int64_t rows = 0;               // rows a bank (power of two)
  int64_t columns = 0;            // column addresses a row, each bus_bits wide (power of two)
  int bus_bits = 0;               // data bus width of one channel
  int burst_length = 0;           // BL: transfers a column access
  int transfers_per_clock = 0;    // data transfers a CK a pin (2: DDR; 8: GDDR6 QDR on WCK = 2 CK)
  PagePolicy page_policy = PagePolicy::Open;
  int queue_depth = 0;            // bursts a channel's scheduler sees at once
  // Starvation cap (docs/memory.md, "Scheduling"), core cycles; 0: off. A burst that has
  // waited this long in the scheduler's queue (from its eligible clock) is served next:
  // its bank issues nothing else first, and another bank's command only one that can
  // issue strictly before it.
  uint64_t starvation_cycles = 0;
  // MSB first, e.g. {Row, Bank, Column, BankGroup, Channel}; each field once. The low
  // log2(burst_bytes()) address bits are the offset within a burst and are dropped.
  std::vector<DramField> address_map;
  int64_t tCL = 0, tCWL = 0, tRCD = 0, tRCD_WR = 0, tRP = 0, tRAS = 0, tRC = 0;
  int64_t tCCD_S = 0, tCCD_L = 0, tRRD_S = 0, tRRD_L = 0, tFAW = 0;
  int64_t t32AW = 0;  // GDDR: at most 32 activates in it (implied by tFAW when <= 7 tFAW)
  int64_t tWR = 0, tWTR_S = 0, tWTR_L = 0, tRTP = 0, tREFI = 0, tRFC = 0;

  int banks() const { return bank_groups * banks_per_group; }
  uint64_t burst_bytes() const { return uint64_t(bus_bits) / 8 * uint64_t(burst_length); }
  int64_t burst_clocks() const { return burst_length / transfers_per_clock; }  // data bus per burst
  uint64_t row_bytes() const { return uint64_t(columns) * uint64_t(bus_bits) / 8; }
  // The peak data rate of every channel together, bytes a second.
  double peak_bytes_per_second() const {
    return double(channels) * bus_bits / 8 * transfers_per_clock * double(dram_khz) * 1e3;
  }
  // Empty when the parameters are usable, else what is wrong (the config layer names
  // the key).
  std::string check() const;
};

// Parses "ro:ba:co:bg:ch" (row, bank, column, bank group, channel; MSB first, each once).
// Throws std::invalid_argument naming the allowed fields.
std::vector<DramField> parse_address_map(const std::string& text);
std::string address_map_name(const std::vector<DramField>& map);

// Where a byte address lands.
struct DramAddress {
  int channel = 0, bank_group = 0, bank = 0;  // bank: within its group
  int64_t row = 0, column = 0;                // column in bursts
};
DramAddress decode_address(const DramParams& p, uint64_t address);

// decode_address with the fields' bit positions worked out once: a field is
// (address >> shift) & mask, the shift counting the burst offset and every field below it.
class DramAddressDecoder {
 public:
  explicit DramAddressDecoder(const DramParams& p);
  DramAddress operator()(uint64_t address) const;

 private:
  // By DramField: the shift in bits and the mask (0: the field lies wholly above bit 63).
  std::array<int, 5> shift_{};
  std::array<uint64_t, 5> mask_{};
};

struct DramRequest {
  uint64_t address = 0;  // bytes
  bool write = false;
  uint32_t bytes = 0;    // split into the bursts it touches
  int client = 0;        // index into the stats' clients
  uint64_t tag = 0;      // returned with the completion
};

// A request is complete when the data of its last burst has crossed the bus (a read's
// last beat arrives, a write's last beat is driven).
struct DramCompletion {
  uint64_t cycle = 0;  // core cycle
  uint64_t tag = 0;
  int client = 0;
};

// Counts of one client (row hits etc. count bursts).
struct DramClientStats {
  uint64_t bytes_read = 0, bytes_written = 0, bursts_read = 0, bursts_written = 0;
  uint64_t row_hits = 0, row_misses = 0, row_conflicts = 0;  // open row / closed bank / other row open
  uint64_t data_bus_clocks = 0;                               // DRAM clocks of its data on the bus
  uint64_t requests_read = 0, read_latency_cycles = 0;        // core cycles, arrival to completion
  double row_hit_rate() const;
};

struct DramStats {
  std::vector<DramClientStats> clients;
  uint64_t activates = 0, precharges = 0, refreshes = 0;
  DramClientStats total() const;
};

// One DRAM command, for tests and traces of the schedule (DramModel::log_commands).
struct DramCommand {
  enum Kind : char { Activate = 'A', Precharge = 'P', Read = 'R', Write = 'W', Refresh = 'F' };
  int64_t clock = 0;  // DRAM clock it issues at (a refresh: its REF; auto-precharges are not listed)
  Kind kind = Activate;
  int channel = 0, bank_group = 0, bank = 0;  // a refresh: every bank of the channel
  int64_t row = 0;
};

class DramModel {
 public:
  explicit DramModel(DramParams params);  // throws std::invalid_argument when check() fails

  // A request arriving at core cycle `cycle`; cycles must not decrease from call to call
  // and must not be below the last advance_to(). It may be decided on from DRAM clock
  // to_dram(cycle).
  void enqueue(const DramRequest& request, uint64_t cycle);
  // The next core cycle at which advance_to() has something to do (a command to issue or
  // a completion to report), assuming no further requests; kNoEvent when idle.
  uint64_t next_event() const;
  // Issues every command before DRAM clock to_dram(cycle) (every command a request
  // arriving at `cycle` could not have competed for) and the refreshes due before it.
  void advance_to(uint64_t cycle);
  // The completions at or before the last advance_to() cycle, by cycle then arrival;
  // valid until the next call.
  const std::vector<DramCompletion>& take_completions();
  // take_completions() would return some.
  bool has_completions() const { return !done_.empty() && done_.top().completion.cycle <= advanced_; }
  // next_event() and advance_to() in one call, event after event: advances to each next
  // event at or before core cycle `last` and stops after the first that leaves
  // completions to take (or when the next event comes after `last`). Returns the cycle
  // of the last event advanced to, kNoEvent when none was. The same calls, decisions and
  // completions as the loop `while (next_event() <= last) { advance_to(next_event());
  // if (has_completions()) break; }`.
  uint64_t advance_events(uint64_t last);

  // The core cycle the last request queued now would complete at if none arrived after
  // it (its last completion, posted writes included; 0 when idle): a copy of the model
  // advanced event by event, this one untouched. Frame sampling's DRAM backlog
  // (MemorySystem::backlog_cycles).
  uint64_t drain_end_cycle() const;

  // Appends every command issued from now on to *log (nullptr: stop).
  void log_commands(std::vector<DramCommand>* log) { log_ = log; }

  const DramParams& params() const { return p_; }
  const DramStats& stats() const { return stats_; }
  // Data bus busy clocks over the DRAM clocks of `elapsed_cycles` core cycles times
  // the channels.
  double bandwidth_utilisation(uint64_t busy_clocks, uint64_t elapsed_cycles) const;
  uint64_t to_dram(uint64_t core_cycle) const;  // ceil(core_cycle * f_dram / f_core)
  uint64_t to_core(uint64_t dram_clock) const;  // ceil(dram_clock * f_core / f_dram)

  static constexpr uint64_t kNoEvent = ~uint64_t{0};

 private:
  enum class Cmd { Act, Pre, Read, Write };
  struct Burst {
    uint64_t seq = 0;  // arrival order: the FCFS key
    size_t request = 0;
    DramAddress at;
    int64_t eligible = 0;  // DRAM clock
    bool write = false, precharged = false, activated = false;
  };
  // The scheduler's queue is kept a bank at a time. Within a channel a burst's eligible
  // clock never decreases with its arrival order (arrivals come in non-decreasing cycles
  // at or after the last advance, and a burst admitted from the backlog becomes eligible
  // at the clock its slot freed, before any later arrival's), so among a bank's bursts
  // wanting the same command the oldest can issue first and wins the FCFS tie: each
  // bank offers at most three candidates (its oldest read hit and write hit, or its
  // oldest burst's ACT or PRE) and a decision costs O(banks), not O(queue^2).
  struct Bank {
    int64_t open_row = -1;
    int64_t act_ok = 0, pre_ok = 0, read_ok = 0, write_ok = 0;
    std::vector<Burst> queue;  // this bank's queued bursts, in arrival order
    std::array<int, 2> hits{};  // how many of them want open_row: reads [0], writes [1]
    // The bank's candidates (above: a burst's index into queue and its command), kept
    // while offers_fresh, i.e. until its queue, open row or bounds change (touch()).
    struct Offer {
      size_t index = 0;
      Cmd cmd = Cmd::Act;
      int group = 0;      // the burst's bank group
      int64_t ready = 0;  // DRAM clock: the burst's eligible clock and the bank's bound for cmd
      // The FR-FCFS tie-break at equal clocks as one number: bit 63 set for an ACT or PRE
      // (a column command goes first), below it the burst's seq (the oldest goes first).
      uint64_t tie = 0;
    };
    mutable std::array<Offer, 2> offers{};
    mutable int offer_count = 0;
    mutable bool offers_fresh = false;
  };
  struct Choice {
    int64_t at = -1;  // DRAM clock; -1: nothing to issue
    int bank = 0;     // index into Channel::banks
    size_t index = 0; // into that bank's queue
    Cmd cmd = Cmd::Act;
  };
  // The channel's constraints between banks are kept as the first clock each command may
  // issue at in each bank group, raised as commands issue (docs/memory.md, "Timing
  // equations"): commands on a channel issue at increasing clocks, so the latest command
  // of a kind in a group sets the bound, and a decision reads one value a candidate.
  struct GroupBounds {
    int64_t act = 0, read = 0, write = 0;  // DRAM clock; tRRD, tCCD and the tWTR / read-to-write turnarounds
  };
  struct Channel {
    std::vector<Bank> banks;
    // Bit k of word k / 64: bank k's queue is not empty (choose() visits those banks only,
    // in bank order).
    std::vector<uint64_t> busy_banks;
    size_t queued = 0;           // bursts in the banks' queues together: at most queue_depth
    std::deque<Burst> backlog;   // waiting for a queue slot, in arrival order
    mutable Choice choice;       // choose()'s answer while choice_valid
    mutable bool choice_valid = false;
    int64_t last_cmd = -1;       // the command bus carries one command a clock
    std::vector<GroupBounds> group;  // by bank group
    std::array<int64_t, 32> acts{};  // the last 32 activates, a ring: acts[next_act] is the oldest
    size_t next_act = 0;             // (tFAW: the 4th newest, acts[(next_act + 28) % 32]; t32AW: the oldest)
    int64_t next_refresh = 0;
  };
  struct Pending {  // a request with bursts outstanding
    DramRequest req;
    uint64_t arrival = 0;
    int bursts_left = 0;
    int64_t end = 0;  // DRAM clock its last data beat ends so far
  };
  struct Done {  // a completion not yet taken; request: its number (the order at equal cycles)
    DramCompletion completion;
    uint64_t request = 0;
    bool operator>(const Done& o) const {
      return completion.cycle != o.completion.cycle ? completion.cycle > o.completion.cycle : request > o.request;
    }
  };

  Choice choose(const Channel& ch) const;
  void cap_starvation(const Channel& ch, Choice& best) const;
  void consider(const Channel& ch, int k, Choice& best, uint64_t& best_tie) const;
  void make_offers(const Bank& bank) const;
  static void touch(Channel& ch, Bank& bank) { bank.offers_fresh = false, ch.choice_valid = false; }
  int64_t earliest(const Channel& ch, const Bank::Offer& offer) const;
  void queue_burst(Channel& ch, const Burst& b);
  void issue(Channel& ch, const Choice& c);
  void issue_column(Channel& ch, Burst b, int64_t at);
  void raise_group_bounds(Channel& ch, int group, Cmd cmd, int64_t at);
  void refresh(Channel& ch);
  void admit(Channel& ch, int64_t at);
  void note(const Channel& ch, int64_t at, DramCommand::Kind kind, const DramAddress& a) {
    if (log_) log_->push_back({at, kind, int(&ch - channels_.data()), a.bank_group, a.bank, a.row});
  }
  int bank_index(const DramAddress& a) const { return a.bank_group * p_.banks_per_group + a.bank; }
  Pending& pending(size_t request) { return pending_[request - first_pending_]; }

  DramParams p_;
  DramAddressDecoder decode_;
  // f_dram / f_core reduced: to_dram and to_core multiply and divide by these, in 64 bits
  // below the limits (the products fit), else in 128.
  uint64_t dram_ratio_ = 1, core_ratio_ = 1, to_dram_limit_ = 0, to_core_limit_ = 0;
  int64_t starvation_clocks_ = 0;  // starvation_cycles in DRAM clocks, rounded up (0: off)
  std::vector<Channel> channels_;
  // Requests by number from first_pending_ on (completed ones at the front are dropped;
  // completed ones behind an outstanding one stay, with bursts_left 0).
  std::deque<Pending> pending_;
  size_t first_pending_ = 0;
  std::priority_queue<Done, std::vector<Done>, std::greater<Done>> done_;  // earliest first
  std::vector<DramCompletion> taken_;  // take_completions()' answer
  uint64_t next_seq_ = 0, next_request_ = 0, last_arrival_ = 0, advanced_ = 0;
  DramStats stats_;
  std::vector<DramCommand>* log_ = nullptr;
};

}  // namespace rastsim
