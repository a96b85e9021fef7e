// SPDX-License-Identifier: Apache-2.0
#include "scene/apitrace_texture.h"

#include <algorithm>
#include <cstring>

#include "ref/scene.h"
#include "scene/apitrace_dump.h"
#include "scene/scene_text.h"

namespace rastsim::apitrace {

namespace {

[[noreturn]] void fail(const Call& c, const std::string& name, const std::string& what) {
  scene_text::fail(name, c.line, "call " + std::to_string(c.number) + " " + c.function + ": " + what);
}

const Value& arg(const Call& c, const std::string& name, const char* n) {
  const Value* v = c.arg(n);
  if (!v) fail(c, name, std::string("no argument '") + n + "'");
  return *v;
}

int64_t int_arg(const Call& c, const std::string& name, const char* n) {
  const auto v = integer(arg(c, name, n));
  if (!v) fail(c, name, std::string("argument '") + n + "' is not an integer: '" + arg(c, name, n).text + "'");
  return *v;
}

// Bytes a texel of `format` (unsigned byte components), 0 for a format not read.
int texel_bytes(const std::string& format) {
  if (format == "GL_RGBA") return 4;
  if (format == "GL_RGB") return 3;
  if (format == "GL_LUMINANCE_ALPHA") return 2;
  if (format == "GL_LUMINANCE" || format == "GL_ALPHA") return 1;
  return 0;
}

// glTexImage2D (level 0: the image; another level: counted as uploaded mips) and
// glTexSubImage2D (level 0: a region replaced) into the bound texture.
void tex_image(TextureTable& t, const Call& c, const std::string& name,
               const std::function<std::string(const Value&)>& bytes_of) {
  if (arg(c, name, "target").text != "GL_TEXTURE_2D") return;  // cube maps and others: not sampled by imported draws
  const auto it = t.bound.find(t.active_unit);
  if (it == t.bound.end() || it->second == 0) fail(c, name, "no texture bound to GL_TEXTURE_2D");
  GlTexture& tex = t.textures[it->second];
  const bool sub = c.function == "glTexSubImage2D";
  const int64_t level = int_arg(c, name, "level");
  const int64_t w = int_arg(c, name, "width"), h = int_arg(c, name, "height");
  if (w < 0 || h < 0 || w > 16384 || h > 16384) fail(c, name, "size outside 0..16384");
  if (level != 0) {
    if (!sub) tex.mips = GlTexture::Mips::Uploaded;
    return;
  }
  const Value& px = arg(c, name, "pixels");
  const std::string bytes = px.kind == Value::Kind::Blob ? bytes_of(px) : std::string();
  std::string why;
  std::vector<uint8_t> rgba;
  if (px.kind == Value::Kind::Blob || w * h == 0) {
    rgba = pixels_to_rgba(arg(c, name, "format").text, arg(c, name, "type").text, static_cast<int>(w),
                          static_cast<int>(h), t.unpack_alignment, bytes, why);
  } else if (integer(px) == 0 && !sub) {
    rgba.assign(static_cast<size_t>(w * h * 4), 0);  // NULL: storage only (undefined in GL; zeros here)
  } else {
    why = "pixels '" + px.text + "' are neither a blob nor NULL (a pixel unpack buffer is not imported)";
  }
  ++tex.version;
  tex.image_call = c.number;
  if (!sub) {
    tex.width = static_cast<int>(w), tex.height = static_cast<int>(h);
    tex.rgba = std::move(rgba);
    tex.unusable = why.empty() ? "" : "call " + std::to_string(c.number) + " glTexImage2D: " + why;
    if (tex.mips == GlTexture::Mips::Generated) tex.mips = GlTexture::Mips::None;  // a new level 0 is not regenerated
    return;
  }
  const int64_t x0 = int_arg(c, name, "xoffset"), y0 = int_arg(c, name, "yoffset");
  if (x0 < 0 || y0 < 0 || x0 + w > tex.width || y0 + h > tex.height)
    fail(c, name, "region outside the " + std::to_string(tex.width) + "x" + std::to_string(tex.height) + " image");
  if (!why.empty()) {
    tex.unusable = "call " + std::to_string(c.number) + " glTexSubImage2D: " + why;
    return;
  }
  for (int64_t y = 0; y < h; ++y)
    std::memcpy(&tex.rgba[static_cast<size_t>(((y0 + y) * tex.width + x0) * 4)], &rgba[static_cast<size_t>(y * w * 4)],
                static_cast<size_t>(w * 4));
}

// A filter or wrap parameter as an enum name: glTexParameterf's float prints as a number.
std::string enum_param(const Value& p) {
  static const std::map<int64_t, const char*> names{
      {0x2600, "GL_NEAREST"}, {0x2601, "GL_LINEAR"}, {0x2700, "GL_NEAREST_MIPMAP_NEAREST"},
      {0x2701, "GL_LINEAR_MIPMAP_NEAREST"}, {0x2702, "GL_NEAREST_MIPMAP_LINEAR"}, {0x2703, "GL_LINEAR_MIPMAP_LINEAR"},
      {0x2901, "GL_REPEAT"}, {0x812F, "GL_CLAMP_TO_EDGE"}, {0x8370, "GL_MIRRORED_REPEAT"}};
  const auto v = number(p);
  if (!v) return p.text;
  const auto it = names.find(static_cast<int64_t>(*v));
  return it != names.end() && *v == static_cast<double>(it->first) ? it->second : p.text;
}

void tex_parameter(TextureTable& t, const Call& c, const std::string& name) {
  if (arg(c, name, "target").text != "GL_TEXTURE_2D") return;
  const auto it = t.bound.find(t.active_unit);
  if (it == t.bound.end() || it->second == 0) fail(c, name, "no texture bound to GL_TEXTURE_2D");
  GlTexture& tex = t.textures[it->second];
  const std::string pname = arg(c, name, "pname").text;
  const Value& p = arg(c, name, "param");
  if (pname == "GL_TEXTURE_MIN_FILTER") tex.min_filter = enum_param(p);
  else if (pname == "GL_TEXTURE_MAG_FILTER") tex.mag_filter = enum_param(p);
  else if (pname == "GL_TEXTURE_WRAP_S") tex.wrap_s = enum_param(p);
  else if (pname == "GL_TEXTURE_WRAP_T") tex.wrap_t = enum_param(p);
  else if (pname == "GL_TEXTURE_LOD_BIAS") {
    const auto b = number(p);
    if (!b) fail(c, name, "LOD bias '" + p.text + "' is not a number");
    tex.lod_bias = std::clamp(*b, -16.0, 16.0);
  }
}

}  // namespace

bool texture_call(TextureTable& t, const Call& c, const std::string& name,
                  const std::function<std::string(const Value&)>& bytes_of) {
  const std::string& f = c.function;
  if (f == "glActiveTexture") {
    const std::string u = arg(c, name, "texture").text;
    if (u.rfind("GL_TEXTURE", 0) != 0) fail(c, name, "unit '" + u + "' is not GL_TEXTUREn");
    const auto n = scene_text::parse_int(u.substr(10));
    if (!n) fail(c, name, "unit '" + u + "' is not GL_TEXTUREn");
    t.active_unit = *n;
  } else if (f == "glBindTexture") {
    if (arg(c, name, "target").text == "GL_TEXTURE_2D")
      t.bound[t.active_unit] = static_cast<uint32_t>(int_arg(c, name, "texture"));
  } else if (f == "glTexImage2D" || f == "glTexSubImage2D") {
    tex_image(t, c, name, bytes_of);
  } else if (f == "glTexParameteri" || f == "glTexParameterf") {
    tex_parameter(t, c, name);
  } else if (f == "glGenerateMipmap" || f == "glGenerateMipmapEXT" || f == "glGenerateMipmapOES") {
    const auto it = t.bound.find(t.active_unit);
    if (arg(c, name, "target").text == "GL_TEXTURE_2D" && it != t.bound.end() && it->second != 0)
      t.textures[it->second].mips = GlTexture::Mips::Generated;
  } else if (f == "glCompressedTexImage2D" || f == "glCopyTexImage2D" || f == "glCopyTexSubImage2D") {
    // Images the importer cannot rebuild: a draw that samples them is refused, not drawn
    // with a stale image.
    const auto it = t.bound.find(t.active_unit);
    if (arg(c, name, "target").text == "GL_TEXTURE_2D" && it != t.bound.end() && it->second != 0) {
      GlTexture& tex = t.textures[it->second];
      ++tex.version;
      tex.image_call = c.number;
      tex.unusable = "call " + std::to_string(c.number) + " " + f + ": its image is not imported";
    }
  } else if (f == "glFramebufferTexture2D" || f == "glFramebufferTexture2DEXT") {
    // Rendered into: its image is what the program draws, which the importer does not keep.
    const auto id = integer(arg(c, name, "texture"));
    if (id && *id != 0) {
      GlTexture& tex = t.textures[static_cast<uint32_t>(*id)];
      ++tex.version;
      tex.image_call = c.number;
      tex.unusable = "call " + std::to_string(c.number) + " " + f + ": rendered to, its image is not imported";
    }
  } else if (f == "glPixelStorei") {
    if (arg(c, name, "pname").text == "GL_UNPACK_ALIGNMENT") {
      t.unpack_alignment = int_arg(c, name, "param");
      if (t.unpack_alignment != 1 && t.unpack_alignment != 2 && t.unpack_alignment != 4 && t.unpack_alignment != 8)
        fail(c, name, "GL_UNPACK_ALIGNMENT " + std::to_string(t.unpack_alignment) + " is not 1, 2, 4 or 8");
    }
  } else if (f == "glDeleteTextures") {
    // Names are reused by glGenTextures; a deleted texture's name starts afresh.
    const Value& v = arg(c, name, "textures");
    for (const Value& item : v.kind == Value::Kind::List ? v.items : std::vector<Value>{v})
      if (const auto id = integer(item)) t.textures.erase(static_cast<uint32_t>(*id));
  } else {
    return false;
  }
  return true;
}

std::vector<uint8_t> pixels_to_rgba(const std::string& format, const std::string& type, int w, int h,
                                    int64_t align, const std::string& pixels, std::string& why) {
  const int bpp = texel_bytes(format);
  if (bpp == 0 || type != "GL_UNSIGNED_BYTE") {
    why = "format " + format + ", type " + type + " is not imported (RGBA, RGB, LUMINANCE, LUMINANCE_ALPHA, ALPHA "
          "of GL_UNSIGNED_BYTE are)";
    return {};
  }
  const int64_t row = (int64_t{w} * bpp + align - 1) / align * align;  // bytes a row, padded
  const int64_t need = h == 0 ? 0 : row * (h - 1) + int64_t{w} * bpp;
  if (static_cast<int64_t>(pixels.size()) < need) {
    why = "the pixels have " + std::to_string(pixels.size()) + " bytes, " + std::to_string(w) + "x" +
          std::to_string(h) + " " + format + " with rows of " + std::to_string(row) + " bytes needs " +
          std::to_string(need);
    return {};
  }
  std::vector<uint8_t> out(static_cast<size_t>(w) * static_cast<size_t>(h) * 4);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const auto* p = reinterpret_cast<const uint8_t*>(pixels.data()) + y * row + int64_t{x} * bpp;
      uint8_t* o = &out[(static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x)) * 4];
      if (bpp >= 3) {
        o[0] = p[0], o[1] = p[1], o[2] = p[2], o[3] = bpp == 4 ? p[3] : 255;
      } else if (format == "GL_ALPHA") {
        o[0] = o[1] = o[2] = 0, o[3] = p[0];
      } else {
        o[0] = o[1] = o[2] = p[0], o[3] = bpp == 2 ? p[1] : 255;
      }
    }
  return out;
}

