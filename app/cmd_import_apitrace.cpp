// SPDX-License-Identifier: Apache-2.0
// `rastsim import-apitrace TRACE.trace -o OUT.trace[.zst]`: an apitrace capture of an
// OpenGL program into a rastsim trace (scene/apitrace_import.h, docs/workloads.md). Runs
// Debian's `apitrace dump --blobs --multiline=no` in a temporary directory (the buffer and
// texture data land there as blob_callN.bin files) and converts its text.

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "common.h"
#include "image/image_io.h"
#include "scene/apitrace_import.h"
#include "util/process.h"

namespace rastsim::app {

namespace {

struct ImportOptions {
  std::string trace_path, out_path, dump_path, config_out, size;
  std::vector<int> flat{255, 255, 255};
  std::string other_texenv = "modulate";
  int show = 10;
  bool quiet = false;
};

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  if (!in) throw std::runtime_error(p.string() + ": cannot open");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The output's name without its directory and its .zst / .gz and .trace suffixes: the
// texture files' prefix ("out/build.rs.trace.zst" -> "build.rs").
std::string output_stem(const std::string& out) {
  std::string s = std::filesystem::path(out).filename().string();
  for (const char* suf : {".zst", ".gz", ".trace"})
    if (s.size() > std::strlen(suf) && s.compare(s.size() - std::strlen(suf), std::strlen(suf), suf) == 0)
      s.resize(s.size() - std::strlen(suf));
  return s;
}

// Each texture image beside the trace, as PNG (RGBA8, rows in GL's order: the first row
// is t = 0, docs/workloads.md "Textures").
void write_textures(const std::vector<apitrace::TextureFile>& files, const std::string& out) {
  const std::filesystem::path dir = std::filesystem::path(out).parent_path();
  for (const apitrace::TextureFile& t : files) {
    Framebuffer fb(t.width, t.height);
    for (int y = 0; y < t.height; ++y) fb.write_row(y, t.rgba.data() + size_t(y) * size_t(t.width) * 4);
    write_image(fb, (dir / t.file).string());
  }
}

// `apitrace dump` of the capture into dir/dump.txt (its blobs beside it), run through
// util/process.h (an argv, no shell).
std::filesystem::path run_apitrace_dump(const std::string& trace, const std::filesystem::path& dir) {
  const std::string abs = std::filesystem::absolute(trace).string();
  if (!std::filesystem::is_regular_file(abs)) throw std::runtime_error(trace + ": cannot open");
  ProcessOptions po;
  po.cwd = dir.string();
  po.out = Sink::File, po.out_path = (dir / "dump.txt").string();
  po.err = Sink::Capture;
  const ProcessResult r = run_process(
      {"apitrace", "dump", "--blobs", "--multiline=no", "--color=never", "--arg-names=yes", abs}, po);
  if (!r.ok()) {
    std::string err = r.err;
    while (!err.empty() && err.back() == '\n') err.pop_back();
    const int status = exit_code(r.status);
    throw std::runtime_error(trace + ": `apitrace dump` failed (" +
                             (status == 127 ? std::string("apitrace not found: Debian's apitrace package")
                                            : "exit status " + std::to_string(status) + ": not an apitrace capture?") +
                             ")" + (err.empty() ? "" : ": " + err));
  }
  return dir / "dump.txt";
}

void run_import(const ImportOptions& o) {
  apitrace::ImportOptions opt;
  if (!o.size.empty()) {
    if (std::sscanf(o.size.c_str(), "%dx%d", &opt.width, &opt.height) != 2 || opt.width < 1 || opt.height < 1 ||
        opt.width > 16384 || opt.height > 16384)
      throw std::runtime_error("--size '" + o.size + "': expected WxH, 1..16384 each");
  }
  opt.flat_r = o.flat[0], opt.flat_g = o.flat[1], opt.flat_b = o.flat[2];
  opt.texture_stem = output_stem(o.out_path);
  opt.other_texenv = o.other_texenv;
  std::filesystem::path tmp, dump = o.dump_path;
  if (dump.empty()) {
    std::string templ = (std::filesystem::temp_directory_path() / "rastsim-apitrace-XXXXXX").string();
    if (!mkdtemp(templ.data())) throw std::runtime_error("cannot make a temporary directory");
    tmp = templ;
  }
  struct Cleanup {
    std::filesystem::path p;
    ~Cleanup() {
      std::error_code ec;
      if (!p.empty()) std::filesystem::remove_all(p, ec);
    }
  } cleanup{tmp};
  if (dump.empty()) dump = run_apitrace_dump(o.trace_path, tmp);
  const std::filesystem::path blobs = dump.parent_path();
  opt.read_blob = [&](const std::string& name) {
    if (name.find('/') != std::string::npos) throw std::runtime_error("not a plain file name");
    return slurp(blobs / name);
  };
  // Errors name the line of the dump text (the capture itself is binary): "a.trace dump:58: call 2485 ...".
  const std::string name = o.dump_path.empty() ? o.trace_path + " dump" : o.dump_path;
  const apitrace::ImportResult r = apitrace::import_apitrace_dump(slurp(dump), name, opt);
  int shown = 0;
  for (const std::string& m : r.refusals)
    if (shown++ < o.show) std::cerr << m << "\n";
  if (static_cast<int>(r.refusals.size()) > o.show)
    std::cerr << "(and " << r.refusals.size() - static_cast<size_t>(o.show) << " more refusals)\n";
  if (r.draws_imported == 0)
    throw std::runtime_error(name + ": no draw imported (" + std::to_string(r.draws_refused) + " refused)");
  write_textures(r.textures, o.out_path);
  apitrace::write_trace_file(o.out_path, r.trace);
  std::string sets;
  for (const std::string& s : r.config_sets) sets += s + "\n";
  if (!o.config_out.empty()) {
    std::ofstream c(o.config_out);
    if (!(c << sets)) throw std::runtime_error(o.config_out + ": cannot write");
  }
  if (!o.quiet)
    std::cout << "import-apitrace: " << name << " -> " << o.out_path << ": " << r.frames << " frames, " << r.draws
              << " draws (" << r.draws_imported << " imported, " << r.draws_refused << " refused), "
              << r.clears_refused << " clears refused, " << r.draws_textured << " textured ("
              << r.textures.size() << " texture files), " << r.triangles << " triangles; config:"
              << [&] {
                   std::string s;
                   for (const std::string& c : r.config_sets) s += " --set " + c;
                   return s;
                 }()
              << "\n";
  if (!o.quiet)
    for (const auto& [note, n] : r.texture_notes) std::cout << "import-apitrace: " << n << " textured draws: " << note << "\n";
}

}  // namespace

void register_import_apitrace(CLI::App& app) {
  auto* cmd = app.add_subcommand("import-apitrace",
                                 "Convert an apitrace capture of an OpenGL program into a rastsim trace: clip-space "
                                 "vertices from vertex shaders of the form gl_Position = M * vec4(position, 1.0), "
                                 "one `frame` a glXSwapBuffers (docs/workloads.md)");
  static ImportOptions o;
  cmd->add_option("trace", o.trace_path, "The capture (.trace), read through `apitrace dump` (Debian's apitrace)");
  cmd->add_option("-o,--output", o.out_path, "The rastsim trace to write (.trace, or .trace.zst zstd-compressed)")
      ->required();
  cmd->add_option("--dump", o.dump_path,
                  "Read this `apitrace dump --blobs --multiline=no` text instead of running apitrace (its blob files "
                  "beside it)");
  cmd->add_option("--size", o.size, "Framebuffer WxH (default: the capture's first glViewport, the window)");
  cmd->add_option("--flat-color", o.flat, "R G B (0..255) of draws without a vertex colour attribute")
      ->expected(3)->check(CLI::Range(0, 255));
  cmd->add_option("--other-texenv", o.other_texenv,
                  "texenv of a textured draw whose fragment shader is neither a plain texture lookup nor one times a "
                  "varying colour (default modulate; stated in the trace)")
      ->check(CLI::IsMember({"replace", "modulate", "decal"}));
  cmd->add_option("--config-out", o.config_out,
                  "Write the config the trace needs (depth test, culling), one KEY=VALUE a line, for --set");
  cmd->add_option("--show-refusals", o.show, "Print at most this many refusal messages (default 10)");
  add_quiet_flag(cmd, o.quiet, "the summary line");
  cmd->callback([] {
    if (o.trace_path.empty() == o.dump_path.empty())
      throw CLI::ValidationError("import-apitrace", "give exactly one of: a capture, --dump");
    run_import(o);
  });
}

}  // namespace rastsim::app
