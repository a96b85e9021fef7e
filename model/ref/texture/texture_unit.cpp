// SPDX-License-Identifier: Apache-2.0
#include "ref/texture/texture_unit.h"

#include <algorithm>
#include <bit>

#include "ref/memory/surface_layout.h"

namespace rastsim {

namespace {
constexpr uint64_t kTextureAlign = 4096, kLevelAlign = 256;
constexpr int kTileTexels = 4;  // texture.layout = tiled: 4 x 4-texel tiles

uint64_t align_up(uint64_t v, uint64_t a) { return (v + a - 1) / a * a; }

// x bit k to bit 2k, y bit k to bit 2k + 1.
uint64_t morton_index(uint32_t x, uint32_t y) {
  uint64_t m = 0;
  for (int k = 0; k < 32; ++k)
    m |= (uint64_t((x >> k) & 1) << (2 * k)) | (uint64_t((y >> k) & 1) << (2 * k + 1));
  return m;
}

SurfaceLayout grid_layout(TexLayout layout, int w, int h, int bytes) {
  const int tile = layout == TexLayout::Tiled ? kTileTexels : 1;
  return SurfaceLayout(layout == TexLayout::Tiled ? FbLayout::Tiled : FbLayout::Linear, tile, tile, 0, w, h, 1, bytes);
}
}  // namespace

uint64_t texel_offset(TexLayout layout, int w, int h, int bytes, int i, int j) {
  if (layout == TexLayout::Morton) return morton_index(uint32_t(i), uint32_t(j)) * uint64_t(bytes);
  return grid_layout(layout, w, h, bytes).offset_of(i, j, 0);
}

uint64_t level_footprint(TexLayout layout, int w, int h, int bytes) {
  if (layout == TexLayout::Morton) {
    const uint64_t side = std::bit_ceil(uint64_t(std::max(w, h)));
    return side * side * uint64_t(bytes);
  }
  return grid_layout(layout, w, h, bytes).footprint_bytes();
}

const QuadDerivatives& TriangleQuads::derivatives(const SetupTriangle& tri, int px, int py, int frac_bits) {
  const int x0 = px & ~1, y0 = py & ~1;
  const uint64_t key = (uint64_t(uint32_t(y0)) << 32) | uint32_t(x0);
  const auto [it, added] = quads_.try_emplace(key);
  if (added) {
    const Fragment a = interpolate_plane(tri, x0, y0, frac_bits), b = interpolate_plane(tri, x0 + 1, y0, frac_bits),
                   c = interpolate_plane(tri, x0, y0 + 1, frac_bits);
    it->second = {int64_t(b.s) - a.s, int64_t(b.t) - a.t, int64_t(c.s) - a.s, int64_t(c.t) - a.t};
  }
  return it->second;
}

TextureUnit::TextureUnit(const TextureParams& p) : p_(p), next_base_(p.base) {
  if (p.cache.bytes > 0) cache_.emplace(p.cache);
}

const TextureUnit::Resident& TextureUnit::resident(const TextureState& ts) {
  const auto it = resident_.find(ts.image.get());
  if (it != resident_.end()) return it->second;
  Resident r;
  r.image = ts.image;
  r.levels = build_mip_chain(*ts.image, p_.format, true);
  const int bytes = texel_bytes(p_.format);
  uint64_t off = 0;
  for (const MipLevel& l : r.levels) {
    r.level_base.push_back(next_base_ + off);
    off = align_up(off + level_footprint(p_.layout, l.width, l.height, bytes), kLevelAlign);
  }
  next_base_ = align_up(next_base_ + off, kTextureAlign);
  return resident_.emplace(ts.image.get(), std::move(r)).first->second;
}

void TextureUnit::fetch(uint64_t address) {
  ++stats_.texel_fetches;
  if (!cache_) {
    ++stats_.cache_misses;
    stats_.dram_bytes += uint64_t(texel_bytes(p_.format));
    if (on_fill) on_fill(address, uint64_t(texel_bytes(p_.format)));
    return;
  }
  SetAssocCache::Victim victim;
  if (cache_->access(address / uint64_t(cache_->line_bytes()), false, victim)) {
    ++stats_.cache_hits;
  } else {
    ++stats_.cache_misses;
    const uint64_t line = uint64_t(cache_->line_bytes());
    stats_.dram_bytes += line;
    if (on_fill) on_fill(address / line * line, line);
  }
}

Rgba8 TextureUnit::sample_level(const Resident& r, int level, const Fragment& f, const TextureState& ts,
                                int frac_bits) {
  const MipLevel& l = r.levels[size_t(level)];
  const TexelQuad q =
      texel_quad(f.s, f.t, l.width, l.height, frac_bits, ts.filter != TexFilter::Nearest, ts.wrap_s, ts.wrap_t,
                 p_.weight_bits);
  std::array<Rgba8, 4> texels{};
  const int bytes = texel_bytes(p_.format);
  for (size_t k = 0; k < size_t(q.count); ++k) {
    fetch(r.level_base[size_t(level)] + texel_offset(p_.layout, l.width, l.height, bytes, q.i[k], q.j[k]));
    texels[k] = l.texel(q.i[k], q.j[k]);
  }
  return filter_texels(q, texels);
}

Fragment TextureUnit::shade(const Fragment& f, const QuadDerivatives& d, const TextureState& ts, int frac_bits) {
  const Resident& r = resident(ts);
  ++stats_.samples[size_t(ts.filter)];
  const int levels = ts.mipmap ? int(r.levels.size()) : 1;
  const MipLevel& base = r.levels[0];
  const int32_t lambda = levels > 1 ? texture_lod(d, base.width, base.height, frac_bits) : 0;
  const LevelChoice c = choose_levels(lambda, ts.lod_bias, levels, ts.filter);
  Rgba8 tex = sample_level(r, c.level0, f, ts, frac_bits);
  ++stats_.level_samples;
  if (c.level1 != c.level0) {
    tex = blend_levels(tex, sample_level(r, c.level1, f, ts, frac_bits), c.frac);
    ++stats_.level_samples;
  }
  const auto rgb = texenv_combine(ts.env, tex, {f.r, f.g, f.b});
  Fragment out = f;
  out.r = rgb[0];
  out.g = rgb[1];
  out.b = rgb[2];
  return out;
}

}  // namespace rastsim
