# SPDX-License-Identifier: GPL-2.0-or-later
# docs/architecture.md shows the example cue that tests/unit/test_tracker_loop.cpp compiles:
# fails when the page's copy is not the header, character for character.
#   cmake -DDOC=<page> -DHEADER=<header> -P check_example_in_docs.cmake
file(READ ${DOC} doc)
file(READ ${HEADER} header)
string(FIND "${doc}" "```cpp\n${header}```" position)
if(position EQUAL -1)
  message(FATAL_ERROR "${DOC} does not show ${HEADER} as it is; copy the header into its cpp block")
endif()
message(STATUS "${DOC} shows ${HEADER} as compiled")
