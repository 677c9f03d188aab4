# SPDX-License-Identifier: GPL-2.0-or-later
# Renders a tiny stereo sequence with `icgp make-sequence --stereo-baseline` and runs
# `icgp stereo` on it: exit 0, both rows of the table, the ratio line, progress on stderr and
# the JSON summary's two rows.
# -DICGP=<program> -DMODEL=<mesh> -DOUT=<folder> -DVIEWPOINT_MODELS=<yaml>
file(REMOVE_RECURSE "${OUT}")
execute_process(COMMAND "${ICGP}" make-sequence "${MODEL}" --out "${OUT}/sequence" --frames 5 --width 160 --height 120
                        --focal 150 --stereo-baseline 0.06 --color-noise 2 --antialias 4
                RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE errors)
if(NOT result EQUAL 0 OR NOT output MATCHES "wrote 5 frames of '[^']+' \\(stereo\\)")
  message(FATAL_ERROR "icgp make-sequence --stereo-baseline failed (${result}):\n${output}\n${errors}")
endif()
if(NOT EXISTS "${OUT}/sequence/color2/000004.png")
  message(FATAL_ERROR "make-sequence --stereo-baseline wrote no color2/000004.png")
endif()

execute_process(COMMAND "${ICGP}" stereo --sequence "${OUT}/sequence" --config "${VIEWPOINT_MODELS}"
                        --summary "${OUT}/summary.json"
                RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE errors)
message("${output}")
if(NOT result EQUAL 0)
  message(FATAL_ERROR "icgp stereo failed (${result}):\n${output}\n${errors}")
endif()
set(number "[0-9]+\\.[0-9]+")
foreach(pattern "configuration +mean mm +max mm +mean deg +max deg +\\|x\\| mm +\\|y\\| mm +\\|z\\| mm +median ms +Hz +lost"
                "one camera \\(Camera1\\) +${number} +${number} +${number} +${number}"
                "two cameras \\(stereo, 60 mm\\) +${number} +${number} +${number} +${number}"
                "mean error one camera / two cameras: translation ${number}x, rotation ${number}x")
  if(NOT output MATCHES "${pattern}")
    message(FATAL_ERROR "the output has no '${pattern}':\n${output}\n${errors}")
  endif()
endforeach()
if(NOT errors MATCHES "two cameras \\(stereo, 60 mm\\): frame 5/5, [0-9.]+ s, about 0 s left")
  message(FATAL_ERROR "no progress with the time left on stderr:\n${errors}")
endif()

file(READ "${OUT}/summary.json" json)
string(JSON rows LENGTH "${json}" rows)
if(NOT rows EQUAL 2)
  message(FATAL_ERROR "expected 2 rows, got ${rows}:\n${json}")
endif()
foreach(i 0 1)
  string(JSON frames GET "${json}" rows ${i} frames)
  string(JSON cameras GET "${json}" rows ${i} cameras)
  math(EXPR expected_cameras "${i} + 1")
  if(NOT frames EQUAL 5 OR NOT cameras EQUAL expected_cameras)
    message(FATAL_ERROR "row ${i}: ${frames} frames, ${cameras} cameras:\n${json}")
  endif()
endforeach()
message("icgp stereo smoke test passed")
