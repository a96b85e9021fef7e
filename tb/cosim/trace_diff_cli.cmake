# SPDX-License-Identifier: Apache-2.0
# ctest cosim.trace_diff.cli: `rastsim cosim --trace-diff DIR --stats` on the shipped torus;
# both CSVs exist with the header and the same number of rows, the stats have every
# stage's figures, and the command names the outcome (identical or first difference).
# usage: cmake -DRASTSIM=... -DSOURCE=... -DDIR=... -P trace_diff_cli.cmake
file(REMOVE_RECURSE ${DIR})
execute_process(COMMAND ${RASTSIM} cosim --config ${SOURCE}/configs/default.toml --scene ${SOURCE}/traces/torus.trace
                        --trace-diff ${DIR} --stats ${DIR}/stats.json
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "rastsim cosim failed (${rc}): ${out}${err}")
endif()
foreach(side model rtl)
  if(NOT EXISTS ${DIR}/${side}.csv)
    message(FATAL_ERROR "${DIR}/${side}.csv was not written")
  endif()
  file(STRINGS ${DIR}/${side}.csv rows_${side})
  list(GET rows_${side} 0 header)
  if(NOT header STREQUAL "stage,transaction,start_cycle,end_cycle")
    message(FATAL_ERROR "${DIR}/${side}.csv:1: header is '${header}'")
  endif()
  list(LENGTH rows_${side} n_${side})
endforeach()
if(NOT n_model EQUAL n_rtl OR n_model LESS 1000)
  message(FATAL_ERROR "row counts: model.csv ${n_model}, rtl.csv ${n_rtl} (equal and over 1000 expected)")
endif()
if(NOT out MATCHES "trace-diff .*(identical|first difference: [a-z_]+ transaction [0-9]+)")
  message(FATAL_ERROR "no trace-diff verdict in the output:\n${out}")
endif()
file(READ ${DIR}/stats.json stats)
foreach(stage command_fetch prim_assembly tri_setup coarse_raster fine_raster interpolate rop draw2d_setup engine2d)
  foreach(key busy_rtl busy_model stalled_rtl stalled_model starved_rtl starved_model)
    string(JSON v ERROR_VARIABLE jerr GET "${stats}" stages ${stage} ${key})
    if(jerr)
      message(FATAL_ERROR "stats.json: stages.${stage}.${key} missing: ${jerr}")
    endif()
  endforeach()
endforeach()
