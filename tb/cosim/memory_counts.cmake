# SPDX-License-Identifier: Apache-2.0
# ctests cosim.hiz.top.*.memory: `rastsim render --stats` and `rastsim cosim --stats` of one
# scene and config; every key of memory.clients.<client> for each client in CLIENTS (the
# reference's functional counts: accesses, hits, misses, bytes) must be equal. The
# reference's numbers come from render, not from the RTL run, so the check is independent:
# e.g. a Hi-Z accepted tile whose depth the RTL ROP still reads shows as more rop_depth
# accesses than render's (docs/depth-culling.md "RTL").
# KEYS (optional): top-level stats keys that must be equal too (cosim.earlyz.*.memory:
# fragments_culled_early, render's count against the RTL's).
# usage: cmake -DRASTSIM=... -DDIR=... -DCLIENTS=rop_depth,rop_color [-DKEYS=k1,k2] -DARGS=--config,F,--set,K=V,--scene,S
#              -P memory_counts.cmake        (comma-separated: no list escaping through add_test)
string(REPLACE "," ";" CLIENTS "${CLIENTS}")
string(REPLACE "," ";" KEYS "${KEYS}")
string(REPLACE "," ";" ARGS "${ARGS}")
file(MAKE_DIRECTORY ${DIR})
foreach(cmd render cosim)
  execute_process(COMMAND ${RASTSIM} ${cmd} -q ${ARGS} --stats ${DIR}/${cmd}.json
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "rastsim ${cmd} failed (${rc}): ${out}${err}")
  endif()
  file(READ ${DIR}/${cmd}.json ${cmd}_json)
endforeach()
set(bad "")
foreach(key ${KEYS})
  string(JSON want ERROR_VARIABLE jerr GET "${render_json}" ${key})
  string(JSON got ERROR_VARIABLE jerr2 GET "${cosim_json}" ${key})
  if(jerr OR jerr2)
    string(APPEND bad "  ${key}: render ${want}, cosim ${got} (missing)\n")
  elseif(NOT got STREQUAL want)
    string(APPEND bad "  ${key}: render ${want}, cosim ${got}\n")
  else()
    message(STATUS "${key} = ${got} (render's)")
  endif()
endforeach()
foreach(client ${CLIENTS})
  string(JSON obj ERROR_VARIABLE jerr GET "${render_json}" memory clients ${client})
  if(jerr)
    message(FATAL_ERROR "render's stats: memory.clients.${client} missing (memory.model = dram?): ${jerr}")
  endif()
  string(JSON n LENGTH "${obj}")
  math(EXPR last "${n} - 1")
  foreach(i RANGE ${last})
    string(JSON key MEMBER "${obj}" ${i})
    string(JSON want GET "${obj}" ${key})
    string(JSON got ERROR_VARIABLE jerr GET "${cosim_json}" memory clients ${client} ${key})
    if(jerr)
      string(APPEND bad "  memory.clients.${client}.${key}: render ${want}, cosim missing\n")
    elseif(NOT got STREQUAL want)
      string(APPEND bad "  memory.clients.${client}.${key}: render ${want}, cosim ${got}\n")
    else()
      message(STATUS "memory.clients.${client}.${key} = ${got} (render's)")
    endif()
  endforeach()
endforeach()
if(bad)
  message(FATAL_ERROR "cosim's counts differ from render's:\n${bad}")
endif()
