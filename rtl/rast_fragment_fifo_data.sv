// SPDX-License-Identifier: Apache-2.0
// rast_fragment_fifo_data: the ring of beats of rast_top's fragment FIFO (rtl/rast_top.sv,
// "Fragment FIFO"): Depth words of Width bits, Reads ports of combinational reads, Writes
// ports of whole-word writes at the clock edge. rast_top keeps the pointers, the count
// and the tile bookkeeping; this module is only the array.
//
// - A read port gives the word at rd_addr_i (an address >= Depth reads a don't-care).
// - A write port (wr_en_i, the caller's enable: an address < Depth) writes wr_data_i over
//   the word at wr_addr_i; a read of it sees the new word from the next cycle on.
// Several writes to one address in a cycle: the highest port's word (the caller never does).
//
// Area (docs/area.md, "Storage of the memory system"): one SRAM array, not logic. At the
// default config it is 1,216 beats x 374 bits (454,784 bits: ~18 M transistors as
// flip-flops, ~3 M as SRAM), and as flops it made rast_top's own logic the slowest Yosys
// run of all. `(* blackbox *)` makes Yosys keep it as a cell without contents, and
// `rastsim area` counts Depth x Width bits by the storage rule of
// model/rtlsim/area_memory.h (row fragment_fifo.beats); Verilator ignores the attribute
// and simulates the body. The ports are not priced (a macro's are in its periphery).
`default_nettype none

(* blackbox *)
module rast_fragment_fifo_data #(
  parameter int Depth = 4,   // words (rast_top's FragBeats)
  parameter int Width = 8,   // bits a word (rast_top's BeatW: $bits(beat_t))
  parameter int Reads = 1,   // read ports
  parameter int Writes = 1,  // write ports
  // Derived (leave at the default): an address.
  parameter int AddrW = Depth > 1 ? $clog2(Depth) : 1
) (
  input  wire logic                    clk_i,      // core clock
  input  wire logic [Reads*AddrW-1:0]  rd_addr_i,  // port r's address at [r*AddrW +: AddrW]
  output      logic [Reads*Width-1:0]  rd_data_o,  // port r's word at [r*Width +: Width]
  input  wire logic [Writes-1:0]       wr_en_i,    // port w writes
  input  wire logic [Writes*AddrW-1:0] wr_addr_i,  // ... at [w*AddrW +: AddrW], < Depth
  input  wire logic [Writes*Width-1:0] wr_data_i   // ... the word at [w*Width +: Width]
);
  logic [Width-1:0] mem_q [Depth];

  for (genvar r = 0; r < Reads; r++) begin : g_rd
    assign rd_data_o[r*Width +: Width] = mem_q[rd_addr_i[r*AddrW +: AddrW]];
  end

  // One process, the ports in order: the highest port's write lands last.
  always_ff @(posedge clk_i) begin
    for (int w = 0; w < Writes; w++)
      if (wr_en_i[w]) mem_q[wr_addr_i[w*AddrW +: AddrW]] <= wr_data_i[w*Width +: Width];
  end
endmodule

`default_nettype wire
