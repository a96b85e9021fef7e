// SPDX-License-Identifier: Apache-2.0
// The values on the verilated models' ports (rtl/rast_top.sv, rtl/rast_engine2d.sv) in one
// cycle, as plain structs: what RastPorts (testbench.h) reads and the port adapters
// (cosim_driver.h) fill. No behaviour here.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace rastsim::rtlsim {

// ---- The RTL's ports (rtl/rast_top.sv, rtl/rast_engine2d.sv) as plain values ----

// rast_top's fragment port this cycle.
struct FragmentBeat {
  bool valid = false;   // frag_valid_o
  bool marker = false;  // frag_marker_o: the beat is a marker
  bool last = false;    // frag_last_o: a tile's last beat
};
// rast_top's texture cache this cycle (tex_hits_o, tex_miss_o).
struct TexCacheEvents {
  int hits = 0;       // texels that hit
  bool miss = false;  // a miss (a line fill follows)
};
// rast_top's stage observation ports (bit s: 0 setup, 1 coarse raster, 2 fine raster,
// 3 interpolation, 4 ROP).
struct RtlStageBits {
  uint32_t has = 0;      // dbg_has_o: stage s holds a transaction
  uint32_t done = 0;     // dbg_done_o: stage s finishes its transaction this cycle
  uint32_t blocked = 0;  // dbg_blocked_o: stage s offers an output that is not taken
  bool rop_start = false;  // dbg_rop_start_o: the ROP starts a batch or command
  bool tex_busy = false;     // dbg_tex_busy_o: the texture stage holds textured work
  bool tex_blocked = false;  // dbg_tex_blocked_o: its output refused, or its input held for a credit
  int hiz_culled = 0;         // dbg_hiz_culled_o: tiles coarse raster culled (Hi-Z)
  bool hiz_accepted = false;  // dbg_hiz_accepted_o: the tile it sent was accepted
};
// rast_top's hiz_mem_req_* (a flush's read, a write-back and its entry) and dbg_hiz_error_o.
struct HizRequest {
  bool valid = false, write = false, flush = false, error = false;
  uint64_t address = 0;
  std::array<uint8_t, 64> data{};
};
// One lane of a ROP memory request (rast_top's rd_* / wr_*): a byte address and a burst
// length in 32-bit words.
struct RopLane {
  uint32_t addr = 0;
  uint32_t len = 0;
};
// Binned mode: a beat the tile buffer offers on rast_top's tl_* port (rtl/rast_tile_buffer.sv).
struct TileBeat {
  bool valid = false, write = false;  // tl_valid_o, tl_write_o
  uint32_t addr = 0;                  // tl_addr_o: the first word's byte address
  int count = 0;                      // tl_count_o: words
  std::vector<uint32_t> words;        // tl_wdata_o: the words of the store beat taken in the cycle before
};

// The 2D engine's memory addresses this cycle, sign-extended pixel indices.
struct Engine2dAccess {
  int x = 0, y = 0;    // mem_x_o, mem_y_o: lane 0's destination (lane k at x + k)
  int sx = 0, sy = 0;  // mem_sx_o, mem_sy_o: the blit source
};
// The 2D engine's read request this cycle (rtl/rast_engine2d.sv, "Memory port").
struct Engine2dRead {
  bool valid = false;  // rd_valid_o
  uint32_t lanes = 0;  // rd_lanes_o: bit k reads D of lane k
  bool source = false; // rd_src_o: reads S at (sx, sy)
};
// The 2D engine's write request this cycle (its data: engine_write_rgb).
struct Engine2dWrite {
  bool valid = false;         // wr_valid_o
  bool last = false;          // wr_last_o: the operation's last write
  uint32_t byte_enables = 0;  // wr_be_o: bits 3k .. 3k+2 lane k's {r, g, b} bytes (lanes_max lanes)
};

}  // namespace rastsim::rtlsim
