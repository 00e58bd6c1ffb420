# Fails on a name that a layer defines outside its own namespace (docs/architecture.md,
# Namespaces): ibl, io, scene and frame define theirs in iblab itself, gl, bake, ui and app in
# iblab::<layer>, lab in iblab::bench, iblab::stress, iblab::accuracy or iblab::lab; a
# sub-namespace of a layer's own holds its internals (but iblab::<another layer> is not a
# sub-namespace of iblab's own). universal-ctags finds every class, struct, union, enum,
# alias, variable, function and function or variable declaration with the namespace that holds it;
# forward declarations of another layer's types are not tagged, so they stay allowed.
# Allowed besides: a program's main, the C entry points named below, and a specialisation of a
# template, which C++ puts in the template's namespace.
#
#   cmake -DSOURCE_DIR=<repo> -DCTAGS=<universal-ctags> [-DEXTRA_FILE=f -DEXTRA_LAYER=layer]
#         -P check_namespaces.cmake
#
# EXTRA_FILE is checked as well, as a file of EXTRA_LAYER: the test proving that the check fails.
cmake_minimum_required(VERSION 3.25)
set(own_ibl iblab)
set(own_io iblab)
set(own_scene iblab)
set(own_frame iblab)
set(own_gl iblab::gl)
set(own_bake iblab::bake)
set(own_ui iblab::ui)
set(own_app iblab::app)
set(own_lab iblab::bench iblab::stress iblab::accuracy iblab::lab)
set(layer_namespaces gl bake ui app bench stress accuracy lab)
# "file|name" defined outside iblab, with why.
set(exceptions
  # The OpenImageIO codec's entry point, found by dlsym under its C name.
  "renderer/io/image_codec_oiio.cpp|iblab_image_codec")

include(${CMAKE_CURRENT_LIST_DIR}/ctags_tags.cmake)
ctags_tags(tags WHAT "the namespace check" ARGS --kinds-C++=csugtvfpx --fields=+nKZ-P --fields-C++=+{specialization})
set(wrong "")
set(checked 0)
foreach(tag IN LISTS tags)
  if(tag STREQUAL "")
    continue()
  endif()
  string(JSON scope_kind ERROR_VARIABLE global GET "${tag}" scopeKind)
  if(NOT global AND NOT scope_kind STREQUAL "namespace")
    continue() # a member, held by its class
  endif()
  string(JSON name GET "${tag}" name)
  string(JSON kind GET "${tag}" kind)
  string(JSON path GET "${tag}" path)
  string(JSON line GET "${tag}" line)
  set(scope "")
  if(NOT global)
    string(JSON scope GET "${tag}" scope)
    # Unnamed namespaces add nothing to a name's namespace.
    string(REGEX REPLACE "(^|::)__anon[0-9a-f]+" "" scope "${scope}")
    string(REGEX REPLACE "^::" "" scope "${scope}")
  endif()
  if(path STREQUAL EXTRA_FILE)
    set(layer ${EXTRA_LAYER})
  else()
    file(RELATIVE_PATH relative ${SOURCE_DIR} ${path})
    string(REGEX REPLACE "^renderer/" "" layer "${relative}")
    string(REGEX REPLACE "/.*" "" layer "${layer}")
  endif()
  file(RELATIVE_PATH shown ${SOURCE_DIR} ${path})
  math(EXPR checked "${checked} + 1")
  string(JSON specialization ERROR_VARIABLE plain GET "${tag}" specialization)
  set(allowed FALSE)
  if(scope STREQUAL "")
    if(name STREQUAL "main" OR "${shown}|${name}" IN_LIST exceptions)
      set(allowed TRUE)
    endif()
  elseif(NOT plain AND scope MATCHES "^iblab(::|$)")
    set(allowed TRUE)
  else()
    foreach(own ${own_${layer}})
      if(scope STREQUAL own)
        set(allowed TRUE)
      elseif(scope MATCHES "^${own}::([A-Za-z0-9_]+)")
        if(NOT own STREQUAL "iblab" OR NOT CMAKE_MATCH_1 IN_LIST layer_namespaces)
          set(allowed TRUE)
        endif()
      endif()
    endforeach()
  endif()
  if(NOT allowed)
    if(scope STREQUAL "")
      set(scope "the global namespace")
    endif()
    list(APPEND wrong "${shown}:${line}: layer '${layer}' defines ${kind} '${name}' in ${scope}")
  endif()
endforeach()
ctags_check_report(${checked} "definitions" "${wrong}" "names outside their layer's namespace (docs/architecture.md, Namespaces)"
                   "each in its layer's namespace")
