// SPDX-License-Identifier: Apache-2.0
// Command fetch: reads the scene as a command stream.
//
// - A state command (viewport, scissor, clear, clear depth) is one transaction.
// - A primitive command (list, strip, fan) is streamed one triangle at a time: each
//   transaction names the command and the triangle index, so assembly can start on the
//   first triangle while the rest of the vertices are still being fetched.
// - Cost: fetch.cycles_per_command for a command header, plus ceil(new vertices /
//   fetch.vertices_per_cycle) per triangle (3 new vertices in a list, 1 in a strip or
//   fan after its first triangle).
#pragma once

#include <cstddef>

#include "ref/scene.h"
#include "sc/stage.h"
#include "config/timing_params.h"

namespace rastsim::sc {

struct TriangleRef {
  const Command* cmd = nullptr;  // a primitives command
  size_t index = 0;              // triangle index within it
};
using CommandItem = Item<TriangleRef>;

class CommandFetch : public Stage {
 public:
  CommandFetch(sc_core::sc_module_name name, SimContext& ctx, const Scene& scene, const TimingParams& p,
               Link<CommandItem>& out)
      : Stage(name, ctx, 0), scene_(scene), p_(p), out_(out) {}

 private:
  void body() override;
  const Scene& scene_;
  const TimingParams& p_;
  Link<CommandItem>& out_;
};

}  // namespace rastsim::sc
