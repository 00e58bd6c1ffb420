# Every dependency is a Debian 12 package; README.md lists the apt line.
find_package(PkgConfig REQUIRED)
find_package(OpenImageIO CONFIG REQUIRED)
find_package(TinyGLTF CONFIG REQUIRED)
find_package(glfw3 CONFIG REQUIRED)
find_package(glm CONFIG REQUIRED)
find_package(nlohmann_json CONFIG REQUIRED)
find_package(CLI11 CONFIG REQUIRED)
find_package(Threads REQUIRED)
pkg_check_modules(EPOXY REQUIRED IMPORTED_TARGET epoxy)
pkg_check_modules(EGL REQUIRED IMPORTED_TARGET egl)
pkg_check_modules(IMGUI REQUIRED IMPORTED_TARGET imgui)

# Debian's OpenImageIO config lists /usr/include/opencv4 as an include directory even
# though OpenImageIO's public headers never need OpenCV; CMake refuses a missing
# include directory on an imported target, so drop it instead of pulling in OpenCV.
foreach(prop INTERFACE_INCLUDE_DIRECTORIES INTERFACE_SYSTEM_INCLUDE_DIRECTORIES)
  get_target_property(dirs OpenImageIO::OpenImageIO ${prop})
  if(dirs)
    list(FILTER dirs EXCLUDE REGEX "opencv4")
    set_target_properties(OpenImageIO::OpenImageIO PROPERTIES ${prop} "${dirs}")
  endif()
endforeach()

# Debian ships Dear ImGui's platform backends as sources only; compile the two we use.
set(IMGUI_BACKEND_DIR /usr/share/doc/libimgui-dev/examples/backends)
add_library(imgui_backends STATIC
  ${IMGUI_BACKEND_DIR}/imgui_impl_glfw.cpp
  ${IMGUI_BACKEND_DIR}/imgui_impl_opengl3.cpp)
target_include_directories(imgui_backends SYSTEM PUBLIC /usr/include/imgui/backends)
# Our loader is libepoxy: the custom-loader switch makes the backend use whatever GL
# declarations are already visible, and the forced include provides them.
target_compile_definitions(imgui_backends PUBLIC IMGUI_IMPL_OPENGL_LOADER_CUSTOM)
target_compile_options(imgui_backends PRIVATE -include epoxy/gl.h -w)
target_link_libraries(imgui_backends PUBLIC PkgConfig::IMGUI PkgConfig::EPOXY glfw)
