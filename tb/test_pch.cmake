# SPDX-License-Identifier: Apache-2.0
# rastsim_test_pch(TARGET [SYSTEMC]): the test binary TARGET compiles tb/common/test_pch.h
# (GTest and the standard headers; with SYSTEMC, test_pch_sc.h: SystemC and nlohmann/json
# too) once into a precompiled header that every one of its files uses. Worth it for the
# binaries of many files: tb/test_traversal.cpp 13.0 -> 9.5 s of CPU, tb/test_fixed_point.cpp
# 5.8 -> 3.2 s, tb/sc/test_sc_errors.cpp 9.4 -> 6.4 s, for 6-9 s once a binary.
function(rastsim_test_pch target)
  cmake_parse_arguments(PCH "SYSTEMC" "" "" ${ARGN})
  if(PCH_SYSTEMC)
    target_precompile_headers(${target} PRIVATE ${PROJECT_SOURCE_DIR}/tb/common/test_pch_sc.h)
  else()
    target_precompile_headers(${target} PRIVATE ${PROJECT_SOURCE_DIR}/tb/common/test_pch.h)
  endif()
  target_include_directories(${target} PRIVATE ${PROJECT_SOURCE_DIR}/tb)
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    # GCC 12 loses the system-header status of <string> when it arrives through the
    # precompiled header and then reports its known false positive (GCC bug 105651) on
    # std::string operator+ at -O1 (-Warray-bounds, -Wstringop-overflow, -Wrestrict: 19
    # sites, all `std::string(DIR) + "/x"`).
    target_compile_options(${target} PRIVATE -Wno-array-bounds -Wno-stringop-overflow -Wno-restrict)
  endif()
endfunction()
