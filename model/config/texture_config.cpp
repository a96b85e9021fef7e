// SPDX-License-Identifier: Apache-2.0
#include "config/texture_config.h"

#include <bit>

namespace rastsim {

TextureParams texture_params_from_config(const Config& cfg) {
  TextureParams p;
  const std::string format = cfg.get_string("texture.format"), layout = cfg.get_string("texture.layout");
  p.format = format == "rgb565" ? TexelFormat::Rgb565 : format == "l8" ? TexelFormat::L8 : TexelFormat::Rgba8888;
  p.layout = layout == "tiled" ? TexLayout::Tiled : layout == "morton" ? TexLayout::Morton : TexLayout::Linear;
  p.base = uint64_t(cfg.get_int("texture.base"));
  p.weight_bits = int(cfg.get_int("texture.weight_bits"));
  p.cache = {uint64_t(cfg.get_int("texture.cache_bytes")), int(cfg.get_int("texture.ways")),
             int(cfg.get_int("texture.line_bytes"))};
  const uint64_t way_bytes = uint64_t(p.cache.ways) * uint64_t(p.cache.line_bytes);
  if (p.cache.bytes != 0 && (p.cache.bytes % way_bytes != 0 || !std::has_single_bit(p.cache.bytes / way_bytes)))
    throw ConfigError(cfg.origin("texture.cache_bytes") + ": texture.cache_bytes = " + std::to_string(p.cache.bytes) +
                      " is not texture.ways (" + std::to_string(p.cache.ways) + ") x texture.line_bytes (" +
                      std::to_string(p.cache.line_bytes) + ") x a power-of-two number of sets");
  return p;
}

}  // namespace rastsim
