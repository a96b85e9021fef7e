// SPDX-License-Identifier: Apache-2.0
// llvmpipe 4x multisampling through OSMesa: FBO set-up, OR-mask passes, per-sample
// read-back through texelFetch, and a resolve for cross-checking.
#include "osmesa_msaa.h"

#include <GL/osmesa.h>
#include <GL/glext.h>

#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace rastsim::mesa {
namespace {

// The GL entry points past 1.3, looked up through OSMesaGetProcAddress (libOSMesa does
// not export every one of them).
struct GlFns {
  PFNGLGENFRAMEBUFFERSPROC GenFramebuffers;
  PFNGLDELETEFRAMEBUFFERSPROC DeleteFramebuffers;
  PFNGLBINDFRAMEBUFFERPROC BindFramebuffer;
  PFNGLFRAMEBUFFERTEXTURE2DPROC FramebufferTexture2D;
  PFNGLFRAMEBUFFERRENDERBUFFERPROC FramebufferRenderbuffer;
  PFNGLCHECKFRAMEBUFFERSTATUSPROC CheckFramebufferStatus;
  PFNGLGENRENDERBUFFERSPROC GenRenderbuffers;
  PFNGLDELETERENDERBUFFERSPROC DeleteRenderbuffers;
  PFNGLBINDRENDERBUFFERPROC BindRenderbuffer;
  PFNGLRENDERBUFFERSTORAGEPROC RenderbufferStorage;
  PFNGLTEXIMAGE2DMULTISAMPLEPROC TexImage2DMultisample;
  PFNGLGETMULTISAMPLEFVPROC GetMultisamplefv;
  PFNGLBLITFRAMEBUFFERPROC BlitFramebuffer;
  PFNGLCREATESHADERPROC CreateShader;
  PFNGLSHADERSOURCEPROC ShaderSource;
  PFNGLCOMPILESHADERPROC CompileShader;
  PFNGLGETSHADERIVPROC GetShaderiv;
  PFNGLGETSHADERINFOLOGPROC GetShaderInfoLog;
  PFNGLDELETESHADERPROC DeleteShader;
  PFNGLCREATEPROGRAMPROC CreateProgram;
  PFNGLATTACHSHADERPROC AttachShader;
  PFNGLLINKPROGRAMPROC LinkProgram;
  PFNGLGETPROGRAMIVPROC GetProgramiv;
  PFNGLDELETEPROGRAMPROC DeleteProgram;
  PFNGLUSEPROGRAMPROC UseProgram;
  PFNGLGETUNIFORMLOCATIONPROC GetUniformLocation;
  PFNGLUNIFORM1IPROC Uniform1i;
};

template <class F>
void load(F& f, const char* name) {
  f = reinterpret_cast<F>(OSMesaGetProcAddress(name));
  if (!f) throw std::runtime_error(std::string("OSMesa: no ") + name);
}

const GlFns& gl() {
  static const GlFns fns = [] {
    GlFns f{};
    load(f.GenFramebuffers, "glGenFramebuffers");
    load(f.DeleteFramebuffers, "glDeleteFramebuffers");
    load(f.BindFramebuffer, "glBindFramebuffer");
    load(f.FramebufferTexture2D, "glFramebufferTexture2D");
    load(f.FramebufferRenderbuffer, "glFramebufferRenderbuffer");
    load(f.CheckFramebufferStatus, "glCheckFramebufferStatus");
    load(f.GenRenderbuffers, "glGenRenderbuffers");
    load(f.DeleteRenderbuffers, "glDeleteRenderbuffers");
    load(f.BindRenderbuffer, "glBindRenderbuffer");
    load(f.RenderbufferStorage, "glRenderbufferStorage");
    load(f.TexImage2DMultisample, "glTexImage2DMultisample");
    load(f.GetMultisamplefv, "glGetMultisamplefv");
    load(f.BlitFramebuffer, "glBlitFramebuffer");
    load(f.CreateShader, "glCreateShader");
    load(f.ShaderSource, "glShaderSource");
    load(f.CompileShader, "glCompileShader");
    load(f.GetShaderiv, "glGetShaderiv");
    load(f.GetShaderInfoLog, "glGetShaderInfoLog");
    load(f.DeleteShader, "glDeleteShader");
    load(f.CreateProgram, "glCreateProgram");
    load(f.AttachShader, "glAttachShader");
    load(f.LinkProgram, "glLinkProgram");
    load(f.GetProgramiv, "glGetProgramiv");
    load(f.DeleteProgram, "glDeleteProgram");
    load(f.UseProgram, "glUseProgram");
    load(f.GetUniformLocation, "glGetUniformLocation");
    load(f.Uniform1i, "glUniform1i");
    return f;
  }();
  return fns;
}

// Copies sample `s` of the multisample texture to the pixel under the fragment: unorm8
// -> float -> unorm8 is exact for every value.
const char* kVertexShader =
    "#version 150 compatibility\n"
    "void main() { gl_Position = gl_Vertex; }\n";
const char* kFragmentShader =
    "#version 150\n"
    "uniform sampler2DMS ms;\n"
    "uniform int s;\n"
    "out vec4 colour;\n"
    "void main() { colour = texelFetch(ms, ivec2(gl_FragCoord.xy), s); }\n";

GLuint compile(GLenum type, const char* src) {
  const GlFns& g = gl();
  const GLuint sh = g.CreateShader(type);
  g.ShaderSource(sh, 1, &src, nullptr);
  g.CompileShader(sh);
  GLint ok = 0;
  g.GetShaderiv(sh, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[1024] = {};
    g.GetShaderInfoLog(sh, sizeof log, nullptr, log);
    throw std::runtime_error(std::string("sample-copy shader: ") + log);
  }
  return sh;
}

}  // namespace

