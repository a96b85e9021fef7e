// SPDX-License-Identifier: Apache-2.0
// Fuzz harness (fuzz/harness.h): the recorded-signal reader of `rastsim monitor`
// (model/display/signal_reader.cpp). The input is a VCD file's text; it is read twice,
// as `rastsim monitor` does with the default config (panel timing, default DAC), sampling on
// the clock variable if any and with `--clock none`, each time feeding a Monitor.
// Bad input may end only in SignalFileError; an accepted file must deliver exactly the
// samples it reports.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "config/config.h"
#include "config/video_timing.h"
#include "display/dac.h"
#include "display/monitor.h"
#include "display/signal_reader.h"
#include "fuzz_common.h"
#include "harness.h"

namespace rastsim::fuzz {

void signal_one(std::string_view input) {
  static const Config cfg;
  static const VideoTiming timing = video_timing_from_config(cfg);
  static const Dac dac(dac_config_from_config(cfg));
  const std::string text(input);
  for (const char* clock : {"", "none"}) {
    expect_only<SignalFileError>("SignalFileError", [&] {
      std::istringstream in(text);
      Monitor mon(timing, dac.config());
      long long delivered = 0;
      const SignalReadInfo info = read_video_vcd(
          in, "fuzz.vcd", timing, dac, [&](const VideoSample& s) { ++delivered, mon.push(s); }, {clock});
      check(info.samples == delivered, "reported " + std::to_string(info.samples) + " samples, delivered " +
                                           std::to_string(delivered));
      check(info.sample_clock_hz > 0, "sample clock not positive");
      (void)mon.finish();
    });
  }
}

}  // namespace rastsim::fuzz
