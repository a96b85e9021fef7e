// SPDX-License-Identifier: Apache-2.0
// ROP: depth test against the depth buffer, then colour (and depth) write.
#pragma once

#include "ref/framebuffer.h"
#include "ref/interpolate.h"
#include "ref/raster_state.h"

namespace rastsim {

// True when func(fragment_z, stored_z) passes.
bool depth_test(DepthFunc func, uint32_t fragment_z, uint32_t stored_z);

// Tests and writes one fragment; returns true when it was written (any sample). With a
// multisampled framebuffer the fragment's depth is tested against, and its colour and
// depth written to, each sample of f.mask separately; `samples_passed`, if given, counts
// the samples written.
bool rop_write(Framebuffer& fb, const Fragment& f, DepthFunc func, bool depth_write,
               uint64_t* samples_passed = nullptr);

}  // namespace rastsim
