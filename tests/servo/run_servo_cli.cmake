# SPDX-License-Identifier: GPL-2.0-or-later
# Runs `icgp servo` on a small scenario and checks the summary JSON has every key of the
# machine-readable contract (README / issue: scenario, tracker, trials, ...).
# -DICGP=<program> -DSCENARIO=<yaml> -DOUT=<folder> [-DARGS=<extra arguments, ;-separated>]
# [-DJSON_MATCH=<regular expression summary.json must match>]
# [-DOUTPUT_MATCH=<regular expression the program's output must match>]
# [-DREQUIRES=blender: without a `blender` program, print "skipped: no Blender" and stop]
if(REQUIRES STREQUAL "blender")
  find_program(BLENDER blender)
  if(NOT BLENDER AND NOT DEFINED ENV{ICGP_BLENDER})
    message("skipped: no Blender (scripts/setup --cycles installs it)")
    return()
  endif()
endif()
file(REMOVE_RECURSE "${OUT}")
execute_process(COMMAND "${ICGP}" servo "${SCENARIO}" --out "${OUT}" --summary "${OUT}/summary.json" --quiet ${ARGS}
                RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE errors)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "icgp servo failed (${result}):\n${output}\n${errors}")
endif()
file(READ "${OUT}/summary.json" json)
foreach(key scenario tracker trials converged success_rate final_t_mm final_r_deg median median_track_ms
            steps_per_s safety_stops)
  string(FIND "${json}" "\"${key}\":" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "summary.json has no \"${key}\":\n${json}")
  endif()
endforeach()
if(DEFINED JSON_MATCH AND NOT json MATCHES "${JSON_MATCH}")
  message(FATAL_ERROR "summary.json does not match ${JSON_MATCH}:\n${json}")
endif()
foreach(file log.csv error.png velocity.png)
  if(NOT EXISTS "${OUT}/${file}" AND NOT ARGS MATCHES "--trials")
    message(FATAL_ERROR "icgp servo did not write ${OUT}/${file}")
  endif()
endforeach()
if(DEFINED OUTPUT_MATCH AND NOT "${output}${errors}" MATCHES "${OUTPUT_MATCH}")
  message(FATAL_ERROR "the output does not match ${OUTPUT_MATCH}:\n${output}\n${errors}")
endif()
message("${output}")
