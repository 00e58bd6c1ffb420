# Fails on a function of app/, ui/ or renderer/ longer than MAX_LINES (100; the rule of
# docs/architecture.md), naming each with its file, line and length. A function here is a
# body whose braces stand alone at the start of a line ("{" ... "}"), as the code is
# formatted; a member defined in its class, or a lambda, counts in what holds it. Data tables
# (a list of rows, read rather than followed) are exceptions, named below with why.
#
#   cmake -DSOURCE_DIR=<repo> [-DMAX_LINES=100] [-DEXTRA_FILE=f] -P check_function_lengths.cmake
#
# EXTRA_FILE is checked as well: the test proving that the check fails.
cmake_minimum_required(VERSION 3.25)
if(NOT DEFINED MAX_LINES)
  set(MAX_LINES 100)
endif()
# "file|signature start": the first line of the function's signature, up to its "(".
set(exceptions
  # Data tables: one row per candidate or measurement, no control flow to follow.
  "renderer/lab/bench_sweep.cpp|std::vector<SweepPoint> sweepPoints"
  "renderer/lab/auto_quality.cpp|AutoCandidates autoCandidates")

file(GLOB_RECURSE sources ${SOURCE_DIR}/app/*.cpp ${SOURCE_DIR}/app/*.hpp ${SOURCE_DIR}/ui/*.cpp ${SOURCE_DIR}/ui/*.hpp
                          ${SOURCE_DIR}/renderer/*.cpp ${SOURCE_DIR}/renderer/*.hpp)
if(DEFINED EXTRA_FILE)
  list(APPEND sources ${EXTRA_FILE})
endif()
set(too_long "")
set(functions 0)
foreach(source ${sources})
  file(READ ${source} text)
  file(RELATIVE_PATH shown ${SOURCE_DIR} ${source})
  set(rest "${text}")
  set(line 1)
  while(TRUE)
    string(FIND "${rest}" "\n{\n" open)
    if(open EQUAL -1)
      break()
    endif()
    string(SUBSTRING "${rest}" 0 ${open} before)
    math(EXPR from "${open} + 3")
    string(SUBSTRING "${rest}" ${from} -1 rest)
    string(FIND "${rest}" "\n}" close)
    if(close EQUAL -1)
      break()
    endif()
    string(SUBSTRING "${rest}" 0 ${close} body)
    math(EXPR from "${close} + 2")
    string(SUBSTRING "${rest}" ${from} -1 rest)
    # The signature's first line: the last line of `before` that starts in column 0.
    string(REGEX MATCH "(^|\n)([^ \t\n][^\n]*)(\n[ \t][^\n]*)*$" signature "${before}")
    set(signature "${CMAKE_MATCH_2}")
    string(REGEX REPLACE "\\(.*" "" name "${signature}")
    string(REGEX REPLACE "[^\n]" "" newlines "${before}")
    string(LENGTH "${newlines}" skipped)
    math(EXPR start "${line} + ${skipped}")
    string(REGEX REPLACE "[^\n]" "" newlines "${body}")
    string(LENGTH "${newlines}" count)
    math(EXPR count "${count} + 3") # the braces' lines and the body's last line
    math(EXPR line "${start} + ${count} - 1")
    math(EXPR functions "${functions} + 1")
    if(count GREATER MAX_LINES AND NOT "${shown}|${name}" IN_LIST exceptions)
      list(APPEND too_long "${shown}:${start}: ${name} (${count} lines)")
    endif()
  endwhile()
endforeach()
if(too_long)
  list(JOIN too_long "\n  " text)
  message(FATAL_ERROR "functions over ${MAX_LINES} lines (split them into steps):\n  ${text}")
endif()
message(STATUS "${functions} functions, none over ${MAX_LINES} lines but the ones named as exceptions")
