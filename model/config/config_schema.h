// SPDX-License-Identifier: Apache-2.0
// The parts of the configuration schema (config_schema() in config.h): one function a
// group of keys, each defined in its own config_schema_*.cpp and appended by
// config_schema.cpp in this order. Internal to rastsim_config.
#pragma once

#include <vector>

#include "config/config.h"

namespace rastsim {

// Keys of the triangle traversal method.
void add_traversal_params(std::vector<ParamDef>& schema);  // config_schema_traversal.cpp
// Keys of multisample anti-aliasing (samples, mode, build-time maximum).
void add_aa_params(std::vector<ParamDef>& schema);  // config_schema_aa.cpp
// Keys of OBJ mesh placement (up axis, yaw, pitch, fill).
void add_scene_params(std::vector<ParamDef>& schema);  // config_schema_scene.cpp
// Keys of the timed model (clock, stage latencies/throughputs, FIFO depths).
void add_timing_params(std::vector<ParamDef>& schema);  // config_schema_timing.cpp
// Keys of video timing, the DAC and scan-out.
void add_scanout_params(std::vector<ParamDef>& schema);  // config_schema_scanout.cpp
// Keys of the 2D primitives (lines, polygons).
void add_2d_params(std::vector<ParamDef>& schema);  // config_schema_2d.cpp
// Keys of the attribute interpolation method.
void add_interp_params(std::vector<ParamDef>& schema);  // config_schema_interp.cpp
// Keys of the geometry front end (clip method, guard band).
void add_clip_params(std::vector<ParamDef>& schema);  // config_schema_clip.cpp
// Keys of the DRAM model (memory.preset, dram.*).
void add_dram_params(std::vector<ParamDef>& schema);  // config_schema_dram.cpp
// Keys of the functional memory system (layout, ROP caches, fast clear, compression).
void add_memory_params(std::vector<ParamDef>& schema);  // config_schema_memory.cpp
// Keys of the texture unit (texel format, layout, base address, texture cache).
void add_texture_params(std::vector<ParamDef>& schema);  // config_schema_texture.cpp
void add_binning_params(std::vector<ParamDef>& schema);  // config_schema_binning.cpp
// An integer key's check: a power of two (config_schema.cpp).
bool is_power_of_two(const ParamValue& v);
// An address key's check: a multiple of 4096, a DRAM page (config_schema.cpp).
bool is_page_multiple(const ParamValue& v);
// A string key's check: of form s<I>.<F> (FixedFormat::parse accepts it).
bool is_fixed_format(const ParamValue& v);

}  // namespace rastsim