SamplerState sampler_state(const GlTexture& t) {
  SamplerState s;
  const std::string& mn = t.min_filter;
  const std::string& mg = t.mag_filter;
  const bool mip = mn.find("_MIPMAP_") != std::string::npos;
  if (mn == "GL_NEAREST" && mg == "GL_NEAREST") s.filter = "nearest";
  else if (mn == "GL_LINEAR" && mg == "GL_LINEAR") s.filter = "bilinear";
  else if (mn == "GL_NEAREST_MIPMAP_NEAREST" && mg == "GL_NEAREST") s.filter = "nearest";
  else if (mn == "GL_LINEAR_MIPMAP_NEAREST" && mg == "GL_LINEAR") s.filter = "bilinear";
  else if (mn == "GL_LINEAR_MIPMAP_LINEAR" && mg == "GL_LINEAR") s.filter = "trilinear";
  if (s.filter.empty()) {
    s.why = "min filter " + mn + " with mag filter " + mg + " has no rastsim texfilter (one filter for both)";
    return s;
  }
  if (mip && t.mips == GlTexture::Mips::None) {
    s.why = "min filter " + mn + " without mip levels (GL's texture is incomplete)";
    return s;
  }
  s.mipmap = mip;
  auto wrap = [](const std::string& w) -> std::string {
    if (w == "GL_REPEAT") return "repeat";
    if (w == "GL_CLAMP_TO_EDGE") return "clamp";
    if (w == "GL_MIRRORED_REPEAT") return "mirror";
    return "";
  };
  s.wrap_s = wrap(t.wrap_s), s.wrap_t = wrap(t.wrap_t);
  if (s.wrap_s.empty() || s.wrap_t.empty()) {
    s.why = "wrap " + (s.wrap_s.empty() ? t.wrap_s : t.wrap_t) + " is not imported (REPEAT, CLAMP_TO_EDGE, "
            "MIRRORED_REPEAT are)";
    return s;
  }
  s.ok = true;
  return s;
}

}  // namespace rastsim::apitrace
