// SPDX-License-Identifier: Apache-2.0
// ROP: depth test against the depth buffer, then colour (and depth) write.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <utility>

#include "ref/framebuffer.h"
#include "ref/interpolate.h"
#include "ref/memory/rop_memory.h"
#include "ref/raster_state.h"

namespace rastsim {

// True when the depth function looks at the stored depth: every one but always and never,
// so only these read the depth surface (RopMemory::depth_read).
inline bool depth_test_reads(DepthFunc func) { return func != DepthFunc::Always && func != DepthFunc::Never; }

// True when func(fragment_z, stored_z) passes.
inline bool depth_test(DepthFunc func, uint32_t z, uint32_t stored) {
  switch (func) {
    case DepthFunc::Never: return false;
    case DepthFunc::Less: return z < stored;
    case DepthFunc::LEqual: return z <= stored;
    case DepthFunc::Equal: return z == stored;
    case DepthFunc::Greater: return z > stored;
    case DepthFunc::GEqual: return z >= stored;
    case DepthFunc::NotEqual: return z != stored;
    case DepthFunc::Always: return true;
  }
  return false;
}

// Tests and writes one fragment; returns true when it was written (any sample). With a
// multisampled framebuffer the fragment's depth is tested against, and its colour and
// depth written to, each sample of f.mask separately; `samples_passed`, if given, counts
// the samples written. `mem`, if given, sees each sample's accesses in order: the depth
// read (depth_test_reads), then on a pass the depth write (depth_write) and the colour
// write. Inline: it runs once a fragment (a call was a fifth of a render of small
// triangles).
inline bool rop_write(Framebuffer& fb, const Fragment& f, DepthFunc func, bool depth_write,
                      uint64_t* samples_passed = nullptr, RopMemory* mem = nullptr) {
  uint32_t n = 0;
  const int samples = fb.samples;
  const uint32_t mask = samples == 1 ? 1u : f.mask;
  for (int s = 0; s < samples; ++s) {
    if (!((mask >> s) & 1)) continue;
    if (mem && depth_test_reads(func)) mem->depth_read(f.x, f.y, s);
    if (!depth_test(func, f.z, std::as_const(fb).depth_at(f.x, f.y, s))) continue;
    if (depth_write) {
      fb.set_depth(f.x, f.y, s, f.z);
      if (mem) mem->depth_write(f.x, f.y, s);
    }
    const uint8_t rgba[4] = {f.r, f.g, f.b, 255};
    std::memcpy(fb.sample(f.x, f.y, s), rgba, 4);
    if (mem) mem->color_write(f.x, f.y, s);
    ++n;
  }
  if (samples_passed) *samples_passed += n;
  return n > 0;
}

// The early depth test (depth.early, docs/depth.md): true when fragment f fails `func`
// at every sample of its mask against the stored depth, so that rop_write would write
// none of it and it can be dropped before its colour and texture work. `mem`, if given,
// sees the depth reads of a fragment it culls (one a covered sample, in sample order, as
// rop_write's); a fragment it keeps is read at the ROP, so the memory system sees the
// same access stream with the early test as without.
inline bool early_depth_cull(const Framebuffer& fb, const Fragment& f, DepthFunc func, RopMemory* mem = nullptr) {
  if (func == DepthFunc::Always) return false;  // passes everywhere: nothing to cull
  const uint32_t mask = fb.samples == 1 ? 1u : f.mask;
  for (int s = 0; s < fb.samples; ++s)
    if (((mask >> s) & 1) && depth_test(func, f.z, fb.depth_at(f.x, f.y, s))) return false;
  if (mem && depth_test_reads(func))
    for (int s = 0; s < fb.samples; ++s)
      if ((mask >> s) & 1) mem->depth_read(f.x, f.y, s);
  return true;
}

namespace rop_detail {

// rop_write_run, with the depth function's test left out when it is `always` (kAlways).
template <bool kAlways, class FragAt>
inline uint32_t write_run(Framebuffer& fb, int y, int x0, int x1, FragAt& frag, DepthFunc func, bool depth_write,
                          RopMemory* mem) {
  uint32_t n = 0;
  for (int xa = x0; xa < x1;) {
    const int xb = std::min(x1, fb.tile_end_x(xa));
    // Depth read from the stored tile, or the clear value where none is; the tiles are
    // allocated on the first write, as set_depth() and sample() would. `always` does not
    // look at the stored depth: not reading it saves a cache miss a fragment.
    const uint32_t* zr = std::as_const(fb).stored_depth_run(xa, y);
    const uint32_t zclear = fb.cleared_depth();
    uint32_t* zw = nullptr;
    uint8_t* cw = nullptr;
    for (int x = xa; x < xb; ++x) {
      const Fragment f = frag(x);
      const int i = x - xa;
      if constexpr (!kAlways) {
        if (mem && depth_test_reads(func)) mem->depth_read(x, y, 0);
        if (!depth_test(func, f.z, zr ? zr[i] : zclear)) continue;
      }
      if (depth_write) {
        if (!zw) zr = zw = fb.depth_run(xa, y);
        zw[i] = f.z;
        if (mem) mem->depth_write(x, y, 0);
      }
      if (!cw) cw = fb.color_run(xa, y);
      const uint8_t rgba[4] = {f.r, f.g, f.b, 255};
      std::memcpy(cw + size_t(i) * 4, rgba, 4);
      if (mem) mem->color_write(x, y, 0);
      ++n;
    }
    xa = xb;
  }
  return n;
}

}  // namespace rop_detail

// rop_write of the fragments frag(x0), frag(x0 + 1), ..., frag(x1 - 1) of row y, in that
// order, on a one-sample framebuffer: the same tests, writes and tile allocations as
// rop_write on each in turn (tb/test_run_paths.cpp), with the tile lookups done once per
// storage tile the run crosses rather than once a pixel (the pipeline's runs,
// pipeline.cpp). frag(x) returns the Fragment of pixel (x, y); it is called for every
// pixel, in order, whatever the test decides. `mem`, if given, sees the same accesses
// as from rop_write. Returns the fragments written (= samples written).
template <class FragAt>
inline uint32_t rop_write_run(Framebuffer& fb, int y, int x0, int x1, FragAt&& frag, DepthFunc func,
                              bool depth_write, RopMemory* mem = nullptr) {
  if (func == DepthFunc::Always) return rop_detail::write_run<true>(fb, y, x0, x1, frag, func, depth_write, mem);
  return rop_detail::write_run<false>(fb, y, x0, x1, frag, func, depth_write, mem);
}

}  // namespace rastsim