OsMesaMsaa::OsMesaMsaa(int width, int height) : width_(width), height_(height), window_(16 * 16) {
  OSMesaContext ctx = static_cast<OSMesaContext>(create_llvmpipe_context());
  ctx_ = ctx;
  make_current();
  const GlFns& g = gl();

  // The 4x colour buffer: a multisample texture (so that its samples can be fetched).
  glGenTextures(1, &ms_tex_);
  glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, ms_tex_);
  g.TexImage2DMultisample(GL_TEXTURE_2D_MULTISAMPLE, kMsaaSamples, GL_RGBA8, width, height, GL_TRUE);
  g.GenFramebuffers(1, &ms_fbo_);
  g.BindFramebuffer(GL_FRAMEBUFFER, ms_fbo_);
  g.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D_MULTISAMPLE, ms_tex_, 0);
  if (g.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw std::runtime_error("4x framebuffer incomplete");
  glGetIntegerv(GL_SAMPLES, &samples_);

  // The one-sample buffer samples are copied (or resolved) into for read-back.
  g.GenRenderbuffers(1, &ss_rb_);
  g.BindRenderbuffer(GL_RENDERBUFFER, ss_rb_);
  g.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
  g.GenFramebuffers(1, &ss_fbo_);
  g.BindFramebuffer(GL_FRAMEBUFFER, ss_fbo_);
  g.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, ss_rb_);
  if (g.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw std::runtime_error("one-sample framebuffer incomplete");

  const GLuint vs = compile(GL_VERTEX_SHADER, kVertexShader), fs = compile(GL_FRAGMENT_SHADER, kFragmentShader);
  program_ = g.CreateProgram();
  g.AttachShader(program_, vs);
  g.AttachShader(program_, fs);
  g.LinkProgram(program_);
  g.DeleteShader(vs);
  g.DeleteShader(fs);
  GLint linked = 0;
  g.GetProgramiv(program_, GL_LINK_STATUS, &linked);
  if (!linked) throw std::runtime_error("sample-copy program does not link");
  g.UseProgram(program_);
  g.Uniform1i(g.GetUniformLocation(program_, "ms"), 0);  // texture unit 0
  sample_uniform_ = g.GetUniformLocation(program_, "s");
  g.UseProgram(0);

  // Drawing state, as OsMesaRenderer but for an FBO: default (lower-left) clip origin,
  // so gallium keeps its top-left rule; multisampling on.
  set_coverage_state(true);
  if (glGetError() != GL_NO_ERROR) throw std::runtime_error("OpenGL error during 4x set-up");
}

OsMesaMsaa::~OsMesaMsaa() {
  make_current();
  const GlFns& g = gl();
  g.DeleteProgram(program_);
  g.DeleteFramebuffers(1, &ss_fbo_);
  g.DeleteFramebuffers(1, &ms_fbo_);
  g.DeleteRenderbuffers(1, &ss_rb_);
  glDeleteTextures(1, &ms_tex_);
  OSMesaDestroyContext(static_cast<OSMesaContext>(ctx_));
}

