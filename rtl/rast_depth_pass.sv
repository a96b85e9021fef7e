// SPDX-License-Identifier: Apache-2.0
// rast_depth_pass: the depth test of model/ref/rop.h depth_test, one comparison: pass_o
// when depth z passes func against the stored depth (func: raster.depth_func as ref
// DepthFunc, 0 never .. 7 always). The one copy of the table: the early test (rast_early_z,
// docs/depth-culling.md "Early Z in the RTL") and the ROP's test of each response word
// (rast_rop) instantiate it.
`default_nettype none

module rast_depth_pass #(
  parameter int DepthW = 24  // raster.depth_bits
) (
  input  wire logic [2:0]        func_i,    // ref DepthFunc
  input  wire logic [DepthW-1:0] z_i,       // the fragment's depth, unorm
  input  wire logic [DepthW-1:0] stored_i,  // the stored depth, unorm
  output      logic              pass_o
);
  // Two comparisons and the result under each function, picked by func_i: a mux tree.
  // (A case over func_i with a comparison an arm synthesised to 149 generic gates at
  // DepthW 24, this to 126: Yosys 0.23, docs/area.md's flow, the module alone; the ROP
  // has PixelsPerCycle x MaxSamples of these, and its inlined function was the cheaper
  // by 18 gates a word.)
  logic       lt, eq;   // z < stored, z == stored
  logic [7:0] by_func;  // pass under ref DepthFunc f at [f]
  assign lt = z_i < stored_i;
  assign eq = z_i == stored_i;
  assign by_func[0] = 1'b0;        // never
  assign by_func[1] = lt;          // less
  assign by_func[2] = lt || eq;    // lequal
  assign by_func[3] = eq;          // equal
  assign by_func[4] = !lt && !eq;  // greater
  assign by_func[5] = !lt;         // gequal
  assign by_func[6] = !eq;         // notequal
  assign by_func[7] = 1'b1;        // always
  assign pass_o = by_func[func_i];
endmodule

`default_nettype wire
