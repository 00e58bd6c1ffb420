# Fails when a layer's source includes a layer it does not link (one above it, or beside it),
# includes a header of another layer that is not on that layer's public face (its FACE list
# in its CMakeLists.txt: the rest is internal to it), or steps around the include roots
# with "../". The build already refuses most such
# includes (each library sees only the roots of the layers it links); this check also
# catches the ones that would compile by accident, e.g. through a test's wider include path,
# and it names the line.
#
#   cmake -DLAYER_MAP=<build>/layer-map.cmake [-DAPP_DIR=<repo>/app] [-DEXTRA_FILE=f -DEXTRA_LAYER=l] -P check_layers.cmake
#
# APP_DIR: app/, the top, which may include every layer, each through its public face.
#
# EXTRA_FILE is checked as if it lived in EXTRA_LAYER: the test proving that the check fails.
cmake_minimum_required(VERSION 3.25)
include(${LAYER_MAP})
set(IBLAB_LAYER_REACH_app ${IBLAB_LAYERS})

set(violations "")
function(check_file file layer)
  file(STRINGS ${file} lines REGEX "^[ \t]*#[ \t]*include[ \t]*\"")
  foreach(line ${lines})
    string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]*\"([^\"]*)\".*" "\\1" target "${line}")
    if(target MATCHES "^\\.\\./" OR target MATCHES "/\\.\\./")
      list(APPEND violations "${file}: \"${target}\" steps around the include roots")
    elseif(target MATCHES "^([a-z_]+)/")
      set(included ${CMAKE_MATCH_1})
      if(included IN_LIST IBLAB_LAYERS AND NOT included IN_LIST IBLAB_LAYER_REACH_${layer})
        list(APPEND violations "${file}: layer '${layer}' includes \"${target}\" from layer '${included}', which it does not build on (it may use: ${IBLAB_LAYER_REACH_${layer}})")
      elseif(included IN_LIST IBLAB_LAYERS AND NOT included STREQUAL layer AND IBLAB_LAYER_FACE_${included})
        string(REGEX REPLACE "^[a-z_]+/" "" header "${target}")
        if(NOT header IN_LIST IBLAB_LAYER_FACE_${included})
          list(JOIN IBLAB_LAYER_FACE_${included} ", " face)
          list(APPEND violations "${file}: layer '${layer}' includes \"${target}\", which is internal to layer '${included}' (its public face: ${face})")
        endif()
      endif()
    endif()
  endforeach()
  set(violations "${violations}" PARENT_SCOPE)
endfunction()

set(checked 0)
foreach(layer ${IBLAB_LAYERS})
  file(GLOB_RECURSE sources ${IBLAB_LAYER_DIR_${layer}}/*.cpp ${IBLAB_LAYER_DIR_${layer}}/*.hpp
                            ${IBLAB_LAYER_DIR_${layer}}/*.inc)
  foreach(source ${sources})
    check_file(${source} ${layer})
    math(EXPR checked "${checked} + 1")
  endforeach()
endforeach()
if(DEFINED APP_DIR)
  file(GLOB_RECURSE sources ${APP_DIR}/*.cpp ${APP_DIR}/*.hpp)
  foreach(source ${sources})
    check_file(${source} app)
    math(EXPR checked "${checked} + 1")
  endforeach()
endif()
if(EXTRA_FILE)
  check_file(${EXTRA_FILE} ${EXTRA_LAYER})
  math(EXPR checked "${checked} + 1")
endif()

if(violations)
  list(JOIN violations "\n  " text)
  message(FATAL_ERROR "layer violations:\n  ${text}")
endif()
list(LENGTH IBLAB_LAYERS layer_count)
message(STATUS "${checked} files in ${layer_count} layers include only the layers below them, and of those only their public faces")
