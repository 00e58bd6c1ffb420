# The layers of iblab, lowest first: ibl (math) < io, gl < scene < bake < frame < lab < ui,
# then app on top. Each layer is a static library, iblab_<name>, made by iblab_layer from one
# folder. Its include root is a directory of the build tree that holds only a link named
# <name> to that folder, so code writes #include "<layer>/<file>.hpp" and finds exactly the
# layers its library links: an include of a layer above (or beside) does not compile.
# tests/layers checks the rest (relative includes that would step around the roots, and
# includes of another layer's internal headers).
set(IBLAB_INCLUDE_ROOTS ${PROJECT_BINARY_DIR}/include-roots)

# iblab_layer(NAME SOURCES file... [LAYERS lower-layer...] [FACE header...] [PUBLIC target...] [PRIVATE target...])
# FACE lists the layer's public face: the headers (relative to its folder) that other layers
# may include. Its other headers are internal to it. Without FACE every header is public.
function(iblab_layer name)
  cmake_parse_arguments(PARSE_ARGV 1 L "" "" "SOURCES;LAYERS;FACE;PUBLIC;PRIVATE")
  foreach(header ${L_FACE})
    if(NOT EXISTS ${CMAKE_CURRENT_SOURCE_DIR}/${header})
      message(FATAL_ERROR "iblab_layer(${name}): FACE names ${header}, which is not in ${CMAKE_CURRENT_SOURCE_DIR}")
    endif()
  endforeach()
  add_library(iblab_${name} STATIC ${L_SOURCES})
  set(root ${IBLAB_INCLUDE_ROOTS}/${name})
  file(MAKE_DIRECTORY ${root})
  file(CREATE_LINK ${CMAKE_CURRENT_SOURCE_DIR} ${root}/${name} SYMBOLIC)
  target_include_directories(iblab_${name} PUBLIC ${root})
  list(TRANSFORM L_LAYERS PREPEND iblab_ OUTPUT_VARIABLE layer_targets)
  target_link_libraries(iblab_${name} PUBLIC ${layer_targets} ${L_PUBLIC} PRIVATE ${L_PRIVATE} iblab_warnings)
  set_property(GLOBAL APPEND PROPERTY IBLAB_LAYERS ${name})
  set_property(GLOBAL PROPERTY IBLAB_LAYER_DIR_${name} ${CMAKE_CURRENT_SOURCE_DIR})
  set_property(GLOBAL PROPERTY IBLAB_LAYER_USES_${name} ${L_LAYERS})
  set_property(GLOBAL PROPERTY IBLAB_LAYER_FACE_${name} ${L_FACE})
endfunction()

# Writes the layers, their folders, what each may include (the layers it links, and theirs)
# and each one's public face for tests/layers/check_layers.cmake.
function(iblab_write_layer_map file)
  get_property(layers GLOBAL PROPERTY IBLAB_LAYERS)
  set(text "set(IBLAB_LAYERS ${layers})\n")
  foreach(layer ${layers})
    get_property(dir GLOBAL PROPERTY IBLAB_LAYER_DIR_${layer})
    set(reach "")
    set(pending ${layer})
    while(pending)
      list(POP_FRONT pending current)
      if(current IN_LIST reach)
        continue()
      endif()
      list(APPEND reach ${current})
      get_property(uses GLOBAL PROPERTY IBLAB_LAYER_USES_${current})
      list(APPEND pending ${uses})
    endwhile()
    get_property(face GLOBAL PROPERTY IBLAB_LAYER_FACE_${layer})
    string(APPEND text "set(IBLAB_LAYER_DIR_${layer} \"${dir}\")\nset(IBLAB_LAYER_REACH_${layer} ${reach})\n")
    string(APPEND text "set(IBLAB_LAYER_FACE_${layer} ${face})\n")
  endforeach()
  file(WRITE ${file} "${text}")
endfunction()
