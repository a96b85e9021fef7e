// SPDX-License-Identifier: Apache-2.0
#include "rtlsim/tb_hiz.h"

#include <algorithm>
#include <vector>

namespace rastsim::rtlsim {

// The test reads issued so far arrive: the last at max(its cycle + 1, c_last), each one
// before at most a cycle before the next (one response a cycle), none before its request's
// next cycle nor before now.
void TbHiz::resolve_tests(uint64_t t) {
  if (unresolved_ == 0) return;
  const uint64_t first = rsp_[rsp_.size() - unresolved_].taken;
  uint64_t c = rsp_.back().taken + 1;
  if (mem_) c = std::max(c, mem_->wait_reads().value_or(0));
  report_.stall_cycles += c > first ? c - first : 0;
  uint64_t next = c + 1;
  for (size_t k = rsp_.size(); k-- > rsp_.size() - unresolved_;) {
    next = std::max({t, rsp_[k].taken + 1, std::min(next - 1, c)});
    rsp_[k].due = next;
  }
  unresolved_ = 0;
}

void TbHiz::drive(uint64_t t, RastPorts& ports) {
  const HizRequest q = ports.hiz_request();
  if (unresolved_ > 0 && !(q.valid && !q.write && !q.flush)) resolve_tests(t);  // the test's reads ended
  offered_ = !rsp_.empty() && rsp_.front().due != 0 && rsp_.front().due <= t;
  ports.drive_hiz(s_.hiz_base, offered_, offered_ ? rsp_.front().data : std::array<uint8_t, 64>{});
}

void TbHiz::serve(uint64_t t, RastPorts& ports, std::string& error) {
  if (offered_) rsp_.pop_front();
  offered_ = false;
  const HizRequest q = ports.hiz_request();
  if (!q.valid) return;
  const char* kind = q.write ? "write-back" : q.flush ? "flush read" : "test read";
  const std::vector<uint64_t>& want = q.write ? s_.hiz_writes : q.flush ? s_.hiz_flush_reads : s_.hiz_test_reads;
  size_t& n = q.write ? writes_ : q.flush ? flushes_ : tests_;
  if (n >= want.size() || want[n] != q.address)
    error = "cycle " + std::to_string(t) + ": Hi-Z " + kind + " " + std::to_string(n) + " at byte " +
            std::to_string(q.address) + ", the reference's " +
            (n < want.size() ? "at byte " + std::to_string(want[n]) : std::string("end before it"));
  ++n;
  const uint64_t bytes = s_.hiz_entry_bytes;
  if (q.write) {
    std::array<uint8_t, 64>& e = entries_[q.address];
    std::copy_n(q.data.begin(), size_t(bytes), e.begin());
    if (mem_) mem_->post_write(MemClient::Hiz, q.address, bytes, t);
    report_.bytes_written += bytes;
    ++report_.writes;
    return;
  }
  Response r;
  r.taken = t;
  if (const auto it = entries_.find(q.address); it != entries_.end()) r.data = it->second;
  report_.bytes_read += bytes;
  ++report_.reads;
  if (mem_) mem_->issue_read(MemClient::Hiz, q.address, bytes, t);
  if (q.flush) {  // the engine's only read: waited for now
    uint64_t c = t + 1;
    if (mem_) c = std::max(c, mem_->wait_reads().value_or(0));
    report_.stall_cycles += c - t;
    r.due = c;
  } else {
    ++unresolved_;
  }
  rsp_.push_back(r);
}

void TbHiz::finish(CosimResult& r, std::string& error) const {
  r.hiz_dram_bytes_read = report_.bytes_read;
  r.hiz_dram_bytes_written = report_.bytes_written;
  if (tests_ != s_.hiz_test_reads.size() || flushes_ != s_.hiz_flush_reads.size() || writes_ != s_.hiz_writes.size())
    error = "Hi-Z spilled entries: the RTL made " + std::to_string(tests_) + " test reads, " +
            std::to_string(flushes_) + " flush reads and " + std::to_string(writes_) + " write-backs, the reference " +
            std::to_string(s_.hiz_test_reads.size()) + ", " + std::to_string(s_.hiz_flush_reads.size()) + " and " +
            std::to_string(s_.hiz_writes.size());
  else if (report_.bytes_read != s_.hiz_bytes_read || report_.bytes_written != s_.hiz_bytes_written)
    error = "Hi-Z spilled entries: the RTL moved " + std::to_string(report_.bytes_read) + " bytes read and " +
            std::to_string(report_.bytes_written) + " written, the reference " + std::to_string(s_.hiz_bytes_read) +
            " and " + std::to_string(s_.hiz_bytes_written);
  if (mem_ && report_.reads + report_.writes > 0) add_hiz_memory_json(r.dram, report_);
}

}  // namespace rastsim::rtlsim
