// SPDX-License-Identifier: Apache-2.0
#include "rtlsim/tb_texture.h"

#include <algorithm>

namespace rastsim::rtlsim {

TbTexture::TbTexture(const TbSetup& s) : s_(s) {
  if (s.texture.cache.bytes > 0) cache_.emplace(s.texture.cache);
}

void TbTexture::issue(uint64_t t) {
  for (Pending& p : queue_) {
    if (p.issued) continue;
    const uint64_t start = std::max(p.taken + 1, last_due_ + 1);
    if (start > t) return;
    uint64_t stall = uint64_t(p.misses) * s_.timing.texture_miss_cycles;
    if (mem_) {
      mem_->begin(start);
      const uint64_t bytes = cache_ ? uint64_t(cache_->line_bytes()) : uint64_t(texel_bytes(s_.texture.format));
      for (int k = 0; k < p.misses; ++k) mem_->fill(p.fills[size_t(k)], bytes);
      stall = mem_->stall_cycles();
    }
    p.due = start + stall;
    p.issued = true;
    last_due_ = p.due;
  }
}

void TbTexture::drive(uint64_t t, RastPorts& ports) {
  issue(t);
  offered_ = !queue_.empty() && queue_.front().issued && queue_.front().due <= t;
  ports.drive_texture_response(offered_, offered_ ? queue_.front().texels : std::array<uint32_t, 4>{});
  ports.drive_texture_ready(true);
}

void TbTexture::serve(uint64_t t, RastPorts& ports, std::string& error) {
  if (offered_ && ports.texture_response_taken()) queue_.pop_front();
  const TexRequest q = ports.texture_request();
  if (!q.valid) return;
  const auto at = [&] { return "cycle " + std::to_string(t) + ": texel request"; };
  if (q.count != 1 && q.count != 4) error = at() + " of " + std::to_string(q.count) + " texels (1 or 4)";
  if (q.format != int(s_.texture.format)) error = at() + " in format " + std::to_string(q.format);
  Pending p;
  p.taken = t;
  for (int k = 0; k < std::min(q.count, 4); ++k) {
    const uint64_t a = q.addr[size_t(k)];
    const auto it = s_.texels.find(a);
    if (it == s_.texels.end()) error = at() + ": byte " + std::to_string(a) + " is no texel's address";
    else p.texels[size_t(k)] = it->second;
    ++fetches_;
    SetAssocCache::Victim victim;
    if (cache_ && cache_->access(a / uint64_t(cache_->line_bytes()), false, victim)) {
      ++hits_;
      continue;
    }
    ++misses_;
    p.fills[size_t(p.misses++)] = cache_ ? a / uint64_t(cache_->line_bytes()) * uint64_t(cache_->line_bytes()) : a;
  }
  queue_.push_back(p);
}

void TbTexture::finish(CosimResult& r) const {
  r.texel_fetches = fetches_;
  r.texture_cache_hits = hits_;
  r.texture_cache_misses = misses_;
  if (mem_ && mem_->report().reads > 0) add_texture_memory_json(r.dram, mem_->report());
}

}  // namespace rastsim::rtlsim