void OsMesaMsaa::make_current() {
  // A process may hold an OsMesaRenderer too: every entry point makes this one current.
  if (!OSMesaMakeCurrent(static_cast<OSMesaContext>(ctx_), window_.data(), GL_UNSIGNED_BYTE, 16, 16))
    throw std::runtime_error("OSMesaMakeCurrent failed");
}

std::string OsMesaMsaa::renderer_name() {
  make_current();
  return reinterpret_cast<const char*>(glGetString(GL_RENDERER));
}

std::array<std::array<float, 2>, kMsaaSamples> OsMesaMsaa::sample_positions() {
  make_current();
  gl().BindFramebuffer(GL_FRAMEBUFFER, ms_fbo_);
  std::array<std::array<float, 2>, kMsaaSamples> pos{};
  for (int s = 0; s < kMsaaSamples; ++s) gl().GetMultisamplefv(GL_SAMPLE_POSITION, GLuint(s), pos[size_t(s)].data());
  if (glGetError() != GL_NO_ERROR) throw std::runtime_error("OpenGL error reading sample positions");
  return pos;
}

void OsMesaMsaa::draw(const std::vector<GridTri>& tris, bool colour_bits) {
  const GlFns& g = gl();
  g.BindFramebuffer(GL_FRAMEBUFFER, ms_fbo_);
  g.UseProgram(0);
  // Gallium row = (ndc_y + 1) P/2 + vy = ndc_y P/2 with vy = -P/2 (FBO: no flip).
  glViewport(-kViewport / 2, -kViewport / 2, kViewport, kViewport);
  if (colour_bits) glEnable(GL_COLOR_LOGIC_OP);
  else glDisable(GL_COLOR_LOGIC_OP);
  glClear(GL_COLOR_BUFFER_BIT);
  draw_triangles(tris, colour_bits);
  glDisable(GL_COLOR_LOGIC_OP);
}

std::array<std::vector<uint32_t>, kMsaaSamples> OsMesaMsaa::sample_masks(const std::vector<GridTri>& tris) {
  if (tris.size() > size_t(kMaxTrisPerPass)) throw std::invalid_argument("more than 32 triangles in one pass");
  make_current();
  const GlFns& g = gl();
  draw(tris, true);
  // Copy each sample into the one-sample buffer with a full-viewport quad, read it back.
  g.BindFramebuffer(GL_FRAMEBUFFER, ss_fbo_);
  glViewport(0, 0, width_, height_);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, ms_tex_);
  g.UseProgram(program_);
  std::array<std::vector<uint32_t>, kMsaaSamples> out;
  for (int s = 0; s < kMsaaSamples; ++s) {
    g.Uniform1i(sample_uniform_, s);
    glRectf(-1.0f, -1.0f, 1.0f, 1.0f);
    out[size_t(s)].resize(size_t(width_) * size_t(height_));
    // FBO row 0 is gallium's row 0, the scene's row 0: no flip.
    glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, out[size_t(s)].data());
  }
  g.UseProgram(0);
  if (glGetError() != GL_NO_ERROR) throw std::runtime_error("OpenGL error in a 4x pass");
  return out;
}

std::vector<uint8_t> OsMesaMsaa::resolved_counts(const GridTri& tri) {
  make_current();
  const GlFns& g = gl();
  draw({tri}, false);
  g.BindFramebuffer(GL_READ_FRAMEBUFFER, ms_fbo_);
  g.BindFramebuffer(GL_DRAW_FRAMEBUFFER, ss_fbo_);
  g.BlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  g.BindFramebuffer(GL_FRAMEBUFFER, ss_fbo_);
  std::vector<uint8_t> red(size_t(width_) * size_t(height_));
  glReadPixels(0, 0, width_, height_, GL_RED, GL_UNSIGNED_BYTE, red.data());
  if (glGetError() != GL_NO_ERROR) throw std::runtime_error("OpenGL error in a resolve");
  // The resolve averages the 4 samples: v = 255 k / 4, rounded; k = round(4 v / 255).
  for (uint8_t& v : red) v = uint8_t(std::lround(4.0 * v / 255.0));
  return red;
}

}  // namespace rastsim::mesa
