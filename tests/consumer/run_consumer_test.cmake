# SPDX-License-Identifier: GPL-2.0-or-later
# Installs the built project into a scratch prefix, then configures, builds and runs the
# consumer project against it. Variables: BUILD_DIR, SOURCE_DIR, WORK_DIR.
# The consumer is built with the compiler and flags the project was configured with, so a
# sanitized build (scripts/test --sanitize) checks a sanitized consumer: linking the
# instrumented icgp libraries needs the sanitizer runtimes, and the run is checked too.
file(REMOVE_RECURSE "${WORK_DIR}")
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "consumer test step failed (${result}): ${ARGN}")
  endif()
endfunction()
load_cache("${BUILD_DIR}" READ_WITH_PREFIX PROJECT_ CMAKE_CXX_COMPILER CMAKE_CXX_FLAGS)
run(${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${WORK_DIR}/prefix")
run(${CMAKE_COMMAND} -S "${SOURCE_DIR}" -B "${WORK_DIR}/build" -DCMAKE_BUILD_TYPE=Release
    "-DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix" "-DCMAKE_CXX_COMPILER=${PROJECT_CMAKE_CXX_COMPILER}"
    "-DCMAKE_CXX_FLAGS=${PROJECT_CMAKE_CXX_FLAGS}")
run(${CMAKE_COMMAND} --build "${WORK_DIR}/build")
run("${WORK_DIR}/build/icgp_consumer")
