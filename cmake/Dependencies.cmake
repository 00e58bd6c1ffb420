# Every dependency is a Debian 12 package; README.md lists the apt line.
find_package(PkgConfig REQUIRED)
find_package(TinyGLTF CONFIG REQUIRED)
find_package(glfw3 CONFIG REQUIRED)
find_package(glm CONFIG REQUIRED)
find_package(nlohmann_json CONFIG REQUIRED)
find_package(CLI11 CONFIG REQUIRED)
find_package(Threads REQUIRED)
pkg_check_modules(EPOXY REQUIRED IMPORTED_TARGET epoxy)
pkg_check_modules(EGL REQUIRED IMPORTED_TARGET egl)
pkg_check_modules(IMGUI REQUIRED IMPORTED_TARGET imgui)
pkg_check_modules(XXHASH REQUIRED IMPORTED_TARGET libxxhash)

# OpenImageIO through its pkg-config file, not its CMake config. Debian splits the
# packages so that the CMake configs name files that libopenimageio-dev and libimath-dev
# do not install: OpenImageIOTargets.cmake imports the command-line tools (/usr/bin/iconvert,
# ... in openimageio-tools), ImathTargets.cmake (pulled in by it) imports libPyImath (in
# python3-imath), and the OpenImageIO target names /usr/include/opencv4 (libopencv-dev).
# Installing those would add Python and OpenCV to build a C++ program that uses none of
# them; the .pc file names exactly the two libraries we link, with nothing missing.
pkg_check_modules(OPENIMAGEIO REQUIRED IMPORTED_TARGET OpenImageIO)
add_library(OpenImageIO::OpenImageIO ALIAS PkgConfig::OPENIMAGEIO)

# Debian ships Dear ImGui's backends as sources only; compile the OpenGL3 renderer backend.
# The platform side is app/gui_input + app/gui_platform instead of imgui_impl_glfw: one input
# queue that a window and a script both feed (imgui_impl_glfw writes GLFW's state straight
# into ImGui and cannot be driven without a window).
set(IMGUI_BACKEND_DIR /usr/share/doc/libimgui-dev/examples/backends)
add_library(imgui_backends STATIC
  ${IMGUI_BACKEND_DIR}/imgui_impl_opengl3.cpp)
target_include_directories(imgui_backends SYSTEM PUBLIC /usr/include/imgui/backends)
# Our loader is libepoxy: the custom-loader switch makes the backend use whatever GL
# declarations are already visible, and the forced include provides them.
target_compile_definitions(imgui_backends PUBLIC IMGUI_IMPL_OPENGL_LOADER_CUSTOM)
target_compile_options(imgui_backends PRIVATE -include epoxy/gl.h -w)
target_link_libraries(imgui_backends PUBLIC PkgConfig::IMGUI PkgConfig::EPOXY)
