# Fails on a function of app/, ui/ or renderer/ longer than MAX_LINES (100; the rule of
# docs/architecture.md), naming each with its file, line and length. universal-ctags finds the
# functions and their first and last lines: free functions, members defined out of or inside
# their class, at any indentation, and lambdas (each counted on its own, and in what holds it).
# A function's length runs from the line of its name to its closing brace. Data tables (a list
# of rows, read rather than followed) are exceptions, named below with why.
#
#   cmake -DSOURCE_DIR=<repo> -DCTAGS=<universal-ctags> [-DMAX_LINES=100] [-DEXTRA_FILE=f]
#         -P check_function_lengths.cmake
#
# EXTRA_FILE is checked as well: the test proving that the check fails.
cmake_minimum_required(VERSION 3.25)
if(NOT DEFINED MAX_LINES)
  set(MAX_LINES 100)
endif()
# "file|function": the function as universal-ctags names it (no scope, no arguments).
set(exceptions
  # Data tables: one row per candidate or measurement, no control flow to follow.
  "renderer/lab/bench_sweep.cpp|sweepPoints"
  "renderer/lab/auto_quality.cpp|autoCandidates")

include(${CMAKE_CURRENT_LIST_DIR}/ctags_tags.cmake)
ctags_tags(tags WHAT "the function-length check" ARGS --kinds-C++=f --fields=+ne-P)
set(too_long "")
set(functions 0)
foreach(tag IN LISTS tags)
  if(tag STREQUAL "")
    continue()
  endif()
  string(JSON end ERROR_VARIABLE no_end GET "${tag}" end)
  if(no_end)
    continue() # a tag with no body
  endif()
  string(JSON name GET "${tag}" name)
  string(JSON path GET "${tag}" path)
  string(JSON start GET "${tag}" line)
  string(JSON scope ERROR_VARIABLE no_scope GET "${tag}" scope)
  math(EXPR count "${end} - ${start} + 1")
  math(EXPR functions "${functions} + 1")
  if(name MATCHES "^__anon")
    set(name "a lambda in ${scope}")
  endif()
  file(RELATIVE_PATH shown ${SOURCE_DIR} ${path})
  if(count GREATER MAX_LINES AND NOT "${shown}|${name}" IN_LIST exceptions)
    list(APPEND too_long "${shown}:${start}: ${name} (${count} lines)")
  endif()
endforeach()
ctags_check_report(${functions} "functions" "${too_long}" "functions over ${MAX_LINES} lines (split them into steps)"
                   "none over ${MAX_LINES} lines but the data tables named as exceptions")
