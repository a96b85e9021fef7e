// SPDX-License-Identifier: Apache-2.0
// The DRAM timing model (dram.h; the equations and the scheduling rules are in
// docs/memory.md, "The DRAM model").
#include "timing/dram.h"

#include <algorithm>
#include <bit>
#include <numeric>
#include <stdexcept>

namespace rastsim {

namespace {

__extension__ typedef unsigned __int128 Wide;  // core cycle * kHz needs more than 64 bits

// "Long ago": every constraint measured from it is met at clock 0, and adding a timing
// parameter to it cannot overflow.
constexpr int64_t kNever = INT64_MIN / 4;
// Read-to-write bus turnaround beyond the read's data: JESD79-4 4.19 (RL + BL/2 - WL + 2
// clocks with 1-clock preambles), used for every preset.
constexpr int64_t kReadToWriteGap = 2;

struct FieldName {
  DramField field;
  const char* name;
};
constexpr FieldName kFieldNames[] = {{DramField::Row, "ro"},
                                     {DramField::Channel, "ch"},
                                     {DramField::Bank, "ba"},
                                     {DramField::BankGroup, "bg"},
                                     {DramField::Column, "co"}};

bool pow2(int64_t v) { return v > 0 && std::has_single_bit(uint64_t(v)); }

// v * mul / div, rounded up or down; in 64 bits when v <= limit (then v * mul + div - 1
// fits), else in 128.
uint64_t scale_clock(uint64_t v, uint64_t mul, uint64_t div, uint64_t limit, bool round_up) {
  const uint64_t add = round_up ? div - 1 : 0;
  if (v <= limit) return (v * mul + add) / div;
  return uint64_t((Wide(v) * mul + add) / div);
}

}  // namespace

std::vector<DramField> parse_address_map(const std::string& text) {
  std::vector<DramField> map;
  size_t at = 0;
  while (at <= text.size()) {
    const size_t colon = std::min(text.find(':', at), text.size());
    const std::string name = text.substr(at, colon - at);
    const FieldName* f = std::find_if(std::begin(kFieldNames), std::end(kFieldNames),
                                      [&](const FieldName& n) { return name == n.name; });
    if (f == std::end(kFieldNames) || std::find(map.begin(), map.end(), f->field) != map.end())
      throw std::invalid_argument("address map \"" + text + "\": field \"" + name +
                                  "\" is unknown or repeated; give each of ro, ch, ba, bg, co once, MSB "
                                  "first, separated by ':'");
    map.push_back(f->field);
    at = colon + 1;
  }
  if (map.size() != std::size(kFieldNames))
    throw std::invalid_argument("address map \"" + text + "\" must name each of ro, ch, ba, bg, co once");
  return map;
}

std::string address_map_name(const std::vector<DramField>& map) {
  std::string s;
  for (DramField f : map)
    for (const FieldName& n : kFieldNames)
      if (n.field == f) s += (s.empty() ? "" : ":") + std::string(n.name);
  return s;
}

std::string DramParams::check() const {
  if (core_khz == 0 || dram_khz == 0) return "clock frequencies must be positive";
  if (!pow2(channels) || !pow2(bank_groups) || !pow2(banks_per_group) || !pow2(rows) || !pow2(columns))
    return "channels, bank groups, banks a group, rows and columns must be powers of two";
  if (bus_bits <= 0 || bus_bits % 8 != 0) return "the bus width must be a positive multiple of 8 bits";
  if (!pow2(burst_length) || transfers_per_clock <= 0 || burst_length % transfers_per_clock != 0)
    return "the burst length must be a power of two and a multiple of the transfers a clock";
  if (columns < burst_length) return "a row must hold at least one burst";
  if (queue_depth < 1) return "the queue depth must be at least 1";
  if (address_map.size() != std::size(kFieldNames)) return "the address map must name every field once";
  for (int64_t t : {tCL, tCWL, tRCD, tRCD_WR, tRP, tRAS, tRC, tCCD_S, tCCD_L, tRRD_S, tRRD_L, tFAW, t32AW, tWR,
                    tWTR_S, tWTR_L, tRTP, tRFC})
    if (t < 1) return "every timing parameter must be at least 1 clock";
  if (tREFI <= tRFC) return "tREFI must exceed tRFC";
  return {};
}

DramAddress decode_address(const DramParams& p, uint64_t address) { return DramAddressDecoder(p)(address); }

DramAddressDecoder::DramAddressDecoder(const DramParams& p) {
  int shift = std::countr_zero(p.burst_bytes());  // the offset within a burst
  for (auto it = p.address_map.rbegin(); it != p.address_map.rend(); ++it) {
    int64_t count = 0;  // the field's values (a power of two)
    switch (*it) {
      case DramField::Row: count = p.rows; break;
      case DramField::Channel: count = p.channels; break;
      case DramField::Bank: count = p.banks_per_group; break;
      case DramField::BankGroup: count = p.bank_groups; break;
      case DramField::Column: count = p.columns / std::max(p.burst_length, 1); break;
    }
    const int width = std::countr_zero(uint64_t(count));
    const size_t f = size_t(*it);
    shift_[f] = shift < 64 ? shift : 0;
    mask_[f] = shift >= 64 ? 0 : width >= 64 ? ~uint64_t{0} : (uint64_t{1} << width) - 1;
    shift += width;
  }
}

DramAddress DramAddressDecoder::operator()(uint64_t address) const {
  const auto field = [&](DramField f) { return (address >> shift_[size_t(f)]) & mask_[size_t(f)]; };
  DramAddress a;
  a.row = int64_t(field(DramField::Row));
  a.channel = int(field(DramField::Channel));
  a.bank = int(field(DramField::Bank));
  a.bank_group = int(field(DramField::BankGroup));
  a.column = int64_t(field(DramField::Column));
  return a;
}

double DramClientStats::row_hit_rate() const {
  const uint64_t n = row_hits + row_misses + row_conflicts;
  return n ? double(row_hits) / double(n) : 0.0;
}

DramClientStats DramStats::total() const {
  DramClientStats t;
  for (const DramClientStats& c : clients) {
    t.bytes_read += c.bytes_read, t.bytes_written += c.bytes_written;
    t.bursts_read += c.bursts_read, t.bursts_written += c.bursts_written;
    t.row_hits += c.row_hits, t.row_misses += c.row_misses, t.row_conflicts += c.row_conflicts;
    t.data_bus_clocks += c.data_bus_clocks;
    t.requests_read += c.requests_read, t.read_latency_cycles += c.read_latency_cycles;
  }
  return t;
}

DramModel::DramModel(DramParams params) : p_(std::move(params)), decode_(p_) {
  if (const std::string why = p_.check(); !why.empty()) throw std::invalid_argument("DRAM parameters: " + why);
  const uint64_t common = std::gcd(p_.dram_khz, p_.core_khz);
  dram_ratio_ = p_.dram_khz / common;
  core_ratio_ = p_.core_khz / common;
  to_dram_limit_ = (UINT64_MAX - (core_ratio_ - 1)) / dram_ratio_;
  to_core_limit_ = (UINT64_MAX - (dram_ratio_ - 1)) / core_ratio_;
  starvation_clocks_ = int64_t(to_dram(p_.starvation_cycles));
  channels_.resize(size_t(p_.channels));
  for (Channel& ch : channels_) {
    ch.banks.resize(size_t(p_.banks()));
    ch.busy_banks.assign((ch.banks.size() + 63) / 64, 0);
    ch.group.assign(size_t(p_.bank_groups), GroupBounds{kNever, kNever, kNever});
    ch.acts.fill(kNever);
    ch.next_refresh = p_.tREFI;
  }
}

uint64_t DramModel::to_dram(uint64_t c) const {
  return scale_clock(c, dram_ratio_, core_ratio_, to_dram_limit_, true);
}

uint64_t DramModel::to_core(uint64_t d) const {
  return scale_clock(d, core_ratio_, dram_ratio_, to_core_limit_, true);
}

double DramModel::bandwidth_utilisation(uint64_t busy_clocks, uint64_t elapsed_cycles) const {
  const double clocks = double(elapsed_cycles) * double(p_.dram_khz) / double(p_.core_khz) * p_.channels;
  return clocks > 0 ? double(busy_clocks) / clocks : 0.0;
}

void DramModel::enqueue(const DramRequest& r, uint64_t cycle) {
  if (cycle < last_arrival_ || cycle < advanced_)
    throw std::invalid_argument("DRAM request at core cycle " + std::to_string(cycle) +
                                " arrives before an earlier request or the model's time " +
                                std::to_string(std::max(last_arrival_, advanced_)));
  if (r.bytes == 0 || r.client < 0) throw std::invalid_argument("DRAM request of 0 bytes or a negative client");
  last_arrival_ = cycle;
  if (size_t(r.client) >= stats_.clients.size()) stats_.clients.resize(size_t(r.client) + 1);
  const uint64_t bb = p_.burst_bytes();
  const uint64_t first = r.address / bb, last = (r.address + r.bytes - 1) / bb;
  const size_t number = next_request_++;
  pending_.push_back(Pending{r, cycle, int(last - first + 1), 0});
  const int64_t eligible = int64_t(to_dram(cycle));
  for (uint64_t n = first; n <= last; ++n) {
    Burst b;
    b.seq = next_seq_++;
    b.request = number;
    b.at = decode_(n * bb);
    b.eligible = eligible;
    b.write = r.write;
    Channel& ch = channels_[size_t(b.at.channel)];
    if (ch.queued < size_t(p_.queue_depth) && ch.backlog.empty())
      queue_burst(ch, b);
    else
      ch.backlog.push_back(b);
  }
}

void DramModel::queue_burst(Channel& ch, const Burst& b) {
  const size_t k = size_t(bank_index(b.at));
  Bank& bank = ch.banks[k];
  bank.queue.push_back(b);
  ch.busy_banks[k / 64] |= uint64_t{1} << (k % 64);
  if (b.at.row == bank.open_row) ++bank.hits[b.write];
  ++ch.queued;
  touch(ch, bank);
}

// The first clock at which an offer's command meets every constraint (docs/memory.md,
// "Timing equations"): the burst's eligible clock and the bank's own state (offer.ready),
// the command bus, the other banks through its bank group's bounds (Channel::group) and
// the activate windows.
inline int64_t DramModel::earliest(const Channel& ch, const Bank::Offer& offer) const {
  const GroupBounds& group = ch.group[size_t(offer.group)];
  const int64_t t = std::max(offer.ready, ch.last_cmd + 1);
  switch (offer.cmd) {
    case Cmd::Pre: return t;
    case Cmd::Act:
      return std::max({t, group.act, ch.acts[(ch.next_act + 28) % ch.acts.size()] + p_.tFAW,
                       ch.acts[ch.next_act] + p_.t32AW});
    case Cmd::Read: return std::max(t, group.read);
    case Cmd::Write: return std::max(t, group.write);
  }
  return t;
}

// Raises every bank group's bounds for a command `cmd` issued at clock `at` in group
// `from`: the same group's by the _L spacing, the others' by the _S one. A column
// command raises both column bounds, in one pass over the groups.
void DramModel::raise_group_bounds(Channel& ch, int from, Cmd cmd, int64_t at) {
  const int64_t burst = p_.burst_clocks();
  // The new bounds, [0] in group `from`, [1] in the others.
  int64_t read[2] = {kNever, kNever}, write[2] = {kNever, kNever};
  switch (cmd) {
    case Cmd::Pre: return;
    case Cmd::Act:
      for (size_t g = 0; g < ch.group.size(); ++g) {
        int64_t& b = ch.group[g].act;
        b = std::max(b, at + (int(g) == from ? p_.tRRD_L : p_.tRRD_S));
      }
      return;
    case Cmd::Read: {
      read[0] = at + std::max(burst, p_.tCCD_L), read[1] = at + std::max(burst, p_.tCCD_S);
      write[0] = write[1] = at + p_.tCL + burst - p_.tCWL + kReadToWriteGap;  // the bus turnaround
      break;
    }
    case Cmd::Write:
      write[0] = at + std::max(burst, p_.tCCD_L), write[1] = at + std::max(burst, p_.tCCD_S);
      read[0] = at + p_.tCWL + burst + p_.tWTR_L, read[1] = at + p_.tCWL + burst + p_.tWTR_S;
      break;
  }
  for (size_t g = 0; g < ch.group.size(); ++g) {
    GroupBounds& b = ch.group[g];
    const size_t other = int(g) == from ? 0 : 1;
    b.read = std::max(b.read, read[other]);
    b.write = std::max(b.write, write[other]);
  }
}

// choose() for bank k (its queue not empty): its offers against the best so far, by
// clock and then by the tie-break number (Bank::Offer::tie).
inline void DramModel::consider(const Channel& ch, int k, Choice& best, uint64_t& best_tie) const {
  const Bank& bank = ch.banks[size_t(k)];
  if (!bank.offers_fresh) make_offers(bank);
  for (int o = 0; o < bank.offer_count; ++o) {
    const Bank::Offer& offer = bank.offers[size_t(o)];
    const int64_t at = earliest(ch, offer);
    if (at < best.at || (at == best.at && offer.tie < best_tie))
      best = {at, k, offer.index, offer.cmd}, best_tie = offer.tie;
  }
}

// FR-FCFS: the command that can issue first; at the same clock a column command (a row
// hit) before an activate or precharge, then the oldest burst. A precharge that would
// close a row some queued burst still wants waits. Each bank offers only the oldest
// burst of each command it has (dram.h, Bank: the others cannot win); the answer is
// kept until the channel changes. Only the banks with queued bursts are visited.
DramModel::Choice DramModel::choose(const Channel& ch) const {
  if (ch.choice_valid) return ch.choice;
  Choice best;
  best.at = INT64_MAX;  // every offer's clock is below it (earliest() >= 0)
  uint64_t best_tie = 0;
  for (size_t word = 0; word < ch.busy_banks.size(); ++word)
    for (uint64_t bits = ch.busy_banks[word]; bits != 0; bits &= bits - 1) {
      const int k = int(word * 64) + std::countr_zero(bits);
      consider(ch, k, best, best_tie);
    }
  if (best.at == INT64_MAX) best.at = -1;
  if (starvation_clocks_ > 0 && best.at >= 0) cap_starvation(ch, best);
  ch.choice = best;
  ch.choice_valid = true;
  return best;
}

// The starvation cap (dram.starvation_cycles): the channel's oldest queued burst (the one
// with the earliest eligible clock, the first to starve) starves from clock D = its
// eligible clock + the cap. FR-FCFS's choice stands if it issues before D; otherwise the
// oldest burst's own next command issues instead, at D at the earliest: its column
// command if its row is open, its ACT if its bank is closed, else the PRE of the open row
// (even one that queued row hits still want). From D on, its own bank issues nothing
// else first, and another bank's command goes first only if it issues strictly before the
// starving one could (so the other banks keep working while it waits for its bank).
void DramModel::cap_starvation(const Channel& ch, Choice& best) const {
  int oldest = -1;
  for (size_t word = 0; word < ch.busy_banks.size(); ++word)
    for (uint64_t bits = ch.busy_banks[word]; bits != 0; bits &= bits - 1) {
      const int k = int(word * 64) + std::countr_zero(bits);
      if (oldest < 0 || ch.banks[size_t(k)].queue.front().seq < ch.banks[size_t(oldest)].queue.front().seq)
        oldest = k;
    }
  const Bank& bank = ch.banks[size_t(oldest)];
  const Burst& b = bank.queue.front();
  const int64_t starving = b.eligible + starvation_clocks_;
  if (best.at < starving) return;
  Bank::Offer offer;
  offer.group = b.at.bank_group;
  if (bank.open_row == b.at.row)
    offer.cmd = b.write ? Cmd::Write : Cmd::Read, offer.ready = b.write ? bank.write_ok : bank.read_ok;
  else if (bank.open_row < 0)
    offer.cmd = Cmd::Act, offer.ready = bank.act_ok;
  else
    offer.cmd = Cmd::Pre, offer.ready = bank.pre_ok;
  offer.ready = std::max(offer.ready, b.eligible);
  const int64_t at = std::max(earliest(ch, offer), starving);
  // Another bank's command may still go first, if it issues strictly before the starving one could.
  if (best.bank != oldest && best.at < at) return;
  best = {at, oldest, 0, offer.cmd};
}

// A bank's candidates: its oldest burst's ACT or PRE when no burst wants its open row (or
// it is closed), else its oldest read hit and oldest write hit, as far as there are any.
void DramModel::make_offers(const Bank& bank) const {
  bank.offer_count = 0;
  bank.offers_fresh = true;
  const auto offer = [&](size_t index, Cmd cmd) {
    const Burst& b = bank.queue[index];
    const int64_t bound = cmd == Cmd::Act   ? bank.act_ok
                          : cmd == Cmd::Pre ? bank.pre_ok
                          : cmd == Cmd::Read ? bank.read_ok
                                             : bank.write_ok;
    const bool column = cmd == Cmd::Read || cmd == Cmd::Write;
    bank.offers[size_t(bank.offer_count++)] = {index, cmd, b.at.bank_group, std::max(b.eligible, bound),
                                               (column ? 0 : uint64_t{1} << 63) | b.seq};
  };
  if (bank.hits[0] + bank.hits[1] == 0) return offer(0, bank.open_row < 0 ? Cmd::Act : Cmd::Pre);
  bool read = bank.hits[0] == 0, write = bank.hits[1] == 0;
  for (size_t i = 0; i < bank.queue.size() && !(read && write); ++i) {
    const Burst& b = bank.queue[i];
    if (b.at.row != bank.open_row || (b.write ? write : read)) continue;
    (b.write ? write : read) = true;
    offer(i, b.write ? Cmd::Write : Cmd::Read);
  }
}

void DramModel::issue(Channel& ch, const Choice& c) {
  Bank& bank = ch.banks[size_t(c.bank)];
  Burst& b = bank.queue[c.index];
  ch.last_cmd = c.at;
  touch(ch, bank);
  constexpr DramCommand::Kind kKind[] = {DramCommand::Activate, DramCommand::Precharge, DramCommand::Read,
                                         DramCommand::Write};
  note(ch, c.at, kKind[int(c.cmd)], b.at);
  switch (c.cmd) {
    case Cmd::Pre:
      bank.open_row = -1;
      bank.hits = {};
      bank.act_ok = std::max(bank.act_ok, c.at + p_.tRP);
      b.precharged = true;
      ++stats_.precharges;
      return;
    case Cmd::Act:
      bank.open_row = b.at.row;
      for (const Burst& q : bank.queue)
        if (q.at.row == bank.open_row) ++bank.hits[q.write];
      bank.read_ok = c.at + p_.tRCD;
      bank.write_ok = c.at + p_.tRCD_WR;
      bank.pre_ok = std::max(bank.pre_ok, c.at + p_.tRAS);
      bank.act_ok = std::max(bank.act_ok, c.at + p_.tRC);
      raise_group_bounds(ch, b.at.bank_group, Cmd::Act, c.at);
      ch.acts[ch.next_act] = c.at;
      ch.next_act = (ch.next_act + 1) % ch.acts.size();
      b.activated = true;
      ++stats_.activates;
      return;
    case Cmd::Read:
    case Cmd::Write: {
      const Burst done = b;
      bank.queue.erase(bank.queue.begin() + std::ptrdiff_t(c.index));
      if (bank.queue.empty()) ch.busy_banks[size_t(c.bank) / 64] &= ~(uint64_t{1} << (size_t(c.bank) % 64));
      --bank.hits[done.write];
      --ch.queued;
      issue_column(ch, done, c.at);
      admit(ch, c.at);
      return;
    }
  }
}

void DramModel::issue_column(Channel& ch, Burst b, int64_t at) {
  Bank& bank = ch.banks[size_t(bank_index(b.at))];
  const int64_t end = at + (b.write ? p_.tCWL : p_.tCL) + p_.burst_clocks();
  raise_group_bounds(ch, b.at.bank_group, b.write ? Cmd::Write : Cmd::Read, at);
  if (b.write)
    bank.pre_ok = std::max(bank.pre_ok, end + p_.tWR);
  else
    bank.pre_ok = std::max(bank.pre_ok, at + p_.tRTP);
  if (p_.page_policy == PagePolicy::Closed) {  // auto-precharge: no command bus slot
    bank.open_row = -1;
    bank.hits = {};
    bank.act_ok = std::max(bank.act_ok, bank.pre_ok + p_.tRP);
    ++stats_.precharges;
  }
  Pending& p = pending(b.request);
  DramClientStats& s = stats_.clients[size_t(p.req.client)];
  (b.write ? s.bytes_written : s.bytes_read) += p_.burst_bytes();
  ++(b.write ? s.bursts_written : s.bursts_read);
  ++(b.precharged ? s.row_conflicts : b.activated ? s.row_misses : s.row_hits);
  s.data_bus_clocks += uint64_t(p_.burst_clocks());
  p.end = std::max(p.end, end);
  if (--p.bursts_left > 0) return;
  const uint64_t cycle = to_core(uint64_t(p.end));
  if (!p.req.write) ++s.requests_read, s.read_latency_cycles += cycle - p.arrival;
  done_.push(Done{DramCompletion{cycle, p.req.tag, p.req.client}, b.request});
  while (!pending_.empty() && pending_.front().bursts_left == 0) pending_.pop_front(), ++first_pending_;
}

void DramModel::admit(Channel& ch, int64_t at) {
  while (ch.queued < size_t(p_.queue_depth) && !ch.backlog.empty()) {
    Burst b = ch.backlog.front();
    ch.backlog.pop_front();
    b.eligible = std::max(b.eligible, at);
    queue_burst(ch, b);
  }
}

// All-bank refresh when due (no postponement): precharge every open bank in one command
// once each may close, then REF tRP later and once every bank may activate; no bank
// activates for tRFC after it.
void DramModel::refresh(Channel& ch) {
  const int64_t start = std::max(ch.next_refresh, ch.last_cmd + 1);
  int64_t pre_at = start;
  bool any_open = false;
  for (const Bank& bank : ch.banks)
    if (bank.open_row >= 0) any_open = true, pre_at = std::max(pre_at, bank.pre_ok);
  int64_t ref_at = any_open ? pre_at + p_.tRP : start;
  for (const Bank& bank : ch.banks) ref_at = std::max(ref_at, bank.act_ok);
  for (Bank& bank : ch.banks) bank.open_row = -1, bank.hits = {}, bank.act_ok = ref_at + p_.tRFC, touch(ch, bank);
  ch.last_cmd = ref_at;
  note(ch, ref_at, DramCommand::Refresh, DramAddress{});
  ch.next_refresh += p_.tREFI;
  ++stats_.refreshes;
  if (any_open) ++stats_.precharges;
}

uint64_t DramModel::next_event() const {
  uint64_t next = kNoEvent;
  if (!done_.empty()) next = done_.top().completion.cycle;
  for (const Channel& ch : channels_) {
    const Choice c = choose(ch);
    // The first core cycle whose DRAM clock comes after c.at: advance_to() issues it.
    if (c.at >= 0)
      next = std::min(next, scale_clock(uint64_t(c.at), core_ratio_, dram_ratio_, to_core_limit_, false) + 1);
  }
  return next;
}

void DramModel::advance_to(uint64_t cycle) {
  const int64_t horizon = int64_t(to_dram(cycle));
  for (Channel& ch : channels_) {
    while (true) {
      const Choice c = choose(ch);
      if (ch.next_refresh < horizon && (c.at < 0 || ch.next_refresh <= c.at)) {
        refresh(ch);
        continue;
      }
      if (c.at < 0 || c.at >= horizon) break;
      issue(ch, c);
    }
  }
  advanced_ = std::max(advanced_, cycle);
}

// Flattened: every call below it (next_event, advance_to, choose, issue) is inlined into
// the one loop the memory system runs each step, so an event pays no call overheads.
[[gnu::flatten]] uint64_t DramModel::advance_events(uint64_t last) {
  uint64_t advanced = kNoEvent;
  for (uint64_t e = next_event(); e != kNoEvent && e <= last; e = next_event()) {
    advance_to(e);
    advanced = e;
    if (has_completions()) break;
  }
  return advanced;
}

uint64_t DramModel::drain_end_cycle() const {
  DramModel copy(*this);
  copy.log_ = nullptr;
  uint64_t end = 0;
  for (uint64_t e = copy.next_event(); e != kNoEvent; e = copy.next_event()) {
    copy.advance_to(e);
    for (const DramCompletion& d : copy.take_completions()) end = std::max(end, d.cycle);
  }
  return end;
}

const std::vector<DramCompletion>& DramModel::take_completions() {
  taken_.clear();
  for (; !done_.empty() && done_.top().completion.cycle <= advanced_; done_.pop())
    taken_.push_back(done_.top().completion);
  return taken_;
}

}  // namespace rastsim
