// SPDX-License-Identifier: Apache-2.0
// The video DAC (a RAMDAC): framebuffer byte -> palette RAM -> N-bit code -> level.
//
// Levels (volts into the load): an ideal DAC of N bits drives
//   V(code) = code * LSB,  LSB = full_scale / (2^N - 1)
// into a doubly terminated 75 ohm load (75 ohm source termination || 75 ohm monitor
// input = 37.5 ohm), so 0.700 V full scale is a full-scale current of 18.67 mA. Blanking
// and code 0 are 0 V (no pedestal). A real DAC adds INL(code) LSB of nonlinearity:
//   V(code) = (code + INL(code)) * LSB,  INL(0) = INL(2^N - 1) = 0  (endpoint fit)
//   DNL(code) = INL(code) - INL(code - 1)
// The seeded mismatch model draws INL as a bounded walk: |INL| <= dac.inl_lsb,
// |DNL| <= dac.dnl_lsb, pulled toward a bow (the shape a resistor-string or current-
// source gradient gives) so the error reaches its bound. Each channel has its own curve.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "config/dac_config.h"

namespace rastsim {

class Dac {
 public:
  explicit Dac(const DacConfig& c);
  const DacConfig& config() const { return cfg_; }
  int max_code() const { return (1 << cfg_.bits) - 1; }
  double lsb_volts() const { return cfg_.full_scale_volts / max_code(); }

  // Palette RAM: framebuffer byte -> code (one table shared by R, G and B).
  uint16_t code(uint8_t v) const { return lut_[v]; }
  const std::array<uint16_t, 256>& lut() const { return lut_; }
  // The framebuffer byte whose code is nearest `code` (first on ties): what a decoder
  // that knows the palette recovers.
  uint8_t inverse(uint16_t code) const { return inverse_[code]; }

  // Output level of `channel` (0 R, 1 G, 2 B) for `code`, in volts; blank is 0 V.
  double volts(int channel, uint16_t code) const { return levels_[channel][code]; }
  // INL of `channel` at `code`, in LSB (endpoint fit), as the model drew it.
  double inl(int channel, uint16_t code) const { return inl_[channel][code]; }

 private:
  DacConfig cfg_;
  std::array<uint16_t, 256> lut_{};
  std::vector<uint8_t> inverse_;
  std::array<std::vector<double>, 3> inl_, levels_;
};

// The ideal receiver's ADC: a level back to the nearest code (clamped to the range).
uint16_t level_to_code(double volts, int bits, double full_scale_volts);

}  // namespace rastsim
