// SPDX-License-Identifier: Apache-2.0
// RasterState from a validated config: the architecture part of the state every raster
// stage reads (model/ref/raster_state.h).
#include "config/raster_state_config.h"

#include "config/texture_config.h"
#include "ref/traverse.h"

namespace rastsim {

namespace {
template <class E>
E pick(const std::string& v, std::initializer_list<std::pair<const char*, E>> table) {
  for (const auto& [name, e] : table)
    if (v == name) return e;
  throw ConfigError("internal: unhandled enum value '" + v + "'");
}
}  // namespace

DepthFunc depth_func_from_name(const std::string& name) {
  return pick<DepthFunc>(name, {{"never", DepthFunc::Never}, {"less", DepthFunc::Less},
                                {"lequal", DepthFunc::LEqual}, {"equal", DepthFunc::Equal},
                                {"greater", DepthFunc::Greater}, {"gequal", DepthFunc::GEqual},
                                {"notequal", DepthFunc::NotEqual}, {"always", DepthFunc::Always}});
}

namespace {
// pipeline.mode and bin.* (docs/binning.md); the tile buffer must hold one bin's colour
// (4 bytes) and depth (2 or 4 bytes, as the memory system's depth surface) per sample.
BinParams bin_params_from_config(const Config& cfg, const RasterState& s) {
  BinParams b;
  b.mode = cfg.get_string("pipeline.mode") == "binned" ? PipelineMode::Binned : PipelineMode::Immediate;
  b.width = static_cast<int>(cfg.get_int("bin.width"));
  b.height = static_cast<int>(cfg.get_int("bin.height"));
  b.tile_buffer_bytes = static_cast<uint64_t>(cfg.get_int("bin.tile_buffer_bytes"));
  b.parameter_buffer_bytes = static_cast<uint64_t>(cfg.get_int("bin.parameter_buffer_bytes"));
  b.parameter_buffer_base = static_cast<uint64_t>(cfg.get_int("bin.parameter_buffer_base"));
  b.rule = cfg.get_string("bin.binning") == "exact" ? BinningRule::Exact : BinningRule::Bbox;
  b.load_color = cfg.get_bool("bin.load_color");
  b.load_depth = cfg.get_bool("bin.load_depth");
  b.store_depth = cfg.get_bool("bin.store_depth");
  const uint64_t need = uint64_t(b.width) * uint64_t(b.height) * uint64_t(s.samples) *
                        (4 + uint64_t(s.depth_bits <= 16 ? 2 : 4));
  if (b.mode == PipelineMode::Binned && need > b.tile_buffer_bytes)
    throw ConfigError("bin.tile_buffer_bytes = " + std::to_string(b.tile_buffer_bytes) + " does not hold a " +
                      std::to_string(b.width) + "x" + std::to_string(b.height) + " bin at raster.samples = " +
                      std::to_string(s.samples) + " (colour + depth: " + std::to_string(need) + " bytes)");
  if (b.mode == PipelineMode::Binned && s.traversal == Traversal::Scanline)
    throw ConfigError("pipeline.mode = binned needs an exact raster.traversal (tiled, bbox, hierarchical): "
                      "scanline's coverage is measured a whole triangle at a time (docs/binning.md)");
  return b;
}
}  // namespace

RasterState raster_state_from_config(const Config& cfg) {
  cfg.validate();
  RasterState s;
  s.coord_format = FixedFormat::parse(cfg.get_string("raster.coord_format"));
  s.tile_size = static_cast<int>(cfg.get_int("raster.tile_size"));
  s.fill_rule = pick<FillRule>(cfg.get_string("raster.fill_rule"),
                               {{"top_left", FillRule::TopLeft},
                                {"bottom_right", FillRule::BottomRight},
                                {"inclusive", FillRule::Inclusive},
                                {"exclusive", FillRule::Exclusive}});
  s.cull = pick<CullMode>(cfg.get_string("raster.cull"),
                          {{"none", CullMode::None}, {"back", CullMode::Back}, {"front", CullMode::Front}});
  s.front_ccw = cfg.get_string("raster.front_face") == "ccw";
  s.depth_func = depth_func_from_name(cfg.get_string("raster.depth_func"));
  s.depth_bits = static_cast<int>(cfg.get_int("raster.depth_bits"));
  s.depth_write = cfg.get_bool("raster.depth_write");
  s.depth_early = cfg.get_bool("depth.early");
  s.hiz_mode = pick<HizMode>(cfg.get_string("depth.hiz"),
                             {{"off", HizMode::Off}, {"max", HizMode::Max}, {"minmax", HizMode::MinMax}});
  s.hiz_block = static_cast<int>(cfg.get_int("depth.hiz_block"));
  s.hiz_bytes = cfg.get_int("depth.hiz_bytes");
  s.hiz_base = uint64_t(cfg.get_int("depth.hiz_base"));
  s.hiz_sync = pick<HizSync>(cfg.get_string("depth.hiz_sync"),
                             {{"interlock", HizSync::Interlock}, {"lagged", HizSync::Lagged}});
  s.out_of_range = cfg.get_string("raster.out_of_range") == "cull" ? OutOfRange::Cull : OutOfRange::Error;
  s.fb_width = static_cast<int>(cfg.get_int("display.width"));
  s.fb_height = static_cast<int>(cfg.get_int("display.height"));
  s.line_method = pick<LineMethod>(cfg.get_string("line.method"),
                                   {{"diamond", LineMethod::Diamond}, {"bresenham", LineMethod::Bresenham},
                                    {"midpoint", LineMethod::Midpoint}, {"dda", LineMethod::Dda}});
  s.dda_arith = pick<DdaArith>(cfg.get_string("line.dda_arith"),
                               {{"f32", DdaArith::F32}, {"f64", DdaArith::F64}, {"fixed", DdaArith::Fixed}});
  s.polygon_rule = cfg.get_string("polygon.rule") == "nonzero" ? PolygonRule::NonZero : PolygonRule::EvenOdd;
  s.traversal = pick<Traversal>(cfg.get_string("raster.traversal"),
                                {{"tiled", Traversal::Tiled}, {"bbox", Traversal::Bbox},
                                 {"hierarchical", Traversal::Hierarchical}, {"scanline", Traversal::Scanline}});
  s.hier_levels = parse_hier_levels(cfg.get_string("raster.hier_levels"));
  s.scanline_arith = pick<DdaArith>(cfg.get_string("raster.scanline_arith"),
                                    {{"f32", DdaArith::F32}, {"f64", DdaArith::F64}, {"fixed", DdaArith::Fixed}});
  s.interp_method = cfg.get_string("interp.method") == "dda" ? InterpMethod::Dda : InterpMethod::Plane;
  s.interp_arith = cfg.get_string("interp.dda_arith") == "f32" ? InterpArith::F32 : InterpArith::Fixed;
  s.interp_frac_bits = static_cast<int>(cfg.get_int("interp.dda_frac_bits"));
  s.samples = static_cast<int>(cfg.get_int("raster.samples"));
  s.aa_mode = cfg.get_string("raster.aa_mode") == "ssaa" ? AaMode::Ssaa : AaMode::Msaa;
  s.clip_method = cfg.get_string("clip.method") == "homogeneous" ? ClipMethod::Homogeneous : ClipMethod::Clip;
  s.guard_band = static_cast<float>(cfg.get_float("clip.guard_band"));
  s.perspective = cfg.get_bool("interp.perspective");
  s.recip = cfg.get_string("interp.recip") == "newton" ? RecipMethod::Newton : RecipMethod::Exact;
  s.recip_seed_bits = static_cast<int>(cfg.get_int("interp.recip_seed_bits"));
  s.recip_iterations = static_cast<int>(cfg.get_int("interp.recip_iterations"));
  s.texcoord_format = FixedFormat::parse(cfg.get_string("interp.texcoord_format"));
  s.color_frac_bits = static_cast<int>(cfg.get_int("interp.color_frac_bits"));
  s.texture = texture_params_from_config(cfg);
  s.bin = bin_params_from_config(cfg, s);
  s.viewport_width = s.fb_width;
  s.viewport_height = s.fb_height;
  return s;
}

}  // namespace rastsim
