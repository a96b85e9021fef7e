// SPDX-License-Identifier: Apache-2.0
// Primitive assembly: forms each triangle of a list, strip or fan from its vertices
// (ref/prim_assembly.h: assemble_triangle, which keeps a strip's winding).
//
// - A clip-space command's marker: its triangles come from the geometry front end
//   (sc/front_end.h), taken in order until the command's end, each one a transaction.
// - Cost: assembly.cycles_per_triangle per triangle; 1 cycle per state command.
#pragma once

#include <array>

#include "sc/command_fetch.h"

namespace rastsim::sc {

struct AssembledTriangle {
  std::array<SceneVertex, 3> v{};
  CommandPtr cmd;  // the primitives command it came from (for error locations)
};
using TriangleItem = Item<AssembledTriangle>;

class PrimAssembly : public Stage {
 public:
  static constexpr StageId kId = StageId::PrimAssembly;
  PrimAssembly(SimContext& ctx, const TimingParams& p, Link<CommandItem>& in, Link<ScreenItem>& screen_in,
               Link<TriangleItem>& out, sc_core::sc_module_name name = stage_name(kId).data())
      : Stage(name, ctx, kId), p_(p), in_(in), screen_in_(screen_in), out_(out) {}

 private:
  void body() override;
  void assemble(const ScreenTriangle& v, const CommandPtr& cmd);
  const TimingParams& p_;
  Link<CommandItem>& in_;
  Link<ScreenItem>& screen_in_;
  Link<TriangleItem>& out_;
};

}  // namespace rastsim::sc
