# SPDX-License-Identifier: Apache-2.0
# Copyright 2026 The open AN1078 authors
# make_bootstrap.cmake - every make goal that needs a tool or a library runs
# tools/bootstrap before anything else, so it works from a fresh clone (a
# `make unit` without .venv used to leave the Python tests "Not Run")
# (cmake -P, from CTest).
#
#   -DMAKE=<GNU make> -DSRC=<repo root> -DGOALS=<goal,goal,...>
#
# make runs with -n: the first command a goal would run must be
# tools/bootstrap. MAKEFLAGS from a calling make is dropped.
if(NOT MAKE)
  message(STATUS "no GNU make: skipped")
  return()
endif()
string(REPLACE "," ";" goals "${GOALS}")
set(failed "")
foreach(goal IN LISTS goals)
  execute_process(
    COMMAND ${CMAKE_COMMAND} -E env --unset=MAKEFLAGS --unset=MFLAGS --unset=MAKELEVEL
            ${MAKE} -n --no-print-directory -C ${SRC} ${goal}
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(REGEX MATCH "^[^\n]*" first "${out}")
  if(NOT rc EQUAL 0)
    string(APPEND failed "\n  make -n ${goal}: exit ${rc}: ${err}")
  elseif(NOT first MATCHES "tools/bootstrap")
    string(APPEND failed "\n  make ${goal}: its first command is not tools/bootstrap: ${first}")
  endif()
endforeach()
if(failed)
  message(FATAL_ERROR "${failed}")
endif()
message(STATUS "every goal bootstraps first: ${GOALS}")
