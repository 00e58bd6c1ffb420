# The one way the layer checks (check_function_lengths.cmake, check_namespaces.cmake) ask
# universal-ctags about the code: every .cpp/.hpp of app/, ui/ and renderer/ (and EXTRA_FILE,
# a check's proof that it can fail), one JSON tag per list element; and the one way they
# report what they found.
#
#   include(ctags_tags.cmake)
#   ctags_tags(tags WHAT "the namespace check" ARGS --kinds-C++=f --fields=+ne-P)
#   ctags_check_report(${checked} "definitions" "${wrong}" "names outside ..." "each in its namespace")
function(ctags_tags out_var)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "WHAT" "ARGS")
  if(NOT CTAGS)
    message(FATAL_ERROR "universal-ctags not found: ${arg_WHAT} needs it (Debian package universal-ctags, "
                        "in scripts/install-deps.sh); reconfigure once it is installed")
  endif()
  execute_process(COMMAND ${CTAGS} --version OUTPUT_VARIABLE version RESULT_VARIABLE failed)
  if(failed OR NOT version MATCHES "Universal Ctags")
    message(FATAL_ERROR "${CTAGS} is not universal-ctags (it prints no \"Universal Ctags\" version): "
                        "${arg_WHAT} needs universal-ctags' JSON output")
  endif()
  file(GLOB_RECURSE sources ${SOURCE_DIR}/app/*.cpp ${SOURCE_DIR}/app/*.hpp ${SOURCE_DIR}/ui/*.cpp ${SOURCE_DIR}/ui/*.hpp
                            ${SOURCE_DIR}/renderer/*.cpp ${SOURCE_DIR}/renderer/*.hpp)
  if(DEFINED EXTRA_FILE)
    list(APPEND sources ${EXTRA_FILE})
  endif()
  execute_process(COMMAND ${CTAGS} --languages=C++ --langmap=C++:+.hpp ${arg_ARGS} --output-format=json -o - ${sources}
                  OUTPUT_VARIABLE tags RESULT_VARIABLE failed ERROR_VARIABLE errors)
  if(failed)
    message(FATAL_ERROR "${CTAGS} failed (${failed}): ${errors}")
  endif()
  # One tag a line; a ";" would split a tag (none of the fields the checks ask for holds one).
  string(REPLACE ";" "," tags "${tags}")
  string(REPLACE "\n" ";" tags "${tags}")
  set(${out_var} "${tags}" PARENT_SCOPE)
endfunction()

# Fails where ctags saw nothing (a check that read no code would pass on anything) or where
# there are findings (each on its own line under `heading`); else reports the count checked.
function(ctags_check_report checked what findings heading passed)
  if(checked EQUAL 0)
    message(FATAL_ERROR "${CTAGS} found no ${what} in ${SOURCE_DIR}: the check would pass on anything")
  endif()
  if(findings)
    list(JOIN findings "\n  " text)
    message(FATAL_ERROR "${heading}:\n  ${text}")
  endif()
  message(STATUS "${checked} ${what}, ${passed}")
endfunction()
