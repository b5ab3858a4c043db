# SPDX-License-Identifier: Apache-2.0
# Copyright 2026 The open AN1078 authors
# record.cmake - sim --record on a 0.1 s start: the 16-byte header (tools/sim/sim_record.h:
# magic, version 1, 20 bytes a record, 20 periods a window, 20 kHz), 2,000 records of 20
# bytes, the first taking the START (request bit 2) into CALIBRATE with the outputs off, the
# last in LOCK with them on.
#
#   cmake -DPROG=<sim> -DWORK=<scratch dir> -P record.cmake
foreach(v PROG WORK)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "record.cmake: -D${v}= missing")
  endif()
endforeach()
file(MAKE_DIRECTORY "${WORK}")
file(WRITE "${WORK}/start.txt" "0 start\n0.1 end\n")
file(REMOVE "${WORK}/start.rec")
execute_process(COMMAND "${PROG}" --no-progress --record "${WORK}/start.rec" "${WORK}/start.txt"
                RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "sim --record: exit status ${rc}: ${err}")
endif()
file(SIZE "${WORK}/start.rec" size)
if(NOT size EQUAL 40016)
  message(FATAL_ERROR "record: ${size} bytes, want 16 + 2000 x 20 = 40016")
endif()
file(READ "${WORK}/start.rec" head LIMIT 16 HEX)
if(NOT head STREQUAL "414e313037385231010014001400d007")
  message(FATAL_ERROR "record: header ${head}, want AN1078R1, 1, 20, 20, 2000")
endif()
# a record: u16 requests, i16 ia ib vbus pot, u16 duty[3], u8 outputs_on, u8 0, u16 state
file(READ "${WORK}/start.rec" first OFFSET 16 LIMIT 20 HEX)
string(SUBSTRING "${first}" 0 4 req)
string(SUBSTRING "${first}" 32 8 tail)
if(NOT req STREQUAL "0400" OR NOT tail STREQUAL "00000100")
  message(FATAL_ERROR "record: first period ${first}: want the START (0400) into CALIBRATE, "
                      "outputs off (..00000100)")
endif()
file(READ "${WORK}/start.rec" last OFFSET 39996 LIMIT 20 HEX)
string(SUBSTRING "${last}" 0 4 req)
string(SUBSTRING "${last}" 32 8 tail)
if(NOT req STREQUAL "0000" OR NOT tail STREQUAL "01000200")
  message(FATAL_ERROR "record: last period ${last}: want no request, LOCK, outputs on (..01000200)")
endif()
message(STATUS "record: 2000 periods, header and first/last records as written")
