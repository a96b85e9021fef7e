// SPDX-License-Identifier: Apache-2.0
// FNV-1a, 64 bits (Fowler/Noll/Vo): the fingerprints of a resolved config (config_hash, of
// the sweep CSV and the stats' provenance) and of a scene file, and the keys of the on-disk
// caches (RTL models, area runs). Fingerprints and cache keys, not a security boundary.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

namespace rastsim {

constexpr uint64_t kFnv64OffsetBasis = 14695981039346656037ull;
constexpr uint64_t kFnv64Prime = 1099511628211ull;

// The hash of `bytes` continued from `h` (the offset basis for a fresh hash).
constexpr uint64_t fnv1a64(std::string_view bytes, uint64_t h = kFnv64OffsetBasis) {
  for (char c : bytes) h = (h ^ static_cast<uint8_t>(c)) * kFnv64Prime;
  return h;
}

// 16 lower-case hex digits.
inline std::string hex64(uint64_t h) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

// A cache key built from several strings: each added with a 0xff byte after it, so
// ("ab", "c") and ("a", "bc") differ. It starts from kCacheKeySeed, the offset basis with
// its last digit dropped: every existing RTL and area cache entry is named by a key
// started there, so another start would orphan them all.
struct Fnv64 {
  static constexpr uint64_t kCacheKeySeed = 1469598103934665603ull;
  uint64_t h = kCacheKeySeed;
  void add(std::string_view s) { h = fnv1a64("\xff", fnv1a64(s, h)); }
  std::string hex() const { return hex64(h); }
};

}  // namespace rastsim
