# SPDX-License-Identifier: Apache-2.0
# Copyright 2026 The open AN1078 authors
# params_compile.cmake - compiles params_probe.c with one UserParms.h / profile
# value changed and judges the compiler's answer (cmake -P, from CTest).
#
#   -DCC=<compiler> -DSRC=<repo root> -DPROBE=<params_probe.c>
#   -DDEF=<NAME=value> (optional) -DPROFILE=<board>[/<motor>] (optional)
#   -DSTD=<c99|c11> (default c99)
#   -DHAL=1 (optional) the HAL's include paths (PROBE a HAL source)
#   -DEXPECT=<name>  the build must fail and the FIRST line reporting an error
#                    must name <name> (as a word, or inside a check's
#                    bit-field name such as NAME__out_of_range_for__OTHER);
#                    clang's "not an integer constant expression" names it in
#                    the source line it prints right under
#   -DANYWHERE=1     with EXPECT: <stdio.h> and <stdlib.h> included first (a
#                    call to remove() or system() is then valid C), and any
#                    line of the output may name <name>
#   -DEXPECT=        (empty) the build must succeed with -Wall -Wextra -Werror
#
# The first error line is what a user reads: a check that names the value
# only in a later error, or names only a value derived from it, fails here.
if(NOT STD)
  set(STD c99)
endif()
set(args -std=${STD} -fsyntax-only -Wall -Wextra -Werror
         -I${SRC}/firmware -I${SRC}/foc -I${SRC}/smc_estimator)
if(PROFILE)
  string(REPLACE "/" ";" prof "${PROFILE}")
  list(GET prof 0 board)
  string(TOUPPER "${board}" board)
  list(APPEND args -DMC_BOARD_${board})
  list(LENGTH prof n)
  if(n GREATER 1)
    list(GET prof 1 motor)
    list(APPEND args "-DMC_MOTOR_HEADER=\"motors/motor_${motor}.h\"")
  endif()
endif()
if(HAL)
  # the dsPIC HAL's own checks, against the SFR stand-in
  list(APPEND args -I${SRC}/test/support/sfr -I${SRC}/test/support -I${SRC}/hal
       -I${SRC}/hal/dspic33f)
endif()
if(DEF)
  list(APPEND args "-D${DEF}")
endif()
if(ANYWHERE)
  # the C library declared, as in the simulator's files: a call then compiles unless a check stops it
  list(APPEND args -include stdio.h -include stdlib.h)
endif()
execute_process(COMMAND ${CC} ${args} ${PROBE}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)

if(NOT EXPECT)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${DEF} ${PROFILE}: refused, should compile:\n${out}")
  endif()
  message(STATUS "${DEF} ${PROFILE}: compiles")
  return()
endif()

if(rc EQUAL 0)
  message(FATAL_ERROR "${DEF} ${PROFILE}: compiles, should be refused naming ${EXPECT}")
endif()
string(REGEX MATCH "[^\n]*error:[^\n]*" first "${out}")
# clang names a value that is not a constant in the source line it prints under the error
string(REGEX MATCH "[^\n]*error:[^\n]*\n[^\n]*" first_shown "${out}")
if(ANYWHERE)
  if(NOT out MATCHES "(^|[^A-Za-z0-9_]|__)${EXPECT}($|[^A-Za-z0-9_]|__)")
    message(FATAL_ERROR "${DEF} ${PROFILE}: refused, but nothing names ${EXPECT}:\n${out}")
  endif()
  message(STATUS "${DEF} ${PROFILE}: refused: ${first}")
  return()
endif()
if(NOT first MATCHES "(^|[^A-Za-z0-9_]|__)${EXPECT}($|[^A-Za-z0-9_]|__)" AND
   NOT (first MATCHES "not an integer constant expression" AND
        first_shown MATCHES "(^|[^A-Za-z0-9_]|__)${EXPECT}($|[^A-Za-z0-9_]|__)"))
  message(FATAL_ERROR "${DEF} ${PROFILE}: refused, but the first error does not name ${EXPECT}:\n"
                      "  ${first}\nwhole output:\n${out}")
endif()
message(STATUS "${DEF} ${PROFILE}: refused: ${first}")
