# SPDX-License-Identifier: GPL-2.0-or-later
# Runs `icgp bench --sweep --quick` twice and checks the table header, the JSON rows (every
# tracker of every quick cell, with the keys of the contract), the plot, and that the second
# run reuses the cached sequences instead of rendering them again.
# -DICGP=<program> -DOUT=<folder> -DVIEWPOINT_MODELS=<yaml>
file(REMOVE_RECURSE "${OUT}")
set(args bench --sweep --quick --frames 6 --out "${OUT}" --summary "${OUT}/summary.json" --plot "${OUT}/sweep.png"
         --viewpoint-models "${VIEWPOINT_MODELS}")
foreach(run first second)
  execute_process(COMMAND "${ICGP}" ${args} RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE errors)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "icgp bench --sweep failed (${result}) on the ${run} run:\n${output}\n${errors}")
  endif()
  set(${run}_errors "${errors}")
endforeach()
if(NOT first_errors MATCHES "sweep: rendering" OR second_errors MATCHES "sweep: rendering")
  message(FATAL_ERROR "the second run should reuse the sequences the first rendered:\n${first_errors}\n---\n${second_errors}")
endif()
if(NOT second_errors MATCHES "sweep: 3/3 cells .*ETA")
  message(FATAL_ERROR "no progress with an ETA on stderr:\n${second_errors}")
endif()

foreach(pattern "model +depth +image +tracker +mean mm +max mm +mean deg +max deg +ADD +ADD-S +lost +median ms"
                "lost = frames the tracker reported lost" "or whose error exceeded 50 mm or 30 deg"
                "textured_box +exact +sharp +icgp defaults " "textured_box +none +grey antialiased +ViSP edge \\+ KLT")
  if(NOT output MATCHES "${pattern}")
    message(FATAL_ERROR "the table has no '${pattern}':\n${output}")
  endif()
endforeach()

file(READ "${OUT}/summary.json" json)
string(JSON rows LENGTH "${json}" rows)
# Quick cells: exact/sharp and kinect/motion-blurred (icgp defaults, its region + depth,
# icg_reference, ViSP) and the grey cell (two icgp and two ViSP rows).
if(NOT rows EQUAL 12)
  message(FATAL_ERROR "expected 12 rows, got ${rows}:\n${json}")
endif()
math(EXPR last "${rows} - 1")
foreach(i RANGE ${last})
  foreach(key model depth image tracker lost frames mean_t_mm max_t_mm mean_r_deg max_r_deg add_auc adds_auc median_ms)
    string(JSON value ERROR_VARIABLE missing GET "${json}" rows ${i} ${key})
    if(missing)
      message(FATAL_ERROR "row ${i} has no \"${key}\": ${missing}")
    endif()
  endforeach()
  string(JSON frames GET "${json}" rows ${i} frames)
  if(NOT frames EQUAL 6)
    message(FATAL_ERROR "row ${i} tracked ${frames} frames, not 6")
  endif()
endforeach()
string(JSON tracker GET "${json}" rows 0 tracker)
string(JSON t_mm GET "${json}" rows 0 mean_t_mm)
if(NOT tracker STREQUAL "icgp defaults" OR t_mm GREATER 5)
  message(FATAL_ERROR "icgp defaults on exact, sharp frames of the textured box: ${t_mm} mm (${tracker})")
endif()
if(NOT EXISTS "${OUT}/sweep.png")
  message(FATAL_ERROR "no plot ${OUT}/sweep.png")
endif()
message("${output}")
