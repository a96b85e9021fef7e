# SPDX-License-Identifier: Apache-2.0
# How the raster pipeline is verilated: its source lists and its Verilator arguments,
# written once. Two users include this file:
# - rtl/CMakeLists.txt, for the shipped configs (RAST_RTL_CONFIGS) at configure time;
# - the small project `rastsim cosim` writes into its cache when no shipped model fits a
#   config (model/rtlsim/rtl_cache.cpp): the text of this file is compiled into rastsim
#   (model/rtlsim/CMakeLists.txt, embed_rtl.cmake) and written out beside the RTL sources, so
#   an on-demand model is verilated exactly as a shipped one.

# rast_rtl_files(DIR <top> <engine> <waivers>): the sources under DIR (rtl/ or the cache
# project's copy): rast_top with its stages (the 2D units stand alone), the 2D engine
# with its units, and the lint waivers (lint/rast_*.vlt).
function(rast_rtl_files dir top_var engine_var waiver_var)
  file(GLOB top CONFIGURE_DEPENDS ${dir}/rast_*.sv)
  list(FILTER top EXCLUDE REGEX "/(rast_line|rast_rop3|rast_pattern|rast_engine2d)\\.sv$")
  file(GLOB waivers CONFIGURE_DEPENDS ${dir}/lint/rast_*.vlt)
  set(${top_var} ${top} PARENT_SCOPE)
  set(${engine_var} ${dir}/rast_engine2d.sv ${dir}/rast_line.sv ${dir}/rast_pattern.sv ${dir}/rast_rop3.sv
      PARENT_SCOPE)
  set(${waiver_var} ${waivers} PARENT_SCOPE)
endfunction()

# Lint-clean (-Wall) and fast: X values resolved at verilation, not simulated.
set(RAST_VERILATOR_ARGS -Wall -O3 --x-assign fast --x-initial fast)

# The C++ compiler's options for the generated code, in every build type:
# - -g0: no debug info (Vrast_desktop__Trace__0.cpp compiles in 11 s without it and
#   142 s with it, measured on 2 cores; CI builds every model);
# - -O3 (the default RelWithDebInfo is -O2): 1.06-1.14x faster models (desktop and
#   d3d11, scripts/bench_rtl; docs/results.md "RTL simulation speed", round 3).
set(RAST_VERILATED_CXX_OPTIONS -Wno-unused-parameter -g0 -O3)
# ... except the code Verilator marks slow (its *__Slow.cpp and *__Syms.cpp: constructors,
# the initial settle and the trace set-up, run once a simulation), at -O0: a third of the
# models' compile CPU at -O3 (283 of 624 s in a full build), and Vrast_desktop__Trace__0__Slow.cpp
# alone 16.1 s at -O3, 4.8 s at -O0. verilate(... OPT_SLOW) puts it after the target's -O3.
set(RAST_VERILATED_SLOW_OPTIONS -O0)

# rast_top built with the parameter header INC_DIR/rast_params.vh into TARGET as class PREFIX
# (further arguments: more Verilator arguments, e.g. -DRAST_DIVIDER_STEPS).
function(rast_verilate_top target prefix inc_dir sources waivers)
  verilate(${target} SOURCES ${waivers} ${sources} PREFIX ${prefix} TOP_MODULE rast_top TRACE_FST
    OPT_SLOW ${RAST_VERILATED_SLOW_OPTIONS}
    VERILATOR_ARGS -I${inc_dir} ${RAST_VERILATOR_ARGS} ${ARGN})
endfunction()

# The 2D engine (no config parameter: its timing keys are run-time inputs) as Vrast_engine2d.
function(rast_verilate_engine2d target sources)
  verilate(${target} SOURCES ${sources} PREFIX Vrast_engine2d TOP_MODULE rast_engine2d TRACE_FST
    OPT_SLOW ${RAST_VERILATED_SLOW_OPTIONS}
    VERILATOR_ARGS ${RAST_VERILATOR_ARGS})
endfunction()
