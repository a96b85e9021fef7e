// SPDX-License-Identifier: Apache-2.0
// rast_rop_cache_data: the data array of the ROP's cache (rtl/rast_rop_cache.sv), a
// single-port SRAM of Entries lines of LineBytes bytes with a byte write mask and a
// registered read: a read at a cycle's edge shows its line from the next cycle on, and
// rdata_o holds it until the next read. One access a cycle, read or write.
//
// Area (docs/area.md, "Storage of the memory system"): an SRAM macro, not logic.
// `(* blackbox *)` makes Yosys keep it as a cell without contents, and `rastsim area`
// counts its bits by the storage rule of model/rtlsim/area_memory.h; Verilator ignores the
// attribute and simulates the body.
`default_nettype none

(* blackbox *)
module rast_rop_cache_data #(
  parameter int Entries = 8,    // lines (sets x ways)
  parameter int LineBytes = 16, // bytes a line
  // Derived (leave at the default): a line's index.
  parameter int EntW = Entries > 1 ? $clog2(Entries) : 1
) (
  input  wire logic                   clk_i,    // core clock
  input  wire logic                   en_i,     // an access this cycle
  input  wire logic                   we_i,     // ... a write (else a read)
  input  wire logic [EntW-1:0]        addr_i,   // line index
  input  wire logic [LineBytes-1:0]   wmask_i,  // bytes written (byte i at [8 i +: 8])
  input  wire logic [8*LineBytes-1:0] wdata_i,  // line written (under wmask_i)
  output      logic [8*LineBytes-1:0] rdata_o   // the last line read
);
  logic [8*LineBytes-1:0] mem_q [Entries];

  always_ff @(posedge clk_i) begin
    if (en_i && we_i) begin
      for (int b = 0; b < LineBytes; b++)
        if (wmask_i[b]) mem_q[addr_i][8*b +: 8] <= wdata_i[8*b +: 8];
    end
    if (en_i && !we_i) rdata_o <= mem_q[addr_i];
  end
endmodule

`default_nettype wire
