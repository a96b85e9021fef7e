// SPDX-License-Identifier: Apache-2.0
#include "config/obj_placement.h"

#include <sstream>
#include <utility>

namespace rastsim {

std::optional<ObjUp> parse_obj_up(const std::string& name) {
  static const std::pair<const char*, ObjUp> kNames[] = {{"y", ObjUp::PosY},  {"z", ObjUp::PosZ},
                                                         {"-y", ObjUp::NegY}, {"-z", ObjUp::NegZ},
                                                         {"x", ObjUp::PosX},  {"-x", ObjUp::NegX}};
  for (const auto& [n, up] : kNames)
    if (name == n) return up;
  return std::nullopt;
}

ObjPlacement obj_placement_from_config(const Config& cfg) {
  ObjPlacement p;
  p.viewport_width = static_cast<int>(cfg.get_int("display.width"));
  p.viewport_height = static_cast<int>(cfg.get_int("display.height"));
  // The schema's enum admits exactly parse_obj_up's names, so this cannot fail on a
  // validated config; a mismatch between the two lists is a programming error.
  const std::string& up = cfg.get_string("scene.obj_up");
  const auto parsed = parse_obj_up(up);
  if (!parsed) throw ConfigError(cfg.origin("scene.obj_up") + ": scene.obj_up = '" + up + "' is not an axis");
  p.up = *parsed;
  p.yaw_deg = cfg.get_float("scene.obj_yaw_deg");
  p.pitch_deg = cfg.get_float("scene.obj_pitch_deg");
  p.fill = cfg.get_float("scene.obj_fill");
  p.faces_per_command = static_cast<int>(cfg.get_int("scene.obj_faces_per_command"));
  const std::string& order = cfg.get_string("scene.obj_order");
  p.order = order == "front_to_back" ? ObjOrder::FrontToBack : order == "back_to_front" ? ObjOrder::BackToFront
                                                                                          : ObjOrder::File;
  p.coord_format = FixedFormat::parse(cfg.get_string("raster.coord_format"));
  p.lines_points = cfg.get_string("scene.obj_lines_points") == "skip" ? ObjLinesPoints::Skip : ObjLinesPoints::Error;
  p.camera = cfg.get_string("scene.camera") == "perspective" ? ObjCamera::Perspective : ObjCamera::Ortho;
  p.fov_deg = cfg.get_float("scene.fov_deg");
  p.near = cfg.get_float("scene.near");
  p.far = cfg.get_float("scene.far");
  p.distance = cfg.get_float("scene.distance");
  const std::string& filter = cfg.get_string("scene.obj_texfilter");
  p.tex_filter = filter == "nearest" ? TexFilter::Nearest : filter == "trilinear" ? TexFilter::Trilinear
                                                                                  : TexFilter::Bilinear;
  p.tex_mipmap = cfg.get_bool("scene.obj_mipmap");
  if (!(p.far > p.near)) {
    std::ostringstream why;  // the shortest form of each value, as written in a config
    why << cfg.origin("scene.far") << ": scene.far = " << p.far << " must exceed scene.near = " << p.near << " ("
        << cfg.origin("scene.near") << "): the perspective camera's far plane lies beyond its near plane";
    throw ConfigError(why.str());
  }
  return p;
}

}  // namespace rastsim
