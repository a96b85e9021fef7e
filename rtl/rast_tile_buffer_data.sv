// SPDX-License-Identifier: Apache-2.0
// rast_tile_buffer_data: the arrays of the binned mode's tile buffer (rtl/rast_tile_buffer.sv):
// a colour array of Slots 32-bit words and a depth array of Slots DepthW-bit words, each
// word with a valid bit. Reads ports of combinational reads, Writes ports of byte-masked
// writes at the clock edge, a flash clear of each array's valid bits.
//
// - A read port gives the word and its valid bit at slot rd_slot_i of the surface
//   rd_dep_i (1: depth, zero-extended to 32 bits); the caller answers its fill value for a
//   word not valid and for a slot >= Slots (whose word and bit here are don't-cares).
// - A write port (wr_en_i, the caller's enable: a slot < Slots, a byte enabled) writes
//   the bytes wr_be_i of wr_data_i over the word, and sets its valid bit. A word not valid
//   holds its surface's fill value (col_fill_i, dep_fill_i): the bytes not enabled come
//   from that, as from a read of the word (the depth word the low DepthW bits).
// - clear_col_i / clear_dep_i clear the array's valid bits at the edge, after the
//   writes of the same cycle (a clear wins).
// Several writes to one slot in a cycle: the highest port's word (the caller never does).
//
// Area (docs/area.md, "Storage of the memory system"): two SRAM arrays, not logic.
// `(* blackbox *)` makes Yosys keep it as a cell without contents (rast_tile_buffer's
// walk, address and fill logic are synthesised around it), and `rastsim area` counts
// Slots x (32 + 1) and Slots x (DepthW + 1) bits by the storage rule of
// model/rtlsim/area_memory.h (rows tile_buffer.color, tile_buffer.depth); Verilator
// ignores the attribute and simulates the body. The ports are not priced: a macro would
// bank the arrays by sample (a ROP lane's samples are consecutive slots).
`default_nettype none

(* blackbox *)
module rast_tile_buffer_data #(
  parameter int Slots = 64,   // samples held (TileBufferSamples)
  parameter int DepthW = 24,  // raster.depth_bits
  parameter int Reads = 1,    // read ports
  parameter int Writes = 1,   // write ports
  // Derived (leave at the default): a slot's index.
  parameter int IdxW = $clog2(Slots)
) (
  input  wire logic                 clk_i,        // core clock
  input  wire logic [31:0]          col_fill_i,   // a colour word not valid holds this
  input  wire logic [DepthW-1:0]    dep_fill_i,   // a depth word not valid holds this
  input  wire logic                 clear_col_i,  // clear every colour valid bit
  input  wire logic                 clear_dep_i,  // clear every depth valid bit
  input  wire logic [Reads-1:0]     rd_dep_i,     // port r reads depth (else colour)
  input  wire logic [Reads*IdxW-1:0] rd_slot_i,   // port r's slot at [r*IdxW +: IdxW]
  output      logic [Reads*32-1:0]  rd_word_o,    // port r's word at [32 r +: 32]
  output      logic [Reads-1:0]     rd_valid_o,   // ... and its valid bit
  input  wire logic [Writes-1:0]    wr_en_i,      // port w writes
  input  wire logic [Writes-1:0]    wr_dep_i,     // ... depth (else colour)
  input  wire logic [Writes*IdxW-1:0] wr_slot_i,  // ... slot at [w*IdxW +: IdxW], < Slots
  input  wire logic [Writes*4-1:0]  wr_be_i,      // ... bytes written, [4 w +: 4]
  input  wire logic [Writes*32-1:0] wr_data_i     // ... word, [32 w +: 32]
);
  logic [31:0]       col_q [Slots];
  logic [DepthW-1:0] dep_q [Slots];
  logic [Slots-1:0]  col_v_q, dep_v_q;

  // A word as read: its value if valid, else the fill value.
  function automatic logic [31:0] col_word(input logic [IdxW-1:0] i);
    col_word = col_v_q[i] ? col_q[i] : col_fill_i;
  endfunction
  function automatic logic [31:0] dep_word(input logic [IdxW-1:0] i);
    logic [DepthW-1:0] d;
    d = dep_v_q[i] ? dep_q[i] : dep_fill_i;
    dep_word = 32'(d);
  endfunction
  function automatic logic [31:0] merge(input logic [31:0] old, input logic [31:0] d, input logic [3:0] be);
    for (int b = 0; b < 4; b++) merge[b*8 +: 8] = be[b] ? d[b*8 +: 8] : old[b*8 +: 8];
  endfunction

  for (genvar r = 0; r < Reads; r++) begin : g_rd
    logic [IdxW-1:0] s;
    assign s = rd_slot_i[r*IdxW +: IdxW];
    assign rd_word_o[r*32 +: 32] = rd_dep_i[r] ? 32'(dep_q[s]) : col_q[s];
    assign rd_valid_o[r] = rd_dep_i[r] ? dep_v_q[s] : col_v_q[s];
  end

  // Valid bits in one process (a packed vector an array): the writes set, a clear last.
  /* verilator lint_off WIDTHCONCAT */  // the flash clears: Slots-bit zeros
  always_ff @(posedge clk_i) begin
    for (int w = 0; w < Writes; w++)
      if (wr_en_i[w]) begin
        if (wr_dep_i[w]) dep_v_q[wr_slot_i[w*IdxW +: IdxW]] <= 1'b1;
        else col_v_q[wr_slot_i[w*IdxW +: IdxW]] <= 1'b1;
      end
    if (clear_col_i) col_v_q <= '0;
    if (clear_dep_i) dep_v_q <= '0;
  end
  /* verilator lint_on WIDTHCONCAT */

  // Data words: a process a write port (one delayed array write each).
  for (genvar w = 0; w < Writes; w++) begin : g_wr
    logic [IdxW-1:0] s;
    logic [3:0] be;
    logic [31:0] d;
    assign s = wr_slot_i[w*IdxW +: IdxW];
    assign be = wr_be_i[w*4 +: 4];
    assign d = wr_data_i[w*32 +: 32];
    always_ff @(posedge clk_i) begin
      if (wr_en_i[w] && wr_dep_i[w]) dep_q[s] <= DepthW'(merge(dep_word(s), d, be));
      if (wr_en_i[w] && !wr_dep_i[w]) col_q[s] <= merge(col_word(s), d, be);
    end
  end
endmodule

`default_nettype wire
