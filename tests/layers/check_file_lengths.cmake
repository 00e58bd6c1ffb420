# Fails on a source file of app/, ui/, renderer/ or tests/ longer than MAX_LINES (600; the
# rule of docs/architecture.md), naming each with its length. Data files are exceptions:
# generated tables (*.inc) are not C++ a reader follows, so they are not checked.
#
#   cmake -DSOURCE_DIR=<repo> [-DMAX_LINES=600] [-DEXTRA_FILE=f] -P check_file_lengths.cmake
#
# EXTRA_FILE is checked as well: the test proving that the check fails.
cmake_minimum_required(VERSION 3.25)
if(NOT DEFINED MAX_LINES)
  set(MAX_LINES 600)
endif()
file(GLOB_RECURSE sources
  ${SOURCE_DIR}/app/*.cpp ${SOURCE_DIR}/app/*.hpp
  ${SOURCE_DIR}/ui/*.cpp ${SOURCE_DIR}/ui/*.hpp
  ${SOURCE_DIR}/renderer/*.cpp ${SOURCE_DIR}/renderer/*.hpp
  ${SOURCE_DIR}/tests/*.cpp ${SOURCE_DIR}/tests/*.hpp
  ${SOURCE_DIR}/assets/shaders/*.glsl ${SOURCE_DIR}/assets/shaders/*.comp
  ${SOURCE_DIR}/assets/shaders/*.vert ${SOURCE_DIR}/assets/shaders/*.frag)
if(DEFINED EXTRA_FILE)
  list(APPEND sources ${EXTRA_FILE})
endif()
set(too_long "")
foreach(source ${sources})
  # file(STRINGS) drops empty lines; count newlines instead, as wc -l does.
  file(READ ${source} text)
  string(REGEX REPLACE "[^\n]" "" newlines "${text}")
  string(LENGTH "${newlines}" count)
  if(count GREATER MAX_LINES)
    file(RELATIVE_PATH shown ${SOURCE_DIR} ${source})
    list(APPEND too_long "${shown} (${count} lines)")
  endif()
endforeach()
list(LENGTH sources checked)
if(too_long)
  list(JOIN too_long "\n  " shown)
  message(FATAL_ERROR "files over ${MAX_LINES} lines (split them by concept):\n  ${shown}")
endif()
message(STATUS "${checked} source files, none over ${MAX_LINES} lines")
