# SPDX-License-Identifier: Apache-2.0
# Copyright 2026 The open AN1078 authors
# refuses.cmake - runs a simulator program (sim, robust) on one bad input and checks that it is
# refused the way docs/sim.md promises: exit status 2, nothing on stdout, exactly one line on
# stderr, matching EXPECT (which names the field, and FILE:LINE for a scenario file).
#
#   cmake -DPROG=<exe> -DWORK=<scratch dir> -DARGS=<args, '|'-separated> -DEXPECT=<regex>
#         [-DLINE=<scenario line>] [-DRC=1] -P refuses.cmake
#
# RC=1 is a run stopped part way (the plant diverged): exit status 1 and the one line on
# stderr, with the summary of the run so far allowed on stdout.
#
# In ARGS, @SCEN@ is a scenario written to WORK: "0 start", LINE, "4 end" (line 2 is the bad
# one); @GOOD@ is the shipped run_1000 scenario; @KEEP@ is a file holding "keep" that must
# still hold it afterwards (a refused run never truncates a trace it was asked to write).
foreach(v PROG WORK ARGS EXPECT SRC)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "refuses.cmake: -D${v}= missing")
  endif()
endforeach()

if(NOT DEFINED RC)
  set(RC 2)
endif()

file(MAKE_DIRECTORY "${WORK}")
set(scen "${WORK}/bad.txt")
set(keep "${WORK}/keep.csv")
if(DEFINED LINE)
  file(WRITE "${scen}" "0 start\n${LINE}\n4 end\n")
endif()
file(WRITE "${keep}" "keep\n")

string(REPLACE "|" ";" args "${ARGS}")
string(REPLACE "@SCEN@" "${scen}" args "${args}")
string(REPLACE "@GOOD@" "${SRC}/tools/sim/scenarios/run_1000.txt" args "${args}")
string(REPLACE "@KEEP@" "${keep}" args "${args}")

# 60 s: every refusal comes before the first simulated period; a hang (the
# old --substeps 1000000) is a failure, not a wait.
execute_process(COMMAND "${PROG}" ${args}
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 60)

set(fail "")
if(NOT rc STREQUAL "${RC}")
  string(APPEND fail "exit status '${rc}', want ${RC}; ")
endif()
if(RC STREQUAL "2" AND NOT out STREQUAL "")
  string(APPEND fail "stdout not empty; ")
endif()
string(REGEX MATCHALL "\n" nl "${err}")
list(LENGTH nl n_lines)
if(NOT n_lines EQUAL 1 OR NOT err MATCHES "\n$")
  string(APPEND fail "stderr has ${n_lines} line breaks, want exactly one line; ")
endif()
if(NOT err MATCHES "${EXPECT}")
  string(APPEND fail "stderr does not match '${EXPECT}'; ")
endif()
file(READ "${keep}" kept)
if(NOT kept STREQUAL "keep\n")
  string(APPEND fail "the file given to --csv was overwritten; ")
endif()

message("args: ${args}")
message("stderr: ${err}")
if(NOT fail STREQUAL "")
  message(FATAL_ERROR "FAIL: ${fail}")
endif()
message("PASS: refused in one line, exit status ${RC}")
