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
  always_comb begin
    unique case (func_i)
      3'd0: pass_o = 1'b0;               // never
      3'd1: pass_o = z_i < stored_i;     // less
      3'd2: pass_o = z_i <= stored_i;    // lequal
      3'd3: pass_o = z_i == stored_i;    // equal
      3'd4: pass_o = z_i > stored_i;     // greater
      3'd5: pass_o = z_i >= stored_i;    // gequal
      3'd6: pass_o = z_i != stored_i;    // notequal
      default: pass_o = 1'b1;            // always
    endcase
  end
endmodule

`default_nettype wire
