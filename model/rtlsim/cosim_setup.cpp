// SPDX-License-Identifier: Apache-2.0
// The co-simulation testbench's stimulus and expectation for one run (cosim_setup.h):
// shared by run_cosim (shipped models, in this process) and the on-demand runner
// (rtl_runner_main.cpp, its own process).
#include "rtlsim/cosim_setup.h"

#include <algorithm>
#include <bit>
#include <charconv>
#include <memory>
#include <optional>
#include <set>
#include <stdexcept>

#include "config/timing_params.h"
#include "display/scanout_fetch.h"
#include "rtlsim/tb_binning.h"
#include "rtlsim/testbench.h"
#include "ref/pipeline.h"
#include "ref/prim_assembly.h"
#include "ref/raster_state.h"
#include "ref/tri_setup.h"
#include "ref/coarse_raster.h"
#include "ref/hiz.h"
#include "ref/hiz_entry.h"
#include "ref/interpolate.h"
#include "ref/sample_pattern.h"
#include "ref/texture/texture_unit.h"
#include "config/raster_state_config.h"

namespace rastsim::rtlsim {

namespace {

// rast_top's fill_rule_i / cull_mode_i carry these enums' values (rtl/rast_tri_setup.sv).
static_assert(int(FillRule::TopLeft) == 0 && int(FillRule::BottomRight) == 1 && int(FillRule::Inclusive) == 2 &&
              int(FillRule::Exclusive) == 3);
static_assert(int(CullMode::None) == 0 && int(CullMode::Back) == 1 && int(CullMode::Front) == 2);
// rast_top's texture state and static inputs carry these (rtl/rast_texture_stage.sv).
static_assert(int(TexWrap::Repeat) == 0 && int(TexWrap::Clamp) == 1 && int(TexWrap::Mirror) == 2);
static_assert(int(TexEnv::Replace) == 0 && int(TexEnv::Modulate) == 1 && int(TexEnv::Decal) == 2);
static_assert(int(TexelFormat::Rgba8888) == 0 && int(TexelFormat::Rgb565) == 1 && int(TexelFormat::L8) == 2);
static_assert(int(TexLayout::Linear) == 0 && int(TexLayout::Tiled) == 1 && int(TexLayout::Morton) == 2);

// The scene as the testbench's command stream, and the reference model's fragments for
// the same tile size: the same walk as ref/pipeline.cpp render_scene, one handler per
// command type.
class StreamBuilder {
 public:
  StreamBuilder(const ArchParams& arch, int tile_size, TbSetup& s, const Command* command0)
      : setup_(s), timing_(s.timing), state_(arch.raster), tile_size_(tile_size), command0_(command0) {
    state_.tile_size = tile_size;
    if (hiz_applies(state_)) {
      hiz_.emplace(state_);
      s.hiz_lagged = state_.hiz_sync == HizSync::Lagged;
      // Its spilled entries' accesses, in order (tb_hiz.h checks the RTL's against them).
      hiz_->table.on_access = [this](uint64_t address, uint64_t, bool write) { hiz_access(address, write); };
    }
    if (s.binned) bins_ = std::make_unique<BinProgram>(s, tile_size);
  }

  void add(const Command& cmd) {
    visit_command(cmd, Overloaded{
                           [&](const CmdViewport&) { state_marker(cmd, false); },
                           [&](const CmdClear&) { state_marker(cmd, true); },
                           [&](const CmdClearDepth&) { state_marker(cmd, true); },
                           [&](const CmdScissor&) { state_marker(cmd, false); },
                           [&](const CmdPrimitives& p) { primitives(cmd, p); },
                           [&](const CmdDraw2d& d) { draw2d(cmd, d); },
                       });
  }
  void end_of_frame();
  // depth.early: the reference's kept fragments (render_scene's sink, in the walk's order),
  // against which each fragment the walk makes is marked culled or kept (early_culled).
  void early_kept(const std::vector<Fragment>* kept) { kept_ = kept; }
  size_t early_kept_matched() const { return kept_pos_; }
  // The reference's Hi-Z counts (HizTracker's) into the setup.
  void finish_hiz() {
    setup_.hiz = hiz_.has_value();
    if (!hiz_) return;
    setup_.tiles_culled_hiz = hiz_->table.stats.tiles_culled;
    setup_.tiles_accepted_hiz = hiz_->table.stats.tiles_accepted;
    setup_.hiz_entry_bytes = uint64_t(hiz_->table.entry_bytes());
    setup_.hiz_base = hiz_->table.dram_base;
    setup_.hiz_bytes_read = hiz_->table.stats.bytes_read;
    setup_.hiz_bytes_written = hiz_->table.stats.bytes_written;
    if (hiz_read_) setup_.hiz_test_reads.push_back(*hiz_read_);
  }

