// SPDX-License-Identifier: Apache-2.0
#include "scene/apitrace_import.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <optional>
#include <sstream>
#include <tuple>

#include <zstd.h>

#include <fstream>

#include "ref/scene.h"
#include "scene/apitrace_dump.h"
#include "scene/apitrace_shader.h"
#include "scene/apitrace_texture.h"
#include "scene/scene_text.h"

namespace rastsim::apitrace {

namespace {

using Mat4 = std::array<double, 16>;  // column-major, as glUniformMatrix4fv with transpose false

struct Attrib {
  bool enabled = false, client = false, normalized = false;
  uint32_t buffer = 0;
  int size = 4;
  std::string type = "GL_FLOAT";
  int64_t stride = 0, offset = 0;
};

struct Program {
  std::vector<uint32_t> shaders;
  std::map<std::string, int64_t> bound_attribs, attribs;  // glBindAttribLocation; at link / glGetAttribLocation
  std::map<std::string, int64_t> uniform_locations;       // glGetUniformLocation's answers
  std::map<int64_t, Mat4> matrices;                       // glUniformMatrix4fv by location
  std::map<int64_t, int64_t> ints;                        // glUniform1i by location (a sampler's unit)
};

// A linked program's shaders as the importer reads them (apitrace_shader.h).
struct ProgramForm {
  uint32_t vs = 0, fs = 0;        // the shader objects read
  ShaderForm vertex;              // gl_Position
  FragmentForm fragment;          // its use of a texture
  VaryingSource coord, colour;    // the vertex shader's source of fragment.coord, fragment.colour
};

// One GL context's objects and state (glXMakeCurrent switches between them).
struct Context {
  std::map<uint32_t, std::string> buffers;                   // buffer object -> bytes
  std::map<uint32_t, std::pair<bool, std::string>> shaders;  // shader -> (vertex?, source)
  std::map<uint32_t, Program> programs;
  std::map<int64_t, Attrib> attribs;
  TextureTable tex;
  uint32_t array_buffer = 0, element_buffer = 0, program = 0;
  std::array<int64_t, 4> viewport{0, 0, 0, 0}, scissor{0, 0, 0, 0};
  bool scissor_test = false, depth_test = false, cull = false, blend = false, depth_mask = true;
  std::string depth_func = "GL_LESS", cull_face = "GL_BACK", front_face = "GL_CCW";
  std::array<double, 4> clear_color{0, 0, 0, 0};
  double clear_depth = 1, depth_near = 0, depth_far = 1;
};

struct ClipV {
  float x, y, z, w;
  int r, g, b;
  float s = 0, t = 0;  // texture coordinate (repeats), binary32 as the attribute holds it
};

// A draw's texture: none (untextured), or the trace state it is drawn with.
struct DrawTexture {
  bool on = false;
  uint32_t id = 0;             // the GL texture (and the trace's texture ID)
  const GlTexture* tex = nullptr;
  SamplerState sampler;
  std::string env;             // replace, modulate, decal
  const Attrib* coord = nullptr;
  const Attrib* colour = nullptr;  // a modulating varying's attribute, when it passes one through
  std::string note;            // how the colour relates to the program's (ImportResult::texture_notes)
};

// A draw that cannot be imported: the message names the call, and it is counted.
struct Refused {
  std::string why;
};

// Plain decimal (the trace's depth syntax has no exponent), shortest that reads back.
std::string plain_decimal(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17f", v);
  std::string s = buf;
  while (s.size() > 1 && s.back() == '0') s.pop_back();
  if (s.back() == '.') s.pop_back();
  return s;
}

std::string f32(float v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", static_cast<double>(v));  // 9 digits: a binary32 exactly
  return buf;
}

std::string lower_enum(const std::string& e) {
  std::string s = e.rfind("GL_", 0) == 0 ? e.substr(3) : e;
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

class Importer {
 public:
  Importer(const std::string& name, const ImportOptions& opt) : name_(name), opt_(opt) { cur_ = &contexts_[""]; }
  void call(const Call& c);
  ImportResult finish();

 private:
  [[noreturn]] void fail(const Call& c, const std::string& what) const {
    scene_text::fail(name_, c.line, "call " + std::to_string(c.number) + " " + c.function + ": " + what);
  }
  const Value& arg(const Call& c, const char* n) const {
    const Value* v = c.arg(n);
    if (!v) fail(c, std::string("no argument '") + n + "'");
    return *v;
  }
  int64_t int_arg(const Call& c, const char* n) const {
    const auto v = integer(arg(c, n));
    if (!v) fail(c, std::string("argument '") + n + "' is not an integer: '" + arg(c, n).text + "'");
    return *v;
  }
  double num_arg(const Call& c, const char* n) const {
    const auto v = number(arg(c, n));
    if (!v) fail(c, std::string("argument '") + n + "' is not a number: '" + arg(c, n).text + "'");
    return *v;
  }
  std::string bytes_of(const Call& c, const Value& v) const;
  bool state_call(const Call& c);
  bool object_call(const Call& c);
  bool program_call(const Call& c);
  void uniform_matrix(const Call& c);
  void clear(const Call& c);
  void draw(const Call& c);
  void draw_checked(const Call& c, const std::string& mode, const std::vector<uint32_t>& indices);
  std::vector<std::string> config_for_draw() const;
  Mat4 position_matrix(const Program& p, const ShaderForm& f) const;
  const ProgramForm& form_of(uint32_t program);
  const Attrib& enabled_array(const Program& p, const std::string& attr, const char* what) const;
  DrawTexture texture_for_draw(const Program& p, const ProgramForm& pf) const;
  void emit_texture(const DrawTexture& d);
  void emit_vertices(const std::string& mode, const std::vector<ClipV>& verts, bool texcoords);
  const Attrib* named_colour(const Program& p, const ShaderForm& form) const;
  ClipV vertex(const Mat4& m, const Attrib& pos, const Attrib* colour, const Attrib* coord, uint32_t i) const;
  std::array<double, 4> fetch(const Attrib& a, uint32_t index, const char* what) const;
  void emit_state();
  void emit(const std::string& line) {
    body_ << line << '\n';
    ++commands_since_frame_;
  }

  std::string name_;
  ImportOptions opt_;
  std::map<std::string, Context> contexts_;
  Context* cur_;
  std::map<std::pair<const Context*, uint32_t>, ProgramForm> forms_;  // linked program -> its forms
  // Texture files: (context, GL texture, version) -> file; files a GL texture has had;
  // the trace's texture ID -> file it holds now; the texture state lines last written.
  std::map<std::tuple<const Context*, uint32_t, int>, std::string> texture_files_;
  std::map<uint32_t, int> files_of_id_;
  std::map<uint32_t, std::string> emitted_texture_;
  std::map<std::string, std::string> emitted_tex_state_;
  std::ostringstream body_;
  int commands_since_frame_ = 0;
  int width_ = 0, height_ = 0;
  std::string emitted_xform_, emitted_scissor_ = "scissor off", emitted_range_ = "depth_range 0 1";
  ImportResult r_;
};

std::string Importer::bytes_of(const Call& c, const Value& v) const {
  if (v.kind != Value::Kind::Blob) fail(c, "data '" + v.text + "' is not a blob (dump with --blobs)");
  if (!opt_.read_blob) fail(c, "no blob reader for '" + v.text + "'");
  try {
    return opt_.read_blob(v.text);
  } catch (const std::exception& e) {
    fail(c, "cannot read blob '" + v.text + "': " + e.what());
  }
}

// Viewport, scissor, enables, depth and cull state, clear values.
bool Importer::state_call(const Call& c) {
  const std::string& f = c.function;
  Context& x = *cur_;
  if (f == "glViewport" || f == "glScissor") {
    std::array<int64_t, 4> b{int_arg(c, "x"), int_arg(c, "y"), int_arg(c, "width"), int_arg(c, "height")};
    if (b[2] < 0 || b[3] < 0) fail(c, "negative size");
    (f == "glViewport" ? x.viewport : x.scissor) = b;
    if (f == "glViewport" && width_ == 0) {
      width_ = opt_.width > 0 ? opt_.width : static_cast<int>(b[2]);
      height_ = opt_.height > 0 ? opt_.height : static_cast<int>(b[3]);
    }
  } else if (f == "glEnable" || f == "glDisable") {
    const std::string cap = arg(c, "cap").text;
    const bool on = f == "glEnable";
    if (cap == "GL_SCISSOR_TEST") x.scissor_test = on;
    else if (cap == "GL_DEPTH_TEST") x.depth_test = on;
    else if (cap == "GL_CULL_FACE") x.cull = on;
    else if (cap == "GL_BLEND") x.blend = on;
  } else if (f == "glDepthFunc") {
    x.depth_func = arg(c, "func").text;
  } else if (f == "glDepthMask") {
    x.depth_mask = arg(c, "flag").text != "GL_FALSE";
  } else if (f == "glCullFace") {
    x.cull_face = arg(c, "mode").text;
  } else if (f == "glFrontFace") {
    x.front_face = arg(c, "mode").text;
  } else if (f == "glDepthRange" || f == "glDepthRangef") {
    // Its two arguments by position (zNear, zFar or n, f, by the entry point).
    const auto n = c.args.size() == 2 ? number(c.args[0].value) : std::nullopt;
    const auto fa = c.args.size() == 2 ? number(c.args[1].value) : std::nullopt;
    if (!n || !fa) fail(c, "expected two numbers");
    x.depth_near = std::clamp(*n, 0.0, 1.0);
    x.depth_far = std::clamp(*fa, 0.0, 1.0);
  } else if (f == "glClearColor") {
    x.clear_color = {num_arg(c, "red"), num_arg(c, "green"), num_arg(c, "blue"), num_arg(c, "alpha")};
  } else if (f == "glClearDepth" || f == "glClearDepthf") {
    x.clear_depth = std::clamp(num_arg(c, "depth"), 0.0, 1.0);
  } else if (f == "glClear") {
    clear(c);
  } else {
    return false;
  }
  return true;
}

// Buffer objects and vertex arrays.
bool Importer::object_call(const Call& c) {
  const std::string& f = c.function;
  Context& x = *cur_;
  if (f == "glBindBuffer") {
    const std::string t = arg(c, "target").text;
    const auto id = static_cast<uint32_t>(int_arg(c, "buffer"));
    if (t == "GL_ARRAY_BUFFER") x.array_buffer = id;
    if (t == "GL_ELEMENT_ARRAY_BUFFER") x.element_buffer = id;
  } else if (f == "glBufferData" || f == "glBufferSubData") {
    const std::string t = arg(c, "target").text;
    const uint32_t id = t == "GL_ARRAY_BUFFER" ? x.array_buffer : t == "GL_ELEMENT_ARRAY_BUFFER" ? x.element_buffer : 0;
    if (id == 0) return true;  // other targets (uniform, pixel buffers) do not feed vertices
    const int64_t size = int_arg(c, "size");
    const Value& d = arg(c, "data");
    std::string bytes = d.kind == Value::Kind::Blob ? bytes_of(c, d) : std::string();
    if (d.kind == Value::Kind::Blob && static_cast<int64_t>(bytes.size()) != size)
      fail(c, "blob '" + d.text + "' has " + std::to_string(bytes.size()) + " bytes, size says " + std::to_string(size));
    std::string& buf = x.buffers[id];
    if (f == "glBufferData") {
      buf = bytes.empty() ? std::string(static_cast<size_t>(size), '\0') : bytes;
    } else {
      const int64_t off = int_arg(c, "offset");
      if (off < 0 || off + size > static_cast<int64_t>(buf.size())) fail(c, "range past the buffer's end");
      std::memcpy(buf.data() + off, bytes.data(), bytes.size());
    }
  } else if (f == "glEnableVertexAttribArray" || f == "glDisableVertexAttribArray") {
    x.attribs[int_arg(c, "index")].enabled = f == "glEnableVertexAttribArray";
  } else if (f == "glVertexAttribPointer") {
    Attrib& a = x.attribs[int_arg(c, "index")];
    a.size = static_cast<int>(int_arg(c, "size"));
    a.type = arg(c, "type").text;
    a.normalized = arg(c, "normalized").text == "GL_TRUE";
    a.stride = int_arg(c, "stride");
    a.buffer = x.array_buffer;
    const auto off = integer(arg(c, "pointer"));
    a.client = a.buffer == 0 || !off;
    a.offset = off.value_or(0);
  } else {
    return false;
  }
  return true;
}

bool Importer::program_call(const Call& c) {
  const std::string& f = c.function;
  Context& x = *cur_;
  if (f == "glCreateShader") {
    if (!c.ret) fail(c, "no return value");
    x.shaders[static_cast<uint32_t>(integer(*c.ret).value_or(0))] = {arg(c, "type").text == "GL_VERTEX_SHADER", ""};
  } else if (f == "glShaderSource") {
    auto& sh = x.shaders[static_cast<uint32_t>(int_arg(c, "shader"))];
    const Value& s = arg(c, "string");
    sh.second.clear();
    if (s.kind == Value::Kind::String) sh.second = s.text;
    for (const Value& part : s.items) sh.second += part.text;
  } else if (f == "glAttachShader") {
    x.programs[static_cast<uint32_t>(int_arg(c, "program"))].shaders.push_back(static_cast<uint32_t>(int_arg(c, "shader")));
  } else if (f == "glBindAttribLocation") {
    x.programs[static_cast<uint32_t>(int_arg(c, "program"))].bound_attribs[arg(c, "name").text] = int_arg(c, "index");
  } else if (f == "glLinkProgram") {
    const auto id = static_cast<uint32_t>(int_arg(c, "program"));
    Program& p = x.programs[id];
    p.attribs = p.bound_attribs;
    forms_.erase({cur_, id});
  } else if (f == "glGetAttribLocation" || f == "glGetUniformLocation") {
    Program& p = x.programs[static_cast<uint32_t>(int_arg(c, "program"))];
    const int64_t loc = c.ret ? integer(*c.ret).value_or(-1) : -1;
    if (loc >= 0) (f == "glGetAttribLocation" ? p.attribs : p.uniform_locations)[arg(c, "name").text] = loc;
  } else if (f == "glUseProgram") {
    x.program = static_cast<uint32_t>(int_arg(c, "program"));
  } else if (f == "glUniformMatrix4fv") {
    uniform_matrix(c);
  } else if (f == "glUniform1i") {
    cur_->programs[cur_->program].ints[int_arg(c, "location")] = int_arg(c, "v0");
  } else {
    return false;
  }
  return true;
}

void Importer::uniform_matrix(const Call& c) {
  const int64_t loc = int_arg(c, "location");
  const int64_t count = int_arg(c, "count");
  const Value& v = arg(c, "value");
  if (v.kind != Value::Kind::List || static_cast<int64_t>(v.items.size()) != 16 * count)
    fail(c, "value is not " + std::to_string(16 * count) + " numbers");
  const bool transpose = arg(c, "transpose").text == "GL_TRUE";
  Program& p = cur_->programs[cur_->program];
  for (int64_t m = 0; m < count; ++m) {
    Mat4 out{};
    for (int k = 0; k < 16; ++k) {
      // apitrace prints a GLfloat with 7 significant digits: read as the nearest binary32.
      const auto pf = scene_text::parse_float(v.items[static_cast<size_t>(m * 16 + k)].text);
      if (pf.status != scene_text::FloatStatus::Ok) fail(c, "matrix element " + std::to_string(k) + " is not a float");
      out[transpose ? (k % 4) * 4 + k / 4 : k] = pf.value;
    }
    p.matrices[loc + m] = out;
  }
}

void Importer::clear(const Call& c) {
  const std::string mask = arg(c, "mask").text;
  const Context& x = *cur_;
  if (x.scissor_test && !(x.scissor[0] <= 0 && x.scissor[1] <= 0 && x.scissor[0] + x.scissor[2] >= width_ &&
                          x.scissor[1] + x.scissor[3] >= height_)) {
    ++r_.clears_refused;
    r_.refusals.push_back(name_ + ":" + std::to_string(c.line) + ": call " + std::to_string(c.number) +
                          " glClear refused: a scissored clear (rastsim's clear fills the framebuffer)");
    return;
  }
  if (emitted_scissor_ != "scissor off") emit(emitted_scissor_ = "scissor off");
  if (mask.find("GL_COLOR_BUFFER_BIT") != std::string::npos) {
    std::string line = "clear";
    for (int k = 0; k < 3; ++k)
      line += " " + std::to_string(static_cast<int>(std::lround(std::clamp(x.clear_color[k], 0.0, 1.0) * 255.0)));
    emit(line);
  }
  if (mask.find("GL_DEPTH_BUFFER_BIT") != std::string::npos) emit("cleardepth " + plain_decimal(x.clear_depth));
}

// The config a draw needs (rastsim keeps these in the config, not in the trace).
std::vector<std::string> Importer::config_for_draw() const {
  const Context& x = *cur_;
  if (x.cull && x.cull_face == "GL_FRONT_AND_BACK") throw Refused{"glCullFace(GL_FRONT_AND_BACK) is not imported"};
  return {"raster.depth_func=" + (x.depth_test ? lower_enum(x.depth_func) : std::string("always")),
          std::string("raster.depth_write=") + (x.depth_test && x.depth_mask ? "true" : "false"),
          "raster.cull=" + (x.cull ? lower_enum(x.cull_face) : std::string("none")),
          "raster.front_face=" + lower_enum(x.front_face)};
}

const ProgramForm& Importer::form_of(uint32_t program) {
  auto it = forms_.find({cur_, program});
  if (it == forms_.end()) {
    const Program& p = cur_->programs[program];
    ProgramForm e;
    e.vertex.reason = "the program has no vertex shader";
    for (uint32_t s : p.shaders) {
      const auto sh = cur_->shaders.find(s);
      if (sh == cur_->shaders.end()) continue;
      if (sh->second.first) e.vs = s, e.vertex = recognise_vertex_shader(sh->second.second);
      else e.fs = s, e.fragment = recognise_fragment_shader(sh->second.second);
    }
    const auto vs = cur_->shaders.find(e.vs);
    if (vs != cur_->shaders.end() && !e.fragment.coord.empty()) e.coord = varying_source(vs->second.second, e.fragment.coord);
    if (vs != cur_->shaders.end() && !e.fragment.colour.empty())
      e.colour = varying_source(vs->second.second, e.fragment.colour);
    it = forms_.emplace(std::make_pair(cur_, program), e).first;
  }
  return it->second;
}

Mat4 Importer::position_matrix(const Program& p, const ShaderForm& f) const {
  Mat4 m{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  for (const std::string& u : f.matrices) {
    const auto loc = p.uniform_locations.find(u);
    if (loc == p.uniform_locations.end()) throw Refused{"the location of uniform '" + u + "' is unknown"};
    const auto v = p.matrices.find(loc->second);
    if (v == p.matrices.end()) throw Refused{"uniform '" + u + "' was never set"};
    Mat4 out{};
    for (int col = 0; col < 4; ++col)
      for (int row = 0; row < 4; ++row)
        for (int k = 0; k < 4; ++k) out[col * 4 + row] += m[k * 4 + row] * v->second[col * 4 + k];
    m = out;
  }
  return m;
}

// Attribute `index`'s components (missing ones 0, 0, 0, 1 as GL fills them).
std::array<double, 4> Importer::fetch(const Attrib& a, uint32_t index, const char* what) const {
  const auto b = cur_->buffers.find(a.buffer);
  const int bytes = a.type == "GL_FLOAT" ? 4 : a.type == "GL_UNSIGNED_BYTE" ? 1 : 0;
  if (bytes == 0) throw Refused{std::string(what) + " attribute of type " + a.type + " is not imported"};
  if (a.size < 1 || a.size > 4) throw Refused{std::string(what) + " attribute of size " + std::to_string(a.size)};
  const int64_t stride = a.stride ? a.stride : a.size * bytes;
  const int64_t at = a.offset + static_cast<int64_t>(index) * stride;
  if (b == cur_->buffers.end() || at < 0 || at + a.size * bytes > static_cast<int64_t>(b->second.size()))
    throw Refused{std::string(what) + " vertex " + std::to_string(index) + " lies outside buffer " + std::to_string(a.buffer)};
  std::array<double, 4> v{0, 0, 0, 1};
  for (int k = 0; k < a.size; ++k) {
    if (bytes == 4) {
      float f;
      std::memcpy(&f, b->second.data() + at + 4 * k, 4);
      v[static_cast<size_t>(k)] = f;
    } else {
      const auto u = static_cast<unsigned char>(b->second[static_cast<size_t>(at + k)]);
      v[static_cast<size_t>(k)] = a.normalized ? u / 255.0 : u;
    }
  }
  return v;
}

// viewport_xform, scissor and depth_range as GL has them now, where they changed.
void Importer::emit_state() {
  const Context& x = *cur_;
  const auto& v = x.viewport;
  const std::string xform = "viewport_xform " + std::to_string(v[0]) + " " + std::to_string(height_ - v[1] - v[3]) +
                            " " + std::to_string(v[2]) + " " + std::to_string(v[3]);
  if (xform != emitted_xform_) emit(emitted_xform_ = xform);
  const auto& s = x.scissor;
  const std::string sc = x.scissor_test ? "scissor " + std::to_string(std::max<int64_t>(s[0], 0)) + " " +
                                              std::to_string(std::max<int64_t>(height_ - s[1] - s[3], 0)) + " " +
                                              std::to_string(s[2]) + " " + std::to_string(s[3])
                                        : "scissor off";
  if (sc != emitted_scissor_) emit(emitted_scissor_ = sc);
  const std::string range = "depth_range " + plain_decimal(x.depth_near) + " " + plain_decimal(x.depth_far);
  if (range != emitted_range_) emit(emitted_range_ = range);
}

void Importer::draw(const Call& c) {
  ++r_.draws;
  const std::string mode = arg(c, "mode").text;
  std::vector<uint32_t> indices;
  if (c.function == "glDrawArrays") {
    const int64_t first = int_arg(c, "first"), count = int_arg(c, "count");
    if (first < 0 || count < 0) fail(c, "negative first or count");
    for (int64_t i = 0; i < count; ++i) indices.push_back(static_cast<uint32_t>(first + i));
  } else {
    const int64_t count = int_arg(c, "count");
    const std::string type = arg(c, "type").text;
    const int bytes = type == "GL_UNSIGNED_BYTE" ? 1 : type == "GL_UNSIGNED_SHORT" ? 2 : type == "GL_UNSIGNED_INT" ? 4 : 0;
    if (bytes == 0 || count < 0) fail(c, "index type " + type + " or count " + std::to_string(count) + " is not valid");
    const Value& iv = arg(c, "indices");
    std::string src;
    int64_t off = 0;
    if (iv.kind == Value::Kind::Blob) {
      src = bytes_of(c, iv);  // client-side indices, recorded by apitrace
    } else {
      const auto b = cur_->buffers.find(cur_->element_buffer);
      off = integer(iv).value_or(-1);
      if (cur_->element_buffer == 0 || b == cur_->buffers.end() || off < 0) {
        ++r_.draws_refused;
        r_.refusals.push_back(name_ + ":" + std::to_string(c.line) + ": call " + std::to_string(c.number) + " " +
                              c.function + " refused: indices neither in a buffer object nor recorded");
        return;
      }
      src = b->second;
    }
    if (off + count * bytes > static_cast<int64_t>(src.size())) fail(c, "indices past the end of their buffer");
    for (int64_t i = 0; i < count; ++i) {
      uint32_t v = 0;
      std::memcpy(&v, src.data() + off + i * bytes, static_cast<size_t>(bytes));  // little-endian capture host
      indices.push_back(v);
    }
  }
  try {
    draw_checked(c, mode, indices);
    ++r_.draws_imported;
  } catch (const Refused& e) {
    ++r_.draws_refused;
    r_.refusals.push_back(name_ + ":" + std::to_string(c.line) + ": call " + std::to_string(c.number) + " " +
                          c.function + " refused: " + e.why);
  }
}

// The enabled array in a buffer object that feeds attribute `attr` of program p.
const Attrib& Importer::enabled_array(const Program& p, const std::string& attr, const char* what) const {
  const auto loc = p.attribs.find(attr);
  if (loc == p.attribs.end()) throw Refused{std::string("the location of ") + what + " attribute '" + attr + "' is unknown"};
  const auto a = cur_->attribs.find(loc->second);
  if (a == cur_->attribs.end() || !a->second.enabled || a->second.client)
    throw Refused{std::string(what) + " attribute '" + attr + "' is not an enabled array in a buffer object"};
  return a->second;
}

// The texture a draw samples and the trace state it is drawn with (the class comment in
// apitrace_import.h); throws Refused for what cannot be proven.
DrawTexture Importer::texture_for_draw(const Program& p, const ProgramForm& pf) const {
  DrawTexture d;
  const FragmentForm& f = pf.fragment;
  if (f.kind == FragmentForm::Kind::Untextured) return d;
  const std::string fs = "fragment shader " + std::to_string(pf.fs);
  if (f.sampler.empty() || f.coord.empty())
    throw Refused{fs + " samples a texture in another form (" + f.reason +
                  ") without one sampler2D and one varying vec2 to import it by"};
  if (!pf.coord.ok)
    throw Refused{"vertex shader " + std::to_string(pf.vs) + "'s texture coordinate '" + f.coord + "': " + pf.coord.reason};
  d.coord = &enabled_array(p, pf.coord.attribute, "texture coordinate");
  if (d.coord->type != "GL_FLOAT") throw Refused{"texture coordinate of type " + d.coord->type + " is not imported"};
  const auto loc = p.uniform_locations.find(f.sampler);
  const auto unit_it = loc == p.uniform_locations.end() ? p.ints.end() : p.ints.find(loc->second);
  const int64_t unit = unit_it == p.ints.end() ? 0 : unit_it->second;  // a sampler never set is unit 0
  const auto b = cur_->tex.bound.find(unit);
  d.id = b == cur_->tex.bound.end() ? 0 : b->second;
  const auto t = cur_->tex.textures.find(d.id);
  const std::string which = "sampler '" + f.sampler + "' (unit " + std::to_string(unit) + ")";
  if (d.id == 0 || t == cur_->tex.textures.end() || t->second.version == 0)
    throw Refused{which + " has no texture image bound"};
  if (d.id > 65535) throw Refused{"texture " + std::to_string(d.id) + " is past the trace's texture IDs (0..65535)"};
  d.tex = &t->second;
  if (!d.tex->unusable.empty()) throw Refused{"texture " + std::to_string(d.id) + ": " + d.tex->unusable};
  if (d.tex->width == 0 || d.tex->height == 0) throw Refused{"texture " + std::to_string(d.id) + " is empty"};
  d.sampler = sampler_state(*d.tex);
  if (!d.sampler.ok) throw Refused{"texture " + std::to_string(d.id) + ": " + d.sampler.why};
  d.on = true;
  if (f.kind == FragmentForm::Kind::Replace) {
    d.env = "replace", d.note = "texenv replace: the fragment shader is a plain texture lookup";
  } else if (f.kind == FragmentForm::Kind::Modulate && pf.colour.ok) {
    d.env = "modulate", d.colour = &enabled_array(p, pf.colour.attribute, "colour");
    d.note = "texenv modulate: the fragment shader is a texture lookup times the varying '" + f.colour +
             "', the attribute '" + pf.colour.attribute + "' passed through";
  } else if (f.kind == FragmentForm::Kind::Modulate) {
    d.env = "modulate";
    d.note = "texenv modulate with the draw's colour in place of the varying '" + f.colour + "' (" + pf.colour.reason + ")";
  } else {
    d.env = opt_.other_texenv;
    d.note = "texenv " + d.env + " stated for a fragment shader of another form (" + f.reason + ")";
  }
  return d;
}

// `texture ID FILE` where the trace's ID does not hold this image yet (its file made once
// a GL texture and version), then the texture state lines that changed.
void Importer::emit_texture(const DrawTexture& d) {
  auto state = [&](const std::string& key, const std::string& line) {
    auto& e = emitted_tex_state_[key];
    if (e != line) emit(e = line);
  };
  if (!d.on) {
    if (!emitted_tex_state_["bind"].empty()) state("bind", "bindtexture none");
    return;
  }
  const auto key = std::make_tuple(static_cast<const Context*>(cur_), d.id, d.tex->version);
  auto f = texture_files_.find(key);
  if (f == texture_files_.end()) {
    const int k = ++files_of_id_[d.id];
    const std::string file = opt_.texture_stem + ".tex" + std::to_string(d.id) + (k > 1 ? "-" + std::to_string(k) : "") + ".png";
    r_.textures.push_back({file, d.tex->width, d.tex->height, d.tex->rgba});
    f = texture_files_.emplace(key, file).first;
  }
  if (emitted_texture_[d.id] != f->second) {
    emit("texture " + std::to_string(d.id) + " " + (emitted_texture_[d.id] = f->second));
    emitted_tex_state_["bind"].clear();  // a new image: bind again
  }
  state("bind", "bindtexture " + std::to_string(d.id));
  state("filter", "texfilter " + d.sampler.filter);
  state("wrap", "texwrap " + d.sampler.wrap_s + " " + d.sampler.wrap_t);
  state("mipmap", std::string("mipmap ") + (d.sampler.mipmap ? "on" : "off"));
  state("env", "texenv " + d.env);
  if (d.sampler.mipmap || !emitted_tex_state_["bias"].empty())
    state("bias", "texlod_bias " + plain_decimal(d.tex->lod_bias));
}

void Importer::emit_vertices(const std::string& mode, const std::vector<ClipV>& verts, bool texcoords) {
  auto v4 = [&](const ClipV& v) {
    return f32(v.x) + " " + f32(v.y) + " " + f32(v.z) + " " + f32(v.w) + " " + std::to_string(v.r) + " " +
           std::to_string(v.g) + " " + std::to_string(v.b) + (texcoords ? " " + f32(v.s) + " " + f32(v.t) : "");
  };
  if (mode == "GL_TRIANGLES") {
    for (size_t k = 0; k + 2 < verts.size(); k += 3) {
      emit("tri4 " + v4(verts[k]) + " " + v4(verts[k + 1]) + " " + v4(verts[k + 2]));
      ++r_.triangles;
    }
  } else if (verts.size() >= 3) {
    emit(mode == "GL_TRIANGLE_STRIP" ? "strip" : "fan");
    for (const ClipV& v : verts) body_ << "v4 " << v4(v) << '\n';
    body_ << "end\n";
    r_.triangles += verts.size() - 2;
  }
}

// The colour attribute of a draw without a modulating varying: one whose name holds
// "color" or "colour" (docs/workloads.md, "Colours").
const Attrib* Importer::named_colour(const Program& p, const ShaderForm& form) const {
  const Attrib* colour = nullptr;
  for (const std::string& a : form.attributes) {
    std::string l = a;
    std::transform(l.begin(), l.end(), l.begin(), [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
    if ((l.find("color") != std::string::npos || l.find("colour") != std::string::npos) && p.attribs.count(a))
      colour = &enabled_array(p, a, "colour");
  }
  return colour;
}

void Importer::draw_checked(const Call& c, const std::string& mode, const std::vector<uint32_t>& indices) {
  const Context& x = *cur_;
  if (mode != "GL_TRIANGLES" && mode != "GL_TRIANGLE_STRIP" && mode != "GL_TRIANGLE_FAN")
    throw Refused{"mode " + mode + " is not imported (triangles, strips and fans are)"};
  if (x.program == 0) throw Refused{"no program is bound (fixed-function drawing is not imported)"};
  if (x.blend) throw Refused{"blending is on (the trace format has no blend state)"};
  const ProgramForm& pf = form_of(x.program);
  const ShaderForm& form = pf.vertex;
  if (!form.ok)
    throw Refused{"program " + std::to_string(x.program) + "'s vertex shader " + std::to_string(pf.vs) +
                  " is not gl_Position = M * vec4(position, 1.0): " + form.reason};
  const std::vector<std::string> cfg = config_for_draw();
  if (r_.config_sets.empty()) r_.config_sets = cfg;
  if (cfg != r_.config_sets) {
    std::string want, have;
    for (size_t k = 0; k < cfg.size(); ++k)
      if (cfg[k] != r_.config_sets[k]) want += " " + cfg[k], have += " " + r_.config_sets[k];
    throw Refused{"it needs" + want + " where the trace's first draw fixed" + have};
  }
  const Program& p = x.programs.at(x.program);
  const Attrib& pos = enabled_array(p, form.position, "position");
  if (pos.type != "GL_FLOAT") throw Refused{"position of type " + pos.type + " is not imported"};
  const DrawTexture tex = texture_for_draw(p, pf);
  const Attrib* colour = tex.colour ? tex.colour : named_colour(p, form);
  const Mat4 m = position_matrix(p, form);
  std::vector<ClipV> verts;
  for (uint32_t i : indices) verts.push_back(vertex(m, pos, colour, tex.coord, i));
  emit_state();
  emit_texture(tex);
  body_ << "# call " << c.number << " " << c.function << " " << mode << ", " << indices.size() << " vertices, "
        << (colour ? "vertex colour" : "flat colour " + std::to_string(opt_.flat_r) + " " + std::to_string(opt_.flat_g) +
                                           " " + std::to_string(opt_.flat_b) + " (no colour attribute)");
  if (tex.on) {
    body_ << "; texture " << tex.id << " (image of call " << tex.tex->image_call << ", " << tex.tex->width << "x"
          << tex.tex->height << "), " << tex.sampler.filter << (tex.sampler.mipmap ? " mipmapped" : "") << ", "
          << tex.note;
    ++r_.draws_textured;
    ++r_.texture_notes[tex.note];
  }
  body_ << '\n';
  emit_vertices(mode, verts, tex.on);
}

// Vertex i: clip-space position through m, converted (the file comment), its colour and
// texture coordinate.
ClipV Importer::vertex(const Mat4& m, const Attrib& pos, const Attrib* colour, const Attrib* coord, uint32_t i) const {
  const auto v = fetch(pos, i, "position");
  double o[4];
  for (int row = 0; row < 4; ++row) o[row] = m[row] * v[0] + m[4 + row] * v[1] + m[8 + row] * v[2] + m[12 + row];
  ClipV cv{static_cast<float>(o[0]), static_cast<float>(-o[1]), static_cast<float>((o[2] + o[3]) / 2),
           static_cast<float>(o[3]), opt_.flat_r, opt_.flat_g, opt_.flat_b};
  if (colour) {
    const auto col = fetch(*colour, i, "colour");
    int* dst[3] = {&cv.r, &cv.g, &cv.b};
    for (int k = 0; k < 3; ++k) {
      const double u = colour->type == "GL_FLOAT" || colour->normalized ? col[static_cast<size_t>(k)] : col[static_cast<size_t>(k)] / 255.0;
      *dst[k] = static_cast<int>(std::lround(std::clamp(u, 0.0, 1.0) * 255.0));
    }
  }
  if (coord) {
    const auto st = fetch(*coord, i, "texture coordinate");  // float: exact binary32 values
    cv.s = static_cast<float>(st[0]), cv.t = static_cast<float>(st[1]);
  }
  return cv;
}

void Importer::call(const Call& c) {
  const std::string& f = c.function;
  if (f == "glXMakeCurrent" || f == "glXMakeContextCurrent" || f == "eglMakeCurrent") {
    const Value* ctx = c.arg("ctx");
    if (ctx && ctx->text != "NULL") cur_ = &contexts_[ctx->text];
  } else if (f == "glXSwapBuffers" || f == "eglSwapBuffers") {
    if (commands_since_frame_ == 0) {
      // A frame whose every draw was refused: the trace format needs a command in it.
      body_ << "# frame " << r_.frames << ": no command imported\n";
      emit("viewport " + std::to_string(width_) + " " + std::to_string(height_));
    }
    body_ << "frame\n";
    commands_since_frame_ = 0;
    ++r_.frames;
  } else if (f == "glDrawArrays" || f == "glDrawElements") {
    if (width_ == 0) fail(c, "a draw before any glViewport (give the framebuffer size)");
    draw(c);
  } else if (!state_call(c) && !object_call(c) && !program_call(c)) {
    texture_call(cur_->tex, c, name_, [&](const Value& v) { return bytes_of(c, v); });
  }
}

ImportResult Importer::finish() {
  if (width_ == 0) throw SceneError(name_ + ": no glViewport in the capture (give the framebuffer size)");
  std::ostringstream out;
  out << "# rastsim trace imported by `rastsim import-apitrace` from " << name_ << "\n"
      << "# " << r_.frames << " frames, " << r_.draws_imported << " draws imported, " << r_.draws_refused
      << " refused, " << r_.draws_textured << " textured, " << r_.triangles << " triangles\n";
  for (const auto& [note, n] : r_.texture_notes) out << "# textured draws, " << n << ": " << note << "\n";
  out << "# config:";
  for (const std::string& s : r_.config_sets) out << " --set " << s;
  out << "\nviewport " << width_ << " " << height_ << "\n" << body_.str();
  r_.trace = out.str();
  return std::move(r_);
}

}  // namespace

ImportResult import_apitrace_dump(const std::string& dump, const std::string& name, const ImportOptions& opt) {
  Importer imp(name, opt);
  int line_no = 0;
  size_t pos = 0;
  while (pos < dump.size()) {
    size_t end = dump.find('\n', pos);
    if (end == std::string::npos) end = dump.size();
    ++line_no;
    if (const auto call = parse_call_line(std::string_view(dump).substr(pos, end - pos), name, line_no))
      imp.call(*call);
    pos = end + 1;
  }
  return imp.finish();
}

void write_trace_file(const std::string& path, const std::string& text) {
  std::string bytes = text;
  if (path.size() > 4 && path.compare(path.size() - 4, 4, ".zst") == 0) {
    // Level 3 with a content checksum, as the zstd tool writes (docs/trace-format.md).
    ZSTD_CCtx* cctx = ZSTD_createCCtx();
    ZSTD_CCtx_setParameter(cctx, ZSTD_c_compressionLevel, 3);
    ZSTD_CCtx_setParameter(cctx, ZSTD_c_checksumFlag, 1);
    bytes.resize(ZSTD_compressBound(text.size()));
    const size_t n = ZSTD_compress2(cctx, bytes.data(), bytes.size(), text.data(), text.size());
    ZSTD_freeCCtx(cctx);
    if (ZSTD_isError(n)) throw SceneError(path + ": zstd: " + ZSTD_getErrorName(n));
    bytes.resize(n);
  }
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out.flush()) throw SceneError(path + ": cannot write");
}

}  // namespace rastsim::apitrace
