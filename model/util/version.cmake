# SPDX-License-Identifier: Apache-2.0
# cmake -DSRC=<source dir> -DIN=version.cpp.in -DOUT=<build>/version.cpp -P version.cmake
# RASTSIM_VERSION = `git describe --always --dirty` of SRC, or "unknown" when git is
# missing or SRC is not the top of a git checkout (an unpacked tarball, even one inside
# another repository). configure_file leaves OUT untouched when its text is unchanged, so
# a build at the same commit and state compiles nothing.
set(RASTSIM_VERSION unknown)
find_program(GIT git)
if(GIT)
  execute_process(COMMAND ${GIT} -C ${SRC} rev-parse --show-toplevel
                  OUTPUT_VARIABLE top OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE rc ERROR_QUIET)
  file(REAL_PATH "${SRC}" src_real)
  if(rc EQUAL 0 AND top)
    file(REAL_PATH "${top}" top_real)
  endif()
  if(rc EQUAL 0 AND top_real STREQUAL src_real)
    execute_process(COMMAND ${GIT} -C ${SRC} describe --always --dirty
                    OUTPUT_VARIABLE v OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE rc ERROR_QUIET)
    if(rc EQUAL 0 AND v)
      set(RASTSIM_VERSION "${v}")
    endif()
  endif()
endif()
configure_file(${IN} ${OUT} @ONLY)
