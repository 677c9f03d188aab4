# SPDX-License-Identifier: GPL-2.0-or-later
# Runs a command and checks how it ends: its exit status AND a match of its output (stdout
# and stderr), and that it ends at all. CTest's PASS_REGULAR_EXPRESSION alone ignores the
# exit status: a program that printed the expected line and then failed would pass.
# cmake -DSTATUS=<expected exit status> -DPATTERN=<regex> [-DTIMEOUT=<seconds, default 300>]
#       -P expect_outcome.cmake -- <program> <arguments>...
if(NOT DEFINED TIMEOUT)
  set(TIMEOUT 300)
endif()
# The command: every argument after the first "--".
set(COMMAND)
set(in_command FALSE)
math(EXPR last "${CMAKE_ARGC} - 1")
foreach(i RANGE 1 ${last})
  if(in_command)
    list(APPEND COMMAND "${CMAKE_ARGV${i}}")
  elseif(CMAKE_ARGV${i} STREQUAL "--")
    set(in_command TRUE)
  endif()
endforeach()
if(NOT COMMAND)
  message(FATAL_ERROR "expect_outcome.cmake: no command after --")
endif()
execute_process(COMMAND ${COMMAND} RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE errors
                TIMEOUT ${TIMEOUT})
string(REPLACE ";" " " command_line "${COMMAND}")
if(NOT "${result}" STREQUAL "${STATUS}")
  message(FATAL_ERROR "${command_line}: exit status ${result}, expected ${STATUS}:\n${output}\n${errors}")
endif()
if(NOT "${output}${errors}" MATCHES "${PATTERN}")
  message(FATAL_ERROR "${command_line}: the output does not match '${PATTERN}':\n${output}\n${errors}")
endif()
message("exit status ${result}\n${output}${errors}")
