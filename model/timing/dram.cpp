// SPDX-License-Identifier: Apache-2.0
// The DRAM timing model (dram.h; the equations and the scheduling rules are in
// docs/memory.md, "The DRAM model").
#include "timing/dram.h"

#include <algorithm>
#include <bit>
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

DramAddress decode_address(const DramParams& p, uint64_t address) {
  uint64_t bits = address >> std::countr_zero(p.burst_bytes());
  DramAddress a;
  for (auto it = p.address_map.rbegin(); it != p.address_map.rend(); ++it) {
    auto take = [&](int64_t count) {
      const int64_t v = int64_t(bits & uint64_t(count - 1));
      bits >>= std::countr_zero(uint64_t(count));
      return v;
    };
    switch (*it) {
      case DramField::Row: a.row = take(p.rows); break;
      case DramField::Channel: a.channel = int(take(p.channels)); break;
      case DramField::Bank: a.bank = int(take(p.banks_per_group)); break;
      case DramField::BankGroup: a.bank_group = int(take(p.bank_groups)); break;
      case DramField::Column: a.column = take(p.columns / p.burst_length); break;
    }
  }
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

DramModel::DramModel(DramParams params) : p_(std::move(params)) {
  if (const std::string why = p_.check(); !why.empty()) throw std::invalid_argument("DRAM parameters: " + why);
  channels_.resize(size_t(p_.channels));
  for (Channel& ch : channels_) {
    ch.banks.resize(size_t(p_.banks()));
    ch.last_act.assign(size_t(p_.bank_groups), kNever);
    ch.last_read.assign(size_t(p_.bank_groups), kNever);
    ch.last_write.assign(size_t(p_.bank_groups), kNever);
    ch.acts.fill(kNever);
    ch.next_refresh = p_.tREFI;
  }
}

uint64_t DramModel::to_dram(uint64_t c) const {
  return uint64_t((Wide(c) * p_.dram_khz + p_.core_khz - 1) / p_.core_khz);
}

uint64_t DramModel::to_core(uint64_t d) const {
  return uint64_t((Wide(d) * p_.core_khz + p_.dram_khz - 1) / p_.dram_khz);
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
  pending_[number] = Pending{r, cycle, int(last - first + 1), 0};
  for (uint64_t n = first; n <= last; ++n) {
    Burst b;
    b.seq = next_seq_++;
    b.request = number;
    b.at = decode_address(p_, n * bb);
    b.eligible = int64_t(to_dram(cycle));
    b.write = r.write;
    Channel& ch = channels_[size_t(b.at.channel)];
    if (ch.queued < size_t(p_.queue_depth) && ch.backlog.empty())
      queue_burst(ch, b);
    else
      ch.backlog.push_back(b);
  }
}

void DramModel::queue_burst(Channel& ch, const Burst& b) {
  Bank& bank = ch.banks[size_t(bank_index(b.at))];
  bank.queue.push_back(b);
  if (b.at.row == bank.open_row) ++bank.hits[b.write];
  ++ch.queued;
  ch.choice_valid = false;
}

// The first clock at which `cmd` for `b` meets every constraint (docs/memory.md, "Timing
// equations"): the command bus, the bank's own state, and the other banks through the
// bank-group (_L) or other-group (_S) spacing.
int64_t DramModel::earliest(const Channel& ch, const Burst& b, Cmd cmd) const {
  const Bank& bank = ch.banks[size_t(bank_index(b.at))];
  const size_t g = size_t(b.at.bank_group);
  const int64_t burst = p_.burst_clocks();
  int64_t t = std::max(b.eligible, ch.last_cmd + 1);
  for (size_t h = 0; h < size_t(p_.bank_groups); ++h) {
    const bool same = h == g;
    switch (cmd) {
      case Cmd::Pre: break;
      case Cmd::Act: t = std::max(t, ch.last_act[h] + (same ? p_.tRRD_L : p_.tRRD_S)); break;
      case Cmd::Read:
        t = std::max({t, ch.last_read[h] + std::max(burst, same ? p_.tCCD_L : p_.tCCD_S),
                      ch.last_write[h] + p_.tCWL + burst + (same ? p_.tWTR_L : p_.tWTR_S)});
        break;
      case Cmd::Write:
        t = std::max({t, ch.last_write[h] + std::max(burst, same ? p_.tCCD_L : p_.tCCD_S),
                      ch.last_read[h] + p_.tCL + burst - p_.tCWL + kReadToWriteGap});
        break;
    }
  }
  switch (cmd) {
    case Cmd::Pre: return std::max(t, bank.pre_ok);
    case Cmd::Act: return std::max({t, bank.act_ok, ch.acts[28] + p_.tFAW, ch.acts[0] + p_.t32AW});
    case Cmd::Read: return std::max(t, bank.read_ok);
    case Cmd::Write: return std::max(t, bank.write_ok);
  }
  return t;
}

// FR-FCFS: the command that can issue first; at the same clock a column command (a row
// hit) before an activate or precharge, then the oldest burst. A precharge that would
// close a row some queued burst still wants waits. Each bank offers only the oldest
// burst of each command it has (dram.h, Bank: the others cannot win); the answer is
// kept until the channel changes.
DramModel::Choice DramModel::choose(const Channel& ch) const {
  if (ch.choice_valid) return ch.choice;
  Choice best;
  uint64_t best_seq = 0;
  bool best_column = false;
  const auto consider = [&](int k, size_t i, Cmd cmd) {
    const Burst& b = ch.banks[size_t(k)].queue[i];
    const int64_t at = earliest(ch, b, cmd);
    const bool column = cmd == Cmd::Read || cmd == Cmd::Write;
    const bool better = best.at < 0 || at < best.at ||
                        (at == best.at && (column != best_column ? column : b.seq < best_seq));
    if (better) best = {at, k, i, cmd}, best_seq = b.seq, best_column = column;
  };
  for (int k = 0; k < int(ch.banks.size()); ++k) {
    const Bank& bank = ch.banks[size_t(k)];
    if (bank.queue.empty()) continue;
    if (bank.hits[0] + bank.hits[1] == 0) {  // every burst wants another row (or the bank is closed)
      consider(k, 0, bank.open_row < 0 ? Cmd::Act : Cmd::Pre);
      continue;
    }
    // The oldest read hit and write hit, as far as there are any.
    bool read = bank.hits[0] == 0, write = bank.hits[1] == 0;
    for (size_t i = 0; i < bank.queue.size() && !(read && write); ++i) {
      const Burst& b = bank.queue[i];
      if (b.at.row != bank.open_row || (b.write ? write : read)) continue;
      (b.write ? write : read) = true;
      consider(k, i, b.write ? Cmd::Write : Cmd::Read);
    }
  }
  ch.choice = best;
  ch.choice_valid = true;
  return best;
}

void DramModel::note(const Channel& ch, int64_t at, DramCommand::Kind kind, const DramAddress& a) {
  if (log_) log_->push_back({at, kind, int(&ch - channels_.data()), a.bank_group, a.bank, a.row});
}

void DramModel::issue(Channel& ch, const Choice& c) {
  Bank& bank = ch.banks[size_t(c.bank)];
  Burst& b = bank.queue[c.index];
  ch.last_cmd = c.at;
  ch.choice_valid = false;
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
      ch.last_act[size_t(b.at.bank_group)] = c.at;
      std::rotate(ch.acts.begin(), ch.acts.begin() + 1, ch.acts.end());
      ch.acts.back() = c.at;
      b.activated = true;
      ++stats_.activates;
      return;
    case Cmd::Read:
    case Cmd::Write: {
      const Burst done = b;
      bank.queue.erase(bank.queue.begin() + std::ptrdiff_t(c.index));
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
  const size_t g = size_t(b.at.bank_group);
  const int64_t end = at + (b.write ? p_.tCWL : p_.tCL) + p_.burst_clocks();
  if (b.write) {
    ch.last_write[g] = at;
    bank.pre_ok = std::max(bank.pre_ok, end + p_.tWR);
  } else {
    ch.last_read[g] = at;
    bank.pre_ok = std::max(bank.pre_ok, at + p_.tRTP);
  }
  if (p_.page_policy == PagePolicy::Closed) {  // auto-precharge: no command bus slot
    bank.open_row = -1;
    bank.hits = {};
    bank.act_ok = std::max(bank.act_ok, bank.pre_ok + p_.tRP);
    ++stats_.precharges;
  }
  auto node = pending_.find(b.request);
  Pending& p = node->second;
  DramClientStats& s = stats_.clients[size_t(p.req.client)];
  (b.write ? s.bytes_written : s.bytes_read) += p_.burst_bytes();
  ++(b.write ? s.bursts_written : s.bursts_read);
  ++(b.precharged ? s.row_conflicts : b.activated ? s.row_misses : s.row_hits);
  s.data_bus_clocks += uint64_t(p_.burst_clocks());
  p.end = std::max(p.end, end);
  if (--p.bursts_left > 0) return;
  const uint64_t cycle = to_core(uint64_t(p.end));
  if (!p.req.write) ++s.requests_read, s.read_latency_cycles += cycle - p.arrival;
  done_.push_back({b.request, DramCompletion{cycle, p.req.tag, p.req.client}});
  pending_.erase(node);
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
  for (Bank& bank : ch.banks) bank.open_row = -1, bank.hits = {}, bank.act_ok = ref_at + p_.tRFC;
  ch.last_cmd = ref_at;
  ch.choice_valid = false;
  note(ch, ref_at, DramCommand::Refresh, DramAddress{});
  ch.next_refresh += p_.tREFI;
  ++stats_.refreshes;
  if (any_open) ++stats_.precharges;
}

uint64_t DramModel::next_event() const {
  uint64_t next = kNoEvent;
  for (const auto& d : done_) next = std::min(next, d.second.cycle);
  for (const Channel& ch : channels_) {
    const Choice c = choose(ch);
    // The first core cycle whose DRAM clock comes after c.at: advance_to() issues it.
    if (c.at >= 0) next = std::min(next, uint64_t(Wide(c.at) * p_.core_khz / p_.dram_khz) + 1);
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

std::vector<DramCompletion> DramModel::take_completions() {
  if (done_.empty()) return {};
  std::vector<std::pair<uint64_t, DramCompletion>> ready;
  auto later = std::stable_partition(done_.begin(), done_.end(),
                                     [&](const auto& d) { return d.second.cycle > advanced_; });
  ready.assign(later, done_.end());
  done_.erase(later, done_.end());
  std::sort(ready.begin(), ready.end(), [](const auto& a, const auto& b) {
    return a.second.cycle != b.second.cycle ? a.second.cycle < b.second.cycle : a.first < b.first;
  });
  std::vector<DramCompletion> out;
  for (const auto& r : ready) out.push_back(r.second);
  return out;
}

}  // namespace rastsim
