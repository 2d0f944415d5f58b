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
#   -DTEST_NAME=golden:x_tT:egl       the CTest name, for the report; optional (default NAME)
#   -DGOLDEN_COMMAND=ON               the render is the golden frame's own command (golden/frames.txt)
#                                     up to the GL backend and thread count, so its actual frame may
#                                     replace the golden (scripts/update-golden --from); default OFF
#
# Lists come '|'-separated because add_test would split ';' into separate arguments.
# The actual frame is OUT_DIR/NAME.png and the diff picture OUT_DIR/NAME.diff.png. A failing test
# keeps both, copies the golden frame beside them as OUT_DIR/NAME.expected.png (so that OUT_DIR,
# downloaded as a CI artefact, holds all three) and prints their paths; a passing EXPECT=match test
# removes them; a passing EXPECT=differ test keeps the frame and its diff (they show what the
# comparison sees of the perturbation).
#
# Every run leaves its result in OUT_DIR/results/NAME.txt, one `key=value` a line (a backslash
# and a line break in a value written as \\ and \n), for the report (write_report.py) and
# `scripts/update-golden --from`. It is written first with outcome=unfinished, so a test that CTest
# stops (timeout) still shows in the report, and replaced as a whole (temporary name, then rename).
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
if(NOT DEFINED TEST_NAME OR TEST_NAME STREQUAL "")
  set(TEST_NAME "${NAME}")
endif()
string(REPLACE "|" ";" render_options "${RENDER_OPTIONS}")
string(REPLACE "|" ";" extra "${EXTRA}")
string(REPLACE "|" ";" compare_options "${COMPARE_OPTIONS}")

file(MAKE_DIRECTORY "${OUT_DIR}/results")
set(actual "${OUT_DIR}/${NAME}.png")
set(diff "${OUT_DIR}/${NAME}.diff.png")
set(expected "${OUT_DIR}/${NAME}.expected.png")
set(result_file "${OUT_DIR}/results/${NAME}.txt")
set(report "${OUT_DIR}/report.html")
file(REMOVE "${actual}" "${diff}" "${expected}" "${result_file}")

# The commands as someone at the top of the source tree would type them: paths inside it relative,
# words the shell would split or expand in single quotes.
get_filename_component(source_dir "${CMAKE_CURRENT_LIST_DIR}/../.." ABSOLUTE)
function(shown_command out)
  set(words "")
  foreach(word IN LISTS ARGN)
    if(IS_ABSOLUTE "${word}")
      file(RELATIVE_PATH relative "${source_dir}" "${word}")
      if(NOT relative MATCHES "^\\.\\./")
        set(word "${relative}")
      endif()
    endif()
    if(NOT word MATCHES "^[A-Za-z0-9_./:=+,@%-]+$")
      string(REPLACE "'" "'\\''" word "${word}")
      set(word "'${word}'")
    endif()
    list(APPEND words "${word}")
  endforeach()
  list(JOIN words " " joined)
  set(${out} "${joined}" PARENT_SCOPE)
endfunction()

# add_result(VAR KEY VALUE): appends the line KEY=VALUE to the text in VAR, VALUE escaped.
# (Text, not a CMake list: values hold ';', which a list would split.)
function(add_result var key value)
  string(REPLACE "\\" "\\\\" value "${value}")
  string(REPLACE "\n" "\\n" value "${value}")
  set(${var} "${${var}}${key}=${value}\n" PARENT_SCOPE)
endfunction()

# write_result(OUTCOME [LINES]): the result file: what every test has, its outcome, then LINES
# (made by add_result).
function(write_result outcome)
  set(text "${facts}")
  add_result(text outcome "${outcome}")
  file(WRITE "${result_file}.partial" "${text}${ARGN}")
  file(RENAME "${result_file}.partial" "${result_file}")
endfunction()

get_filename_component(frame "${GOLDEN}" NAME_WLE)
set(render_command "${PARTICLES}" render "${SCENARIO}" -o "${actual}" --at "${AT}" ${render_options} ${extra} --quiet)
shown_command(render_shown ${render_command})
if(NOT "$ENV{LP_NUM_THREADS}" STREQUAL "")
  set(render_shown "LP_NUM_THREADS=$ENV{LP_NUM_THREADS} ${render_shown}")
endif()
set(facts "")
add_result(facts test "${TEST_NAME}")
add_result(facts frame "${frame}")
add_result(facts expect "${EXPECT}")
if(GOLDEN_COMMAND)
  add_result(facts golden_command yes)
else()
  add_result(facts golden_command no)
endif()
shown_command(golden_shown "${GOLDEN}")
add_result(facts golden "${golden_shown}")
add_result(facts render_command "${render_shown}")
write_result(unfinished)

