# SPDX-License-Identifier: GPL-2.0-or-later
# Runs `icgp ARGS` and checks how it ends: its exit status, a line of its output, and that
# it ends at all (a refused size must not start the work it would size).
# -DICGP=<program> -DSTATUS=<expected exit status> -DPATTERN=<regex> -DARGS=<arguments, ;-separated>
execute_process(COMMAND "${ICGP}" ${ARGS} RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE errors
                TIMEOUT 120)
if(NOT "${result}" STREQUAL "${STATUS}")
  message(FATAL_ERROR "icgp ${ARGS}: exit status ${result}, expected ${STATUS}:\n${output}\n${errors}")
endif()
if(NOT "${output}${errors}" MATCHES "${PATTERN}")
  message(FATAL_ERROR "icgp ${ARGS}: the output does not match '${PATTERN}':\n${output}\n${errors}")
endif()
message("exit status ${result}\n${output}${errors}")
