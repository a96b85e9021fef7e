// SPDX-License-Identifier: Apache-2.0
// Recorded video signal -> virtual monitor: reads a VCD (or an FST, through gtkwave's
// fst2vcd) of the scan-out's output and replays it, one VideoSample a pixel clock, into
// a sink (usually Monitor::push).
//
// Variables are found by name (the last component, case-insensitive, a trailing `_o`
// dropped), in the shallowest scope that has them:
//   hsync | hs,  vsync | vs,  blank (or de / data_enable: BLANK = !DE)
//   code_r | dac_r, code_g | dac_g, code_b | dac_b          (vectors: DAC input codes)
//   level_r, level_g, level_b                                (reals: volts into the load)
//   clk | clk_i | pclk | pixel_clk | clk_pixel               (optional, 1 bit)
// That covers `rastsim scanout --signal` (hsync, vsync, blank, code_*, level_*) and a
// Verilator trace of rtl/scanout_top.sv or rtl/scanout_cosim_top.sv (hsync_o, vsync_o,
// blank_o, dac_*_o, clk_i). Levels come from level_* when present, otherwise from the
// codes through the DAC given (0 V while BLANK is high).
//
// Sampling, one sample a pixel clock:
// - With a clock variable (and `clock` not "none"): at every rising edge after the first,
//   the values held just before it (what a register clocked by the pixel clock captures:
//   the output launched by the previous edge); the last cycle too when the file runs on
//   for at least half a period after the last edge.
// - Without: at the middle of each pixel clock period of the expected timing, from the
//   first timestamp to the last (period = 1 / pixel clock in $timescale units), so the
//   rounding of our writer's timestamps (1 ps) never moves a sample to another pixel.
//
// Values: scalars 0/1/x/z, vectors b..., reals r...; x or z is read as 0 and reported
// (SignalReadInfo::problems). Malformed files throw SignalFileError "file:line: what".
#pragma once

#include <istream>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "display/dac.h"
#include "display/scanout.h"
#include "config/video_timing.h"

namespace rastsim {

// "file:line: what is wrong" (line 0 when the file as a whole is wrong: "file: what").
class SignalFileError : public std::runtime_error {
 public:
  SignalFileError(const std::string& file, long long line, const std::string& what);
  const std::string& file() const { return file_; }
  long long line() const { return line_; }

 private:
  std::string file_;
  long long line_;
};

struct SignalReaderOptions {
  // Clock variable to sample on: "" = the first one named like a pixel clock (above), if
  // any; "none" = ignore clocks, sample at the expected pixel clock; otherwise its name.
  std::string clock;
};

struct SignalReadInfo {
  std::string timescale;           // as written, e.g. "1ps"
  double timescale_s = 0;          // one time unit in seconds
  std::string clock;               // the variable sampled on; "" = the expected pixel clock
  double sample_clock_hz = 0;      // the expected pixel clock, or the clock variable's mean rate
  long long samples = 0;           // VideoSamples delivered
  std::string levels_from;         // "level_r/g/b" or "code_r/g/b through the DAC"
  std::map<std::string, std::string> variables;  // role (hsync, ..., clock) -> full name found
  // Faults in the recorded values (x/z sampled, codes wider than the DAC): the caller
  // reports them like monitor errors.
  std::vector<std::string> problems;
  // Observations that are not faults (a clock variable at another rate than expected).
  std::vector<std::string> notes;
};

// Reads `path`: .fst through `fst2vcd` (a temporary VCD, removed afterwards; a missing
// fst2vcd is a SignalFileError naming gtkwave), anything else as VCD.
SignalReadInfo read_video_signal(const std::string& path, const VideoTiming& expected, const Dac& dac,
                                 const SampleSink& sink, const SignalReaderOptions& opts = {});
// Reads a VCD from a stream; `name` is the file name used in messages.
SignalReadInfo read_video_vcd(std::istream& in, const std::string& name, const VideoTiming& expected,
                              const Dac& dac, const SampleSink& sink, const SignalReaderOptions& opts = {});

}  // namespace rastsim