# fail_with_error(WHY [LINES]): the test cannot compare (no golden, render or compare failed).
function(fail_with_error why)
  add_result(lines message "${why}")
  write_result(error "${ARGN}${lines}")
  message(FATAL_ERROR "${why}")
endfunction()

if(NOT EXISTS "${GOLDEN}")
  fail_with_error("no golden frame ${GOLDEN}: render it with scripts/update-golden")
endif()

execute_process(COMMAND ${render_command} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT code EQUAL 0)
  fail_with_error("render failed (exit ${code}):\n  ${render_shown}\n${out}${err}")
endif()

set(compare_command "${PARTICLES}" compare "${GOLDEN}" "${actual}" --diff "${diff}" ${compare_options})
execute_process(COMMAND ${compare_command} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
shown_command(compare_shown ${compare_command})
set(numbers "")
add_result(numbers compare_command "${compare_shown}")
if(NOT code MATCHES "^[01]$")
  fail_with_error("compare failed (exit ${code}):\n  ${compare_shown}\n${out}${err}" "${numbers}")
endif()

# The numbers `particles compare` prints (src/app/compare_command.cpp), for the report. A change to
# that wording fails every golden test here rather than leaving the report without its numbers.
string(CONCAT share_line "share: +([0-9.]+) % of the pixels differ by more than ([0-9]+) "
                         "\\(([0-9]+) of ([0-9]+); bound ([^ ]+) %\\)")
if(NOT out MATCHES "${share_line}" OR NOT out MATCHES "largest: +([0-9]+)" OR NOT out MATCHES "box: +([^\n]+)")
  fail_with_error("cannot read the numbers `particles compare` printed:\n  ${compare_shown}\n${out}" "${numbers}")
endif()
string(REGEX MATCH "${share_line}" ignored "${out}")
add_result(numbers share_percent "${CMAKE_MATCH_1}")
add_result(numbers threshold "${CMAKE_MATCH_2}")
add_result(numbers differing "${CMAKE_MATCH_3}")
add_result(numbers pixels "${CMAKE_MATCH_4}")
add_result(numbers bound_percent "${CMAKE_MATCH_5}")
string(REGEX MATCH "largest: +([0-9]+)" ignored "${out}")
add_result(numbers largest "${CMAKE_MATCH_1}")
string(REGEX MATCH "box: +([^\n]+)" ignored "${out}")
add_result(numbers box "${CMAKE_MATCH_1}")
if(code EQUAL 0)
  add_result(numbers verdict match)
else()
  add_result(numbers verdict differ)
endif()
set(kept "")
get_filename_component(name_only "${actual}" NAME)
add_result(kept actual "${name_only}")
get_filename_component(name_only "${diff}" NAME)
add_result(kept diff "${name_only}")
get_filename_component(name_only "${expected}" NAME)
set(kept_with_golden "${kept}")
add_result(kept_with_golden expected "${name_only}")

if(EXPECT STREQUAL "match")
  if(code EQUAL 0)
    file(REMOVE "${actual}" "${diff}")
    write_result(passed "${numbers}")
    message(STATUS "${out}")
    return()
  endif()
  file(COPY_FILE "${GOLDEN}" "${expected}")
  write_result(failed "${numbers}${kept_with_golden}")
  message(NOTICE
    "the frame differs from its golden frame.\n"
    "${out}"
    "  golden: ${GOLDEN}\n"
    "  actual: ${actual}\n"
    "  diff:   ${diff}\n"
    "rendered with: ${render_shown}\n"
    "All golden results side by side, when the golden tests end: ${report}\n"
    "If the change is intended, accept the frames with scripts/update-golden --from ${OUT_DIR}, "
    "or re-render them with scripts/update-golden, and review them.")
  message(FATAL_ERROR "${NAME}: the frame differs from ${GOLDEN}")
else()
  if(code EQUAL 1)
    # The frame and its diff stay: they show what the golden test sees of the perturbation.
    write_result(passed "${numbers}${kept}")
    message(STATUS "the perturbed frame fails the comparison, as it must:\n${out}")
    return()
  endif()
  file(COPY_FILE "${GOLDEN}" "${expected}")
  write_result(failed "${numbers}${kept_with_golden}")
  message(NOTICE
    "the perturbed frame PASSES the comparison: the golden test cannot see this change.\n"
    "${out}"
    "  golden: ${GOLDEN}\n"
    "  actual: ${actual}\n"
    "  diff:   ${diff}\n"
    "rendered with: ${render_shown}\n"
    "All golden results side by side, when the golden tests end: ${report}")
  message(FATAL_ERROR "${NAME}: the perturbed frame matches ${GOLDEN}")
endif()
