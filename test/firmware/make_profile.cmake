# SPDX-License-Identifier: Apache-2.0
# Copyright 2026 The open AN1078 authors
# make_profile.cmake - every make goal that takes BOARD/MOTOR refuses a name
# with no profile header, in one line naming it, before anything runs
# (cmake -P, from CTest).
#
#   -DMAKE=<GNU make> -DSRC=<repo root> -DGOALS=<goal,goal,...>
#   -DVAR=<BOARD|MOTOR> -DVALUE=<name>
#   -DEXPECT_OK=1   the name exists: every goal must get past the check
#
# make runs with -n, so a goal that did get past the check only prints its
# commands; MAKEFLAGS from a calling make (its jobserver) is dropped, so that
# the only output is make's own.
string(REPLACE "," ";" goals "${GOALS}")
set(failed "")
foreach(goal IN LISTS goals)
  execute_process(
    COMMAND ${CMAKE_COMMAND} -E env --unset=MAKEFLAGS --unset=MFLAGS --unset=MAKELEVEL
            ${MAKE} -n --no-print-directory -C ${SRC} ${VAR}=${VALUE} ${goal}
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  string(STRIP "${out}" out)
  if(EXPECT_OK)
    if(NOT rc EQUAL 0 OR out MATCHES ": no (firmware/motors|boards)/")
      string(APPEND failed "\n  make ${VAR}=${VALUE} ${goal}: refused (rc ${rc}): ${out}")
    endif()
    continue()
  endif()
  string(FIND "${out}" "\n" nl)
  if(rc EQUAL 0)
    string(APPEND failed "\n  make ${VAR}=${VALUE} ${goal}: accepted")
  elseif(NOT nl EQUAL -1)
    string(APPEND failed "\n  make ${VAR}=${VALUE} ${goal}: more than one line:\n${out}")
  elseif(NOT out MATCHES "${VAR}=${VALUE}: no (firmware/motors|boards)/")
    string(APPEND failed "\n  make ${VAR}=${VALUE} ${goal}: does not name ${VAR}=${VALUE}: ${out}")
  endif()
endforeach()
if(failed)
  message(FATAL_ERROR "${failed}")
endif()
message(STATUS "${VAR}=${VALUE}: as expected for ${GOALS}")
