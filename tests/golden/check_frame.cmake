# One golden-frame test (docs/physics.md §10, golden/README.md), run by CTest as `cmake -P`:
# renders a frame through `particles render`, exactly as users do, and compares it with its golden
# frame through `particles compare`.
#
#   -DPARTICLES=…/particles  -DSCENARIO=scenarios/x.yaml  -DAT=T  -DGOLDEN=golden/x_tT.png
#   -DOUT_DIR=<build>/golden  -DNAME=<file stem of the outputs, unique per test>
#   -DRENDER_OPTIONS=--size|320x240   options of golden/frames.txt, '|'-separated
#   -DEXTRA=--set|forces[2].ks=420    more render options (a perturbation), '|'-separated; optional
#   -DCOMPARE_OPTIONS=--max-share|0.0005  options of `particles compare`, '|'-separated; optional
#   -DEXPECT=match|differ             match (default): the frame must pass the comparison;
#                                     differ: it must fail it (the test can see the perturbation)
#
# Lists come '|'-separated because add_test would split ';' into separate arguments.
# The actual frame is OUT_DIR/NAME.png and the diff picture OUT_DIR/NAME.diff.png. A failing test
# keeps both and prints their paths; a passing EXPECT=match test removes them; a passing
# EXPECT=differ test keeps them (they show what the comparison sees of the perturbation).
cmake_minimum_required(VERSION 3.22)

foreach(var PARTICLES SCENARIO AT GOLDEN OUT_DIR NAME)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "check_frame.cmake: -D${var}=… is required")
  endif()
endforeach()
if(NOT DEFINED EXPECT OR EXPECT STREQUAL "")
  set(EXPECT match)
endif()
if(NOT EXPECT MATCHES "^(match|differ)$")
  message(FATAL_ERROR "check_frame.cmake: EXPECT must be match or differ, not '${EXPECT}'")
endif()
string(REPLACE "|" ";" render_options "${RENDER_OPTIONS}")
string(REPLACE "|" ";" extra "${EXTRA}")
string(REPLACE "|" ";" compare_options "${COMPARE_OPTIONS}")

if(NOT EXISTS "${GOLDEN}")
  message(FATAL_ERROR "no golden frame ${GOLDEN}: render it with scripts/update-golden")
endif()
file(MAKE_DIRECTORY "${OUT_DIR}")
set(actual "${OUT_DIR}/${NAME}.png")
set(diff "${OUT_DIR}/${NAME}.diff.png")
file(REMOVE "${actual}" "${diff}")

set(render_command "${PARTICLES}" render "${SCENARIO}" -o "${actual}" --at "${AT}" ${render_options} ${extra} --quiet)
execute_process(COMMAND ${render_command} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
list(JOIN render_command " " shown)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "render failed (exit ${code}):\n  ${shown}\n${out}${err}")
endif()

set(compare_command "${PARTICLES}" compare "${GOLDEN}" "${actual}" --diff "${diff}" ${compare_options})
execute_process(COMMAND ${compare_command} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
list(JOIN compare_command " " compared)

if(EXPECT STREQUAL "match")
  if(code EQUAL 0)
    message(STATUS "${out}")
    file(REMOVE "${actual}" "${diff}")
    return()
  endif()
  if(code EQUAL 1)
    message(NOTICE
      "the frame differs from its golden frame.\n"
      "${out}"
      "  golden: ${GOLDEN}\n"
      "  actual: ${actual}\n"
      "  diff:   ${diff}\n"
      "rendered with: ${shown}\n"
      "If the change is intended, re-render the golden frames with scripts/update-golden and review them.")
    message(FATAL_ERROR "${NAME}: the frame differs from ${GOLDEN}")
  endif()
  message(FATAL_ERROR "compare failed (exit ${code}):\n  ${compared}\n${out}${err}")
else()
  if(code EQUAL 1)
    # The frame and its diff stay: they show what the golden test sees of the perturbation.
    message(STATUS "the perturbed frame fails the comparison, as it must:\n${out}")
    return()
  endif()
  if(code EQUAL 0)
    message(NOTICE
      "the perturbed frame PASSES the comparison: the golden test cannot see this change.\n"
      "${out}"
      "  golden: ${GOLDEN}\n"
      "  actual: ${actual}\n"
      "  diff:   ${diff}\n"
      "rendered with: ${shown}")
    message(FATAL_ERROR "${NAME}: the perturbed frame matches ${GOLDEN}")
  endif()
  message(FATAL_ERROR "compare failed (exit ${code}):\n  ${compared}\n${out}${err}")
endif()
