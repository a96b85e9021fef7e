// SPDX-License-Identifier: Apache-2.0
#include "rtlsim/tb_texture.h"

#include <algorithm>

namespace rastsim::rtlsim {

TbTexture::TbTexture(const TbSetup& s) : s_(s) {
  if (s.params.tex_beat_bytes > 0) beats_ = s.params.tex_line_bytes / s.params.tex_beat_bytes;
}

void TbTexture::drive(uint64_t t, RastPorts& ports) {
  ready_ = !fill_;
  ports.drive_texture_fill_ready(ready_);
  offered_ = fill_ && t >= fill_->first + uint64_t(fill_->sent);
  std::array<uint8_t, 16> beat{};
  if (offered_) {
    const int n = s_.params.tex_beat_bytes;
    const uint64_t at = fill_->address + uint64_t(fill_->sent) * uint64_t(n);
    for (int i = 0; i < n; ++i) beat[size_t(i)] = s_.texture_memory.byte(at + uint64_t(i));
  }
  ports.drive_texture_beat(offered_, beat);
}

void TbTexture::serve(uint64_t t, RastPorts& ports, std::string& error) {
  const TexCacheEvents e = ports.texture_cache_events();
  hits_ += uint64_t(e.hits);
  misses_ += e.miss ? 1 : 0;
  if (offered_ && ports.texture_beat_taken() && ++fill_->sent == beats_) fill_.reset();
  const std::optional<uint64_t> a = ports.texture_fill_request();
  if (!ready_ || !a) return;
  if (fills_ >= s_.texture_fills.size() || s_.texture_fills[fills_] != *a)
    error = "cycle " + std::to_string(t) + ": texture line fill " + std::to_string(fills_) + " at byte " +
            std::to_string(*a) + ", the reference's " +
            (fills_ < s_.texture_fills.size() ? "at byte " + std::to_string(s_.texture_fills[fills_])
                                              : std::string("fills end before it"));
  ++fills_;
  const uint64_t beats = uint64_t(beats_);
  uint64_t first = t + 1 + uint64_t(std::max<int64_t>(0, int64_t(s_.timing.texture_miss_cycles) - 2 - int64_t(beats)));
  if (mem_)  // the line's last beat when it has arrived (not before the beats' own cycles)
    first = t + std::max(beats, mem_->fill_at(*a, uint64_t(s_.params.tex_line_bytes), t)) - (beats - 1);
  fill_ = Fill{*a, first, 0};
}

void TbTexture::finish(CosimResult& r, std::string& error) const {
  r.texel_fetches = hits_ + misses_;
  r.texture_cache_hits = hits_;
  r.texture_cache_misses = misses_;
  if (misses_ != s_.texture_fills.size())
    error = "texture cache: the RTL missed " + std::to_string(misses_) + " times, the reference " +
            std::to_string(s_.texture_fills.size());
  if (mem_ && mem_->report().reads > 0) add_texture_memory_json(r.dram, mem_->report());
}

}  // namespace rastsim::rtlsim