 private:
  void state_marker(const Command& cmd, bool clear);
  void draw2d(const Command& cmd, const CmdDraw2d& d2);
  void primitives(const Command& cmd, const CmdPrimitives& prims);
  void clip_space(const Command& cmd, const CmdPrimitives& prims);
  void triangle(const Command& cmd, const CmdPrimitives& prims, size_t k, const ScreenTriangle& verts);
  void texture_state(const Command& cmd, const TextureState& ts, TbItem& it);

  TbSetup& setup_;
  const TimingParams& timing_;
  RasterState state_;  // the state the scene's commands set, as far as the walk has gone
  const int tile_size_;
  const Command* command0_;  // the scene's first command: a command's index is its offset
  Framebuffer fb_{1, 1};  // state commands need one; the testbench ROP keeps no pixels
  TraversalCounters counters_;
  FrontEndStats front_end_;  // the testbench's front end counts here (its steps' costs)
  // Textured triangles: the reference's texture unit (the expected fragments' texture
  // stage and the textures' placement), one triangle's quads, the textures in memory.
  std::optional<TextureUnit> tex_;
  TriangleQuads quads_;
  std::set<const TextureImage*> placed_;
  // Hi-Z (hiz_applies): the zero-lag table rast_top's interlock makes its decisions equal
  // to (ref/hiz.h); a culled tile's fragments are not expected.
  std::optional<HizTracker> hiz_;
  // A spilled entry's access: a read directly followed by the write of its address is a
  // flush's read-modify-write (HizTable::flush), any other read a test's.
  std::optional<uint64_t> hiz_read_;  // the last read, not yet classified
  void hiz_access(uint64_t address, bool write) {
    if (write) {
      if (hiz_read_ != address) throw std::logic_error("Hi-Z: a write-back without its read");
      setup_.hiz_flush_reads.push_back(address);
      setup_.hiz_writes.push_back(address);
      hiz_read_.reset();
      return;
    }
    if (hiz_read_) setup_.hiz_test_reads.push_back(*hiz_read_);
    hiz_read_ = address;
  }
  // depth.hiz_sync = lagged: the culled tile being walked (its fragments expected, flagged:
  // Expected::hiz_tile), -1 none; the culled tiles so far.
  int64_t culled_tile_ = -1;
  int64_t culled_tiles_ = 0;
  size_t culled_first_ = 0;  // its first expected fragment
  std::vector<HizWrite> writes_;  // a drawn tile's depth writes
  // traverse_triangle's tile filter: the tracker's test, then the drawn tile's writes (the
  // ROP's, each pixel's checked in order by the testbench). Lagged, a culled tile is
  // walked too, its fragments flagged as ones the RTL may draw.
  struct HizWalk {
    StreamBuilder* b;
    const SetupTriangle& t;
    bool operator()(const PixelRect& fp, TileClass cls) {
      if (!b->hiz_) return true;
      if (b->hiz_->test(t, fp, cls) == HizDecision::Culled) {
        if (!b->setup_.hiz_lagged) return false;
        b->culled_tile_ = b->culled_tiles_++;
        b->culled_first_ = b->setup_.expected.size();
        return true;
      }
      b->writes_.clear();
      b->hiz_->apply(t, fp, cls, &b->writes_);
      for (const HizWrite& w : b->writes_) b->setup_.depth_writes.push_back({w.x, w.y, w.z});
      return true;
    }
    void done() {
      if (b->culled_tile_ >= 0 && b->setup_.expected.size() == b->culled_first_) ++b->setup_.hiz_culled_empty;
      b->culled_tile_ = -1;
    }
  };
  HizWalk hiz_walk(const SetupTriangle& t) { return HizWalk{this, t}; }
  // depth.early: f (out of interpolation) is one the reference culled early when it is not
  // the next of its kept stream (a subsequence of the walk's fragments, in order).
  const std::vector<Fragment>* kept_ = nullptr;
  size_t kept_pos_ = 0;
  bool early_culled(const Fragment& f) {
    if (!kept_) return false;
    if (kept_pos_ < kept_->size() && (*kept_)[kept_pos_] == f) {
      ++kept_pos_;
      return false;
    }
    return true;
  }
  std::unique_ptr<BinProgram> bins_;  // pipeline.mode = binned: the binner's program (tb_binning.h)
};

// A textured triangle's state on rast_top's tri_tex_* ports, its texture placed as the
// reference places it and its texels stored in the testbench's texture memory at first use
// (the reference's cache fills, in fetch order, recorded for the RTL's to be checked against).
void StreamBuilder::texture_state(const Command& cmd, const TextureState& ts, TbItem& it) {
  if (state_.texture.cache.bytes == 0)
    throw SceneError(cmd.loc.str() + ": texture '" + ts.image->name + "' with texture.cache_bytes = 0: rast_top's "
                     "texture cache (rtl/rast_texture_cache.sv) has no form without a cache; co-simulate with "
                     "texture.cache_bytes > 0 (docs/texture.md \"RTL\")");
  if (!tex_) {
    tex_.emplace(state_.texture);
    tex_->on_fill = [this](uint64_t address, uint64_t) { setup_.texture_fills.push_back(address); };
  }
  const TextureUnit::Resident& r = tex_->resident(ts);
  it.tex_on = true;
  it.tex_bilinear = ts.filter == TexFilter::Bilinear;
  it.tex_trilinear = ts.filter == TexFilter::Trilinear;
  it.tex_levels = ts.mipmap ? int(r.levels.size()) : 1;
  it.tex_bias = ts.lod_bias;
  it.tex_wrap_s = int(ts.wrap_s);
  it.tex_wrap_t = int(ts.wrap_t);
  it.tex_env = int(ts.env);
  it.tex_width = r.levels[0].width;
  it.tex_height = r.levels[0].height;
  it.tex_base = r.level_base[0];
  if (!placed_.insert(ts.image.get()).second) return;
  const TextureParams& p = state_.texture;
  const int bytes = texel_bytes(p.format);
  for (size_t k = 0; k < r.levels.size(); ++k) {
    const MipLevel& l = r.levels[k];
    for (int j = 0; j < l.height; ++j)
      for (int i = 0; i < l.width; ++i) {
        const uint32_t stored = encode_texel(l.texel(i, j), p.format);
        const uint64_t a = r.level_base[k] + texel_offset(p.layout, l.width, l.height, bytes, i, j);
        for (int b = 0; b < bytes; ++b) setup_.texture_memory.set(a + uint64_t(b), uint8_t(stored >> (8 * b)));
      }
  }
}

// A state command travels as a marker: fetched as a header, 1 ROP cycle (a clear: the
// fast clear of the framebuffer).
void StreamBuilder::state_marker(const Command& cmd, bool clear) {
  apply_state_command(cmd, state_, fb_);
  if (hiz_) hiz_->state(cmd);
  TbItem m;
  m.kind = TbItem::Marker;
  m.cmd = &cmd;
  m.fetch_cost = timing_.fetch_cycles_per_command;
  m.rop_cost = clear ? timing_.rop_clear_cycles(uint64_t(state_.fb_width) * uint64_t(state_.fb_height)) : 1;
  setup_.items.push_back(m);
  if (bins_) bins_->state(setup_.items.size() - 1, cmd, state_);  // binned: the binner keeps it
}

// A 2D command: its engine operations for the 2D path, and a marker through the RTL
// that orders them with the triangles at the ROP.
void StreamBuilder::draw2d(const Command& cmd, const CmdDraw2d& d2) {
  TbItem m;
  m.kind = TbItem::Marker;
  m.cmd = &cmd;
  m.fetch_cost = timing_.fetch_draw2d_cycles(draw2d_vertex_count(d2));
  m.work2d = static_cast<int>(setup_.work2d.size());
  TbWork2d w{draw2d_ops(d2, cmd.loc, state_), 0, cmd.loc.str()};
  w.setup_cost = timing_.setup2d_cycles(w.work.ops.size());
  setup_.work2d.push_back(std::move(w));
  setup_.items.push_back(m);
}

// A primitive command: a triangle item each (an empty one: a header-only item),
// fetched as the SystemC model's command fetch costs it (sc/command_fetch.cpp).
void StreamBuilder::primitives(const Command& cmd, const CmdPrimitives& prims) {
  if (prims.clip_space()) {
    clip_space(cmd, prims);
    return;
  }
  size_t k = 0;
  for_each_triangle(prims, state_, cmd.loc, front_end_, [&](const ScreenTriangle& v) { triangle(cmd, prims, k++, v); });
  if (k == 0) {
    TbItem e;
    e.kind = TbItem::Null;
    e.fetch_cost = timing_.fetch_header_cycles();
    setup_.items.push_back(e);
  }
}

// A clip-space command goes through the reference's front end here, in the testbench
// (clipping, the divide by w and the viewport map; docs/rtl.md says why), timed as the
// SystemC model's geometry front end (sc/front_end.cpp): fetched whole, then a step a
// triangle out charged what the front end did since the previous one, and a last step
// for the primitives after the last triangle, ending the command.
void StreamBuilder::clip_space(const Command& cmd, const CmdPrimitives& prims) {
  // The reference rasterizes clip.method = homogeneous without a tile walk (never Hi-Z
  // tested); the testbench clips instead, so rast_top would test those tiles.
  if (hiz_ && state_.clip_method == ClipMethod::Homogeneous)
    throw SceneError(cmd.loc.str() + ": a clip-space command with clip.method = homogeneous and depth.hiz: the "
                     "reference draws it without a tile walk (no Hi-Z test) and rast_top would test its tiles; "
                     "co-simulate with clip.method = clip or depth.hiz = off");
  const size_t job = setup_.items.size();
  TbItem c;
  c.kind = TbItem::ClipCommand;
  c.fetch_cost = timing_.fetch_whole_command_cycles(prims.clip_vertices.size());
  c.first_step = setup_.front_end_steps.size();
  setup_.items.push_back(c);
  FrontEndStats last = front_end_;  // the counters at the last step charged
  size_t k = 0;
  front_end(prims, state_, cmd.loc, front_end_, [&](const ScreenTriangle& v) {
    const uint64_t cycles = timing_.front_end_step_cycles(last, front_end_, true);
    last = front_end_;
    setup_.front_end_steps.push_back(TbFrontEndStep{cycles, int64_t(setup_.items.size())});
    triangle(cmd, prims, k++, v);
    setup_.items.back().from_front_end = true;
  });
  setup_.front_end_steps.push_back(TbFrontEndStep{timing_.front_end_step_cycles(last, front_end_, false), -1});
  setup_.items[job].steps = setup_.front_end_steps.size() - setup_.items[job].first_step;
}

// Triangle k of a primitive command (vertices verts), snapped by the reference's setup, and
// its expected fragments.
void StreamBuilder::triangle(const Command& cmd, const CmdPrimitives& prims, size_t k, const ScreenTriangle& verts) {
  TbItem it;
  const uint64_t new_vertices = (k == 0 || prims.topology == Topology::List) ? 3 : 1;
  it.fetch_cost = timing_.fetch_triangle_cycles(k == 0, new_vertices);
  it.assembly_cost = timing_.assembly_cycles_per_triangle;
  it.tri = static_cast<int>(setup_.tri_names.size());
  setup_.tri_names.push_back(cmd.loc.str() + " triangle " + std::to_string(k));
  setup_.tri_command.push_back(size_t(&cmd - command0_));
  SetupTriangle t;
  const SetupOutcome o = setup_triangle(verts, state_, cmd.loc, t);
  // CulledOutOfRange: nothing the RTL can represent; a zero-area triangle (all vertices
  // 0) costs setup the same.
  if (o != SetupOutcome::CulledOutOfRange) {
    for (int v = 0; v < 3; ++v) {
      it.x[v] = t.x[v];
      it.y[v] = t.y[v];
      it.z[v] = t.z[v];
      const int cw = 8 + t.color_frac_bits;  // a channel: unsigned 8.F
      it.rgb[v] = uint64_t(t.rgb[v][0]) | uint64_t(t.rgb[v][1]) << cw | uint64_t(t.rgb[v][2]) << 2 * cw;
      it.s[v] = t.tex_s[size_t(v)];
      it.t[v] = t.tex_t[size_t(v)];
      it.q[v] = t.persp_q[size_t(v)];
    }
    it.affine = t.affine;
    if (prims.texture.enabled()) texture_state(cmd, prims.texture, it);
    // The RTL builds the newton reciprocal (rtl/rast_recip.sv): a triangle that needs a
    // reciprocal under interp.recip = exact would be compared against another divider.
    if (!t.affine && t.recip != RecipMethod::Newton)
      throw SceneError(cmd.loc.str() + ": a perspective-correct triangle needs the reciprocal unit, and the RTL "
                       "builds interp.recip = \"newton\" (rtl/rast_recip.sv): co-simulate with interp.recip = "
                       "\"newton\" (the default) or interp.perspective = false");
  }
  const PixelRect clip = state_.clip_rect();
  it.clip[0] = clip.x0;
  it.clip[1] = clip.y0;
  it.clip[2] = clip.x1;
  it.clip[3] = clip.y1;
  it.origin[0] = static_cast<int>(state_.origin_x());
  it.origin[1] = static_cast<int>(state_.origin_y());
  setup_.items.push_back(it);
  if (bins_) {  // binned: the binner lists it; its fragments come with the bins' draws
    bins_->triangle(setup_.items.size() - 1, o == SetupOutcome::Accepted ? &t : nullptr, cmd.loc);
    return;
  }
  if (o != SetupOutcome::Accepted) return;
  // Per pixel with a covered sample: its fragment (msaa: one, at the centre, with the
  // mask; one sample: interpolate() with mask 1), as render_scene shades it.
  const int F = state_.coord_format.frac_bits;
  if (!prims.texture.enabled()) {
    traverse_triangle(t, tile_size_, F, counters_, [&](int px, int py, uint32_t m) {
      shade_pixel(t, px, py, m, F,
                  [&](const Fragment& f) { setup_.expected.push_back(Expected{f, it.tri, early_culled(f), culled_tile_}); });
    }, hiz_walk(t));
    return;
  }
  // Textured (ref/pipeline.cpp draw_textured): each fragment through the texture unit with
  // its quad's derivatives; the quads' pixels not covered are helper pixels. A fragment the
  // reference culled early is not textured (its fetches are not the reference's): expected
  // as interpolated.
  quads_.clear();
  const int tex_frac = state_.texcoord_format.frac_bits;
  traverse_triangle(t, tile_size_, F, counters_, [&](int px, int py, uint32_t m) {
    quads_.add_covered(1);
    const QuadDerivatives& d = quads_.derivatives(t, px, py, F);
    shade_pixel(t, px, py, m, F, [&](const Fragment& f) {
      const bool culled = early_culled(f);
      setup_.expected.push_back(
          Expected{culled ? f : tex_->shade(f, d, prims.texture, tex_frac), it.tri, culled, culled_tile_});
    });
  }, hiz_walk(t));
  setup_.helper_pixels += quads_.helper_pixels();
}

// Multisampling: the frame ends with the resolve pass, ordered after every fragment by
// a marker fetched like a command header that travels through the RTL like a state
// command (as the SystemC model's command fetch sends it); the ROP is busy
// resolve_cycles(W H, S) on it.
void StreamBuilder::end_of_frame() {
  if (bins_) {  // binned: fetch sends it at any sample count; it ends the binning pass
    TbItem m;
    m.kind = TbItem::Marker;
    m.fetch_cost = timing_.fetch_header_cycles();
    setup_.items.push_back(m);
    bins_->end_of_frame(setup_.items.size() - 1);
    return;
  }
  if (state_.samples <= 1) return;
  TbItem m;
  m.kind = TbItem::Marker;
  m.fetch_cost = timing_.fetch_header_cycles();
  m.rop_cost = timing_.resolve_cycles(uint64_t(state_.fb_width) * uint64_t(state_.fb_height), state_.samples);
  setup_.items.push_back(m);
}

// kept (depth.early): the reference's kept fragments; returns how many of them the walk's
// fragments matched, in order (all of them, or the early marks are not the reference's).
size_t build(const Scene& scene, const ArchParams& arch, int tile_size, TbSetup& s, const std::vector<Fragment>* kept) {
  StreamBuilder b(arch, tile_size, s, scene.commands.data());
  b.early_kept(kept);
  for (size_t i = 0; i < scene.commands.size(); ++i) {
    const size_t first = s.items.size();
    b.add(scene.commands[i]);
    for (size_t k = first; k < s.items.size(); ++k) s.items[k].command = int64_t(i);
  }
  s.commands = scene.commands.size();
  b.end_of_frame();
  b.finish_hiz();
  return b.early_kept_matched();
}

// pipeline.mode = binned on the RTL (rtl/rast_tile_buffer.sv, docs/rtl.md "Tile buffer"):
// what it does not build yet is refused, naming the key.
void check_binned_cosim(const ArchParams& arch, const CosimOptions& opts) {
  const Config& cfg = arch.config;
  const RasterState& st = arch.raster;
  if (st.bin.mode != PipelineMode::Binned) return;
  if (arch.timing.rop_resolve_bytes_per_cycle % 4 != 0)
    throw ConfigError(cfg.origin("rop.resolve_bytes_per_cycle") + ": rop.resolve_bytes_per_cycle = " +
                      std::to_string(arch.timing.rop_resolve_bytes_per_cycle) + " with pipeline.mode = binned: the "
                      "tile buffer's beat (rtl/rast_tile_buffer.sv) is whole 32-bit words, a multiple of 4 bytes");
  if (opts.initial_fb)
    throw std::runtime_error("pipeline.mode = binned: a range of frames (--frames) has no binned co-simulation "
                             "(the tile buffer starts from the frame's initial value)");
}

}  // namespace

RtlParams cosim_wanted_params(const ArchParams& arch, const CosimOptions& opts) {
  const Config& cfg = arch.config;  // for the keys' names and origins in messages
  // The RTL has the tiled walker only; another method would be compared against the
  // wrong expectation, so stop before building anything.
  if (cfg.get_string("raster.traversal") != "tiled")
    throw ConfigError(cfg.origin("raster.traversal") + ": raster.traversal = " + cfg.get_string("raster.traversal") +
                      " has no RTL; the RTL (rtl/) walks tiles only: co-simulate with raster.traversal = tiled "
                      "(render and simulate run every method)");
  const int tile = opts.tile_size ? opts.tile_size : arch.raster.tile_size;
  if (tile < 2 || !std::has_single_bit(static_cast<unsigned>(tile)))
    throw std::runtime_error("tile size " + std::to_string(tile) + " is not a power of two >= 2");
  const RasterState& st = arch.raster;
  // The RTL interpolator divides the plane-equation numerators (rtl/rast_interpolate.sv):
  // the dda method has no RTL, and comparing against it would only count its error.
  if (st.interp_method != InterpMethod::Plane)
    throw ConfigError(cfg.origin("interp.method") + ": interp.method = \"" + cfg.get_string("interp.method") +
                      "\" has no RTL (the RTL interpolates by plane equations): co-simulate with "
                      "interp.method = \"plane\"");
  // Multisampling: the RTL shades once a pixel (msaa); ssaa (a fragment per sample at the
  // sample's position) has no RTL.
  if (st.samples > 1 && st.aa_mode != AaMode::Msaa)
    throw ConfigError(cfg.origin("raster.aa_mode") + ": raster.aa_mode = " + cfg.get_string("raster.aa_mode") +
                      " has no RTL (the RTL shades once a pixel, at its centre: msaa); co-simulate with "
                      "raster.aa_mode = msaa (render and simulate run ssaa)");
  // Depth culling (docs/depth-culling.md "RTL"): rast_top holds Hi-Z's table, its first
  // entries on chip and the rest through the hiz port (rtl/rast_top_hiz.sv,
  // rast_hiz_spill.sv), at least one on chip. Early Z (rtl/rast_early_z.sv) co-simulates
  // alone (textured or not), immediate mode.
  // Hi-Z that does not apply to this state (hiz_applies: e.g. multisampling) leaves the run
  // exactly the Hi-Z-off one (the shipped models, no table built).
  const bool hiz = hiz_applies(st);
  if (hiz) {
    const int64_t blocks = int64_t((st.fb_width + st.hiz_block - 1) / st.hiz_block) *
                           ((st.fb_height + st.hiz_block - 1) / st.hiz_block);
    const int64_t onchip =
        hiz_onchip_blocks(st.hiz_mode, st.hiz_block, st.hiz_bytes, st.fb_width, st.fb_height, st.depth_bits);
    if (onchip < 1)
      throw ConfigError(cfg.origin("depth.hiz_bytes") + ": depth.hiz_bytes = " + std::to_string(st.hiz_bytes) +
                        " holds none of the display's " + std::to_string(blocks) +
                        " Hi-Z blocks, and the RTL keeps at least one entry on chip: co-simulate with "
                        "depth.hiz_bytes >= " + std::to_string(hiz_entry_bytes(st.hiz_mode, st.hiz_block, st.depth_bits)) +
                        " (render and simulate spill the whole table; docs/depth-culling.md)");
    // depth.hiz_sync = lagged (rast_top_hiz's Lagged) is built for the table on chip only:
    // rast_hiz_spill reads memory as its engine has written it back, its reads waiting
    // under the interlock, while the SystemC rule tests what the ROP has written.
    if (st.hiz_sync == HizSync::Lagged && onchip < blocks)
      throw ConfigError(cfg.origin("depth.hiz_sync") + ": depth.hiz_sync = lagged with spilled Hi-Z entries (" +
                        cfg.origin("depth.hiz_bytes") + ": depth.hiz_bytes = " + std::to_string(st.hiz_bytes) +
                        " holds " + std::to_string(onchip) + " of the display's " + std::to_string(blocks) +
                        " blocks) has no RTL yet (rast_hiz_spill's reads wait under the interlock): co-simulate "
                        "with the table on chip or depth.hiz_sync = interlock (simulate runs both; "
                        "docs/depth-culling.md)");
  }
  if (st.depth_early && (hiz || st.bin.mode == PipelineMode::Binned))
    throw ConfigError(cfg.origin("depth.early") + ": depth.early = true co-simulates without " +
                      (hiz ? "an applied depth.hiz (the RTL's early test does not take Hi-Z's accepts yet)"
                           : "pipeline.mode = binned (the SystemC model refuses it too)") +
                      ": co-simulate one of them (render runs both; docs/depth-culling.md)");
  check_binned_cosim(arch, opts);
  RtlParams wanted = rtl_params(arch);
  if (!hiz) rtl_params_without_hiz(wanted);  // no table used: the model without one (the shipped models') runs it
  wanted.tile_log2_max = std::countr_zero(static_cast<unsigned>(tile));
  wanted.max_samples = st.samples;  // a run-time input up to the built maximum
  return wanted;
}

// depth.early: the expected stream holds every fragment the walk makes, those missing from
// the reference's kept stream (render_scene's sink, the same order) marked as its early
// culls, textured or not (build: a culled one is not textured, as the RTL's texture stage
// skips it). Refused: a run from earlier frames (the early test needs the whole scene).
static void check_early(const ArchParams& arch, const CosimOptions& opts) {
  if (opts.initial_fb)
    throw ConfigError(arch.config.origin("depth.early") +
                      ": depth.early = true co-simulates whole scenes only (--frames from the first frame)");
}

void cosim_setup(const Scene& scene, const ArchParams& arch, const CosimOptions& opts, const RtlParams& model, TbSetup& s,
                 CosimResult& r) {
  s.opts = opts;
  s.opts.progress = {};
  s.params = model;  // the built widths and maximum tile size
  const int tile = opts.tile_size ? opts.tile_size : arch.raster.tile_size;
  s.tile_log2 = std::countr_zero(static_cast<unsigned>(tile));
  // Fill rule, cull mode and front face: run-time inputs, from this config (not the model's).
  const RasterState& st = arch.raster;
  s.samples = st.samples;
  {
    const SamplePattern& pat = sample_pattern(st.samples, st.coord_format.frac_bits);
    for (int k = 0; k < st.samples; ++k) {
      s.sample_dx[size_t(k)] = pat.dx[size_t(k)];
      s.sample_dy[size_t(k)] = pat.dy[size_t(k)];
    }
  }
  s.fill_rule = static_cast<int>(st.fill_rule);
  s.cull_mode = static_cast<int>(st.cull);
  s.front_ccw = st.front_ccw ? 1 : 0;
  s.timing = arch.timing;
  s.arch = st;
  s.arch.tile_size = tile;
  if (opts.initial_fb && !opts.reference_fb)
    throw std::logic_error("cosim_setup: a run from an initial framebuffer needs its reference image");
  // Hi-Z's expected decisions (HizTracker) start from a cleared depth buffer and table, as
  // rast_top's table does; from the frames before a range they would not be the reference's.
  if (opts.initial_fb && hiz_applies(st))
    throw ConfigError(arch.config.origin("depth.hiz") + ": depth.hiz = " + arch.config.get_string("depth.hiz") +
                      " co-simulates whole scenes only (--frames from the first frame): the table would start "
                      "empty after frames that wrote depth");
  RenderStats ref_stats;
  std::vector<Fragment> kept;  // depth.early: the reference's fragments out of its early test
  FragmentSink sink;
  if (st.depth_early) {
    check_early(arch, opts);
    sink = [&kept](const Fragment& f) { kept.push_back(f); };
  }
  s.reference = opts.reference_fb && !st.depth_early ? *opts.reference_fb : render_scene(scene, s.arch, ref_stats, sink);
  s.memory = arch.memory;
  s.dram = arch.dram;
  s.binned = st.bin.mode == PipelineMode::Binned;
  const size_t matched = build(scene, arch, tile, s, st.depth_early ? &kept : nullptr);
  if (st.depth_early) {
    if (matched != kept.size())
      throw std::logic_error("cosim_setup: the reference's kept fragments are not a subsequence of the walk's");
    s.depth_early = true;
    s.fragments_culled_early = ref_stats.fragments_culled_early;
  }
  s.texture = s.arch.texture;

  s.scanout = scanout_params_if_display(arch);
  // Lagged: the reference's own fragments (the culled tiles' the RTL may draw are not).
  r.fragments_expected = uint64_t(std::count_if(s.expected.begin(), s.expected.end(),
                                                [](const Expected& e) { return e.hiz_tile < 0; }));
  for (const TbItem& it : s.items)
    (it.kind == TbItem::Marker ? r.markers : r.triangles) += it.kind == TbItem::Marker || it.kind == TbItem::Triangle;
  r.commands_2d = s.work2d.size();
  if (s.arch.samples > 1 && !s.binned) r.resolve_cycles = s.items.back().rop_cost;
}

// ---- The on-demand runner's request (rtl_runner_main.cpp) ----

namespace {

// A value as the runner's Config takes it back through set_from_string: floats in the
// shortest text that reads back to the same double.
std::string value_text(const ParamValue& v) {
  if (const auto* d = std::get_if<double>(&v)) {
    char buf[64];
    const auto res = std::to_chars(buf, buf + sizeof buf, *d);
    return std::string(buf, res.ptr);
  }
  if (const auto* s = std::get_if<std::string>(&v)) return *s;
  return to_string(v);
}

}  // namespace

nlohmann::json runner_request(const Scene& scene, const ArchParams& arch, const CosimOptions& opts) {
  const Config& cfg = arch.config;  // the runner process resolves the same config again
  nlohmann::json config = nlohmann::json::object();
  for (const auto& [key, v] : cfg.values()) config[key] = {value_text(v), cfg.origin(key)};
  return {{"config", config},
          {"scene", scene.source},
          {"scene_commands", scene.commands.size()},
          {"options", opts}};
}

RunnerRequest read_runner_request(const nlohmann::json& j) {
  RunnerRequest q;
  for (const auto& [key, v] : j.at("config").items())
    q.config.set_from_string(key, v.at(0).get<std::string>(), v.at(1).get<std::string>());
  q.config.validate();
  q.scene = j.at("scene").get<std::string>();
  q.scene_commands = j.at("scene_commands").get<size_t>();
  q.options = j.at("options").get<CosimOptions>();
  return q;
}

}  // namespace rastsim::rtlsim
