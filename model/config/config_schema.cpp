// SPDX-License-Identifier: Apache-2.0
// The configuration schema: every key rastsim reads, declared once.
// The keys of display and raster setup are here; each further group of keys is in its
// own config_schema_*.cpp (config_schema.h).
#include <algorithm>
#include <sstream>

#include "config/config.h"
#include "config/config_schema.h"
#include "ref/fixed_point.h"
#include "ref/framebuffer.h"

namespace rastsim {

bool is_power_of_two(const ParamValue& v) {
  const int64_t n = std::get<int64_t>(v);
  return n > 0 && (n & (n - 1)) == 0;
}

bool is_page_multiple(const ParamValue& v) { return std::get<int64_t>(v) % 4096 == 0; }

namespace {

std::vector<ParamDef> make_schema() {
  using T = ParamType;
  std::vector<ParamDef> s;
  auto add = [&](ParamDef d) { s.push_back(std::move(d)); };
  // ---- display: the framebuffer and the viewport ----
  add({"display.width", T::Int, int64_t{128}, "px", 1, kMaxImageExtent, {},
       "Framebuffer and viewport width in pixels"});
  add({"display.height", T::Int, int64_t{128}, "px", 1, kMaxImageExtent, {},
       "Framebuffer and viewport height in pixels"});
  // ---- raster: setup and traversal ----
  add({"raster.coord_format", T::String, std::string("s7.16"), "", 1, 0, {},
       "Snapped vertex coordinate format s<I>.<F>, relative to the viewport centre",
       is_fixed_format, "of form s<I>.<F> with I >= 0, F >= 1, I + F <= 31"});
  add({"raster.tile_size", T::Int, int64_t{16}, "px", 2, 128, {},
       "Square tile edge for the coarse tile walk", is_power_of_two, "a power of two"});
  add({"raster.fill_rule", T::Enum, std::string("top_left"), "", 1, 0,
       {"top_left", "bottom_right", "inclusive", "exclusive"},
       "Ownership of samples exactly on an edge (top_left: Direct3D 11; inclusive/exclusive are not watertight)"});
  add({"raster.cull", T::Enum, std::string("none"), "", 1, 0, {"none", "back", "front"},
       "Which facing to discard after setup"});
  add({"raster.front_face", T::Enum, std::string("ccw"), "", 1, 0, {"ccw", "cw"},
       "Winding of a front face as seen on screen (ccw: OpenGL/OBJ, cw: Direct3D)"});
  add({"raster.depth_func", T::Enum, std::string("always"), "", 1, 0,
       {"never", "less", "lequal", "equal", "greater", "gequal", "notequal", "always"},
       "Depth test; a fragment passes when func(fragment_z, stored_z) holds"});
  add({"raster.depth_bits", T::Int, int64_t{24}, "bits", 8, 32, {},
       "Depth buffer width; z in [0,1] is quantised to unorm of this width"});
  add({"raster.depth_write", T::Bool, true, "", 1, 0, {},
       "Write the depth of passing fragments"});
  add({"raster.out_of_range", T::Enum, std::string("error"), "", 1, 0, {"error", "cull"},
       "A vertex outside the coordinate format's range: stop with an error, or cull its triangle and count it"});
  add_traversal_params(s);
  add_aa_params(s);
  // ---- scene: how OBJ meshes are placed on screen (not architecture) ----
  add_scene_params(s);
  add_timing_params(s);
  add_scanout_params(s);
  add_2d_params(s);
  add_interp_params(s);
  add_clip_params(s);
  add_dram_params(s);
  add_memory_params(s);
  add_texture_params(s);
  add_binning_params(s);
  // ---- depth: culling ahead of the ROP (docs/depth.md) ----
  add({"depth.early", T::Bool, false, "", 1, 0, {},
       "Depth test before colour/texture interpolation where the state allows it (docs/depth.md; "
       "the same image; render only: simulate and estimate ignore it for now)"});
  add({"depth.hiz", T::Enum, std::string("off"), "", 1, 0, {"off", "max", "minmax"},
       "Hierarchical Z (docs/depth-culling.md): a per-block depth bound coarse raster tests tiles against; "
       "max culls under less/lequal, minmax also under greater/gequal and accepts tiles without the depth read "
       "(the same image; render and simulate)"});
  add({"depth.hiz_block", T::Int, int64_t{8}, "px", 4, 16, {},
       "Square Hi-Z block edge (4, 8 or 16)", is_power_of_two, "a power of two"});
  add({"depth.hiz_bytes", T::Int, int64_t{16384}, "bytes", 0, int64_t{1} << 30, {},
       "On-chip size of the Hi-Z bound table; blocks past it are read and written through memory "
       "(memory.clients.hiz)"});
  add({"depth.hiz_base", T::Int, int64_t{3} << 30, "bytes", 0, double(int64_t{1} << 40), {},
       "Byte address of the spilled Hi-Z table's first entry (block depth.hiz_bytes / entry bytes, "
       "row-major; docs/depth-culling.md)", is_page_multiple, "a multiple of 4096"});
  add({"depth.hiz_sync", T::Enum, std::string("interlock"), "", 1, 0, {"interlock", "lagged"},
       "How the timed levels (simulate, cosim) keep the Hi-Z table in step with the ROP: interlock tests a tile "
       "only once no tile in flight touches its blocks (the reference's decisions); lagged never waits, culls "
       "against the table as the ROP has written it and accepts only on idle blocks (docs/depth-culling.md; "
       "render and estimate are zero-lag either way)"});
  return s;
}

}  // namespace

bool is_fixed_format(const ParamValue& v) {
  try {
    FixedFormat::parse(std::get<std::string>(v));
    return true;
  } catch (const std::invalid_argument&) {
    return false;
  }
}

const std::vector<ParamDef>& config_schema() {
  static const std::vector<ParamDef> schema = make_schema();
  return schema;
}

const ParamDef* find_param(const std::string& key) {
  for (const auto& d : config_schema())
    if (d.key == key) return &d;
  return nullptr;
}

std::string ParamDef::allowed() const {
  std::ostringstream os;
  switch (type) {
    case ParamType::Int:
      os << "an integer in [" << int64_t(min) << ", " << int64_t(max) << "]";
      break;
    case ParamType::Float:
      os << "a number in [" << min << ", " << max << "]";
      break;
    case ParamType::Bool: os << "true or false"; break;
    case ParamType::String: os << "a string"; break;
    case ParamType::Enum: {
      os << "one of ";
      for (size_t i = 0; i < choices.size(); ++i) os << (i ? ", " : "") << choices[i];
      break;
    }
  }
  if (!rule.empty()) os << (type == ParamType::String ? " " : ", ") << rule;
  return os.str();
}

const std::vector<const ParamDef*>& schema_by_section() {
  static const std::vector<const ParamDef*> ordered = [] {
    std::vector<std::string> sections;  // in the order of their first key
    for (const auto& d : config_schema()) {
      const std::string sec = d.key.substr(0, d.key.find('.'));
      if (std::find(sections.begin(), sections.end(), sec) == sections.end()) sections.push_back(sec);
    }
    std::vector<const ParamDef*> keys;
    for (const auto& sec : sections)
      for (const auto& d : config_schema())
        if (d.key.substr(0, d.key.find('.')) == sec) keys.push_back(&d);
    return keys;
  }();
  return ordered;
}

std::string config_doc() {
  std::ostringstream os;
  os << "# rastsim configuration keys (TOML: [section] key = value; CLI: --set section.key=value)\n";
  std::string section;
  for (const ParamDef* d : schema_by_section()) {
    const std::string sec = d->key.substr(0, d->key.find('.'));
    if (sec != section) {
      os << "\n[" << sec << "]\n";
      section = sec;
    }
    os << "  " << d->key << " = " << to_string(d->default_value);
    if (!d->unit.empty()) os << "  (" << d->unit << ")";
    os << "\n      " << d->description << "\n      allowed: " << d->allowed();
    os << "\n";
  }
  return os.str();
}

}  // namespace rastsim
