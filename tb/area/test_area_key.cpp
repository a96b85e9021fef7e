// SPDX-License-Identifier: Apache-2.0
// The area cache's per-module keys (model/rtlsim/area.h, area_module_files and
// area_sources_key): a module's entries hash only the RTL text its synthesis reads, so an
// edit to a file it does not reach keeps them and an edit to one it instantiates drops
// them. No Yosys: the instance graph of the sources alone (milliseconds).
#include <gtest/gtest.h>

#include <algorithm>
#include <list>
#include <stdexcept>
#include <string>
#include <vector>

#include "rtlsim/area.h"
#include "rtlsim/rtl_sources.h"

namespace rastsim {
namespace {

// A set of sources whose texts the test owns (RtlSource holds views), sorted by name as
// rtl_sources() is.
struct Sources {
  std::list<std::string> names, texts;
  std::vector<RtlSource> list;

  Sources() = default;
  Sources(Sources&&) = default;  // a list's nodes stay put: the views stay valid
  Sources(const Sources&) = delete;

  void add(const std::string& name, const std::string& text) {
    names.push_back(name);
    texts.push_back(text);
    list.push_back({names.back(), texts.back()});
    std::sort(list.begin(), list.end(), [](const RtlSource& a, const RtlSource& b) { return a.name < b.name; });
  }
  // The same sources with `name`'s text replaced.
  Sources edited(const std::string& name, const std::string& text) const {
    Sources out;
    for (const RtlSource& s : list) out.add(std::string(s.name), s.name == name ? text : std::string(s.text));
    return out;
  }
};

// A hand-made design: top instantiates child (with parameters) and uses package pkg,
// child includes defs.svh; other is instantiated by nobody, and lone's comment and a
// string name child, which instantiate nothing.
Sources toy() {
  Sources s;
  s.add("top.sv", "module top (input wire logic a);\n  localparam int W = pkg::W;\n"
                  "  child #(.W(W)) u_child (.a);\nendmodule\n");
  s.add("child.sv", "`include \"defs.svh\"\nmodule child #(parameter int W = 1) (input wire logic a);\nendmodule\n");
  s.add("pkg.sv", "package pkg;\n  localparam int W = 4;\nendpackage\n");
  s.add("defs.svh", "`define DEFS 1\n");
  s.add("other.sv", "module other (input wire logic a);\nendmodule\n");
  s.add("lone.sv", "module lone;\n  // child u_child (.a);\n  initial $display(\"child u (\");\nendmodule\n");
  return s;
}

TEST(AreaKey, FilesAModuleReads) {
  const Sources s = toy();
  EXPECT_EQ(area_module_files("top", s.list),
            (std::vector<std::string>{"child.sv", "defs.svh", "pkg.sv", "top.sv"}));
  EXPECT_EQ(area_module_files("child", s.list), (std::vector<std::string>{"child.sv", "defs.svh"}));
  EXPECT_EQ(area_module_files("other", s.list), (std::vector<std::string>{"other.sv"}));
  EXPECT_EQ(area_module_files("lone", s.list), (std::vector<std::string>{"lone.sv"}));  // a comment instantiates nothing
  EXPECT_THROW(area_module_files("nowhere", s.list), std::runtime_error);
}

TEST(AreaKey, UnrelatedEditKeepsTheKeyChildEditChangesIt) {
  const Sources s = toy();
  const std::string top = area_sources_key("top", s.list), child = area_sources_key("child", s.list);
  const Sources other_edit = s.edited("other.sv", "module other (input wire logic a, input wire logic b);\nendmodule\n");
  EXPECT_EQ(area_sources_key("top", other_edit.list), top);
  EXPECT_EQ(area_sources_key("child", other_edit.list), child);
  EXPECT_NE(area_sources_key("other", other_edit.list), area_sources_key("other", s.list));
  const Sources child_edit = s.edited("child.sv", "module child #(parameter int W = 2) (input wire logic a);\nendmodule\n");
  EXPECT_NE(area_sources_key("top", child_edit.list), top);
  EXPECT_NE(area_sources_key("child", child_edit.list), child);
  EXPECT_NE(area_sources_key("top", s.edited("pkg.sv", "package pkg;\n  localparam int W = 5;\nendpackage\n").list), top);
  EXPECT_NE(area_sources_key("child", s.edited("defs.svh", "`define DEFS 2\n").list), child);
}

// The shipped RTL: rast_texture_cache does not reach rast_hiz.sv, so an edit there keeps
// its key; rast_top reaches both (through rast_top_hiz and rast_texture_stage's cache),
// and an edit to the fragment FIFO's array changes rast_top's key only. The ROP reaches
// the depth test it instantiates (rast_depth_pass, the early test's too).
TEST(AreaKey, ShippedRtlHizEditKeepsTheTextureCacheKey) {
  Sources s;
  for (const RtlSource& r : rtl_sources()) s.add(std::string(r.name), std::string(r.text));
  const std::vector<std::string> tex = area_module_files("rast_texture_cache", s.list);
  EXPECT_EQ(std::count(tex.begin(), tex.end(), "rast_hiz.sv"), 0);
  const std::vector<std::string> top = area_module_files("rast_top", s.list);
  for (const char* f : {"rast_top.sv", "rast_hiz.sv", "rast_texture_cache.sv", "rast_fragment_fifo_data.sv",
                        "rast_fifo.sv", "rast_rop.sv", "rast_depth_pass.sv"})
    EXPECT_EQ(std::count(top.begin(), top.end(), f), 1) << f;
  EXPECT_EQ(area_module_files("rast_rop", s.list), (std::vector<std::string>{"rast_depth_pass.sv", "rast_rop.sv"}));
  EXPECT_EQ(std::count(top.begin(), top.end(), "rast_engine2d.sv"), 0);
  const auto with_comment = [&](const std::string& file) {
    std::string text;
    for (const RtlSource& r : s.list)
      if (r.name == file) text = std::string(r.text) + "// an edit\n";
    return s.edited(file, text);
  };
  const Sources hiz = with_comment("rast_hiz.sv");
  EXPECT_EQ(area_sources_key("rast_texture_cache", hiz.list), area_sources_key("rast_texture_cache", s.list));
  EXPECT_NE(area_sources_key("rast_top", hiz.list), area_sources_key("rast_top", s.list));
  const Sources ring = with_comment("rast_fragment_fifo_data.sv");
  EXPECT_NE(area_sources_key("rast_top", ring.list), area_sources_key("rast_top", s.list));
  EXPECT_EQ(area_sources_key("rast_interpolate", ring.list), area_sources_key("rast_interpolate", s.list));
  const Sources test = with_comment("rast_depth_pass.sv");
  EXPECT_NE(area_sources_key("rast_rop", test.list), area_sources_key("rast_rop", s.list));
  EXPECT_EQ(area_sources_key("rast_fine_raster", test.list), area_sources_key("rast_fine_raster", s.list));
  // The embedded sources by default.
  EXPECT_EQ(area_sources_key("rast_top"), area_sources_key("rast_top", s.list));
}

}  // namespace
}  // namespace rastsim
