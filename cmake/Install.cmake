# cmake --install and the Debian package (cpack -G DEB, scripts/package-check.sh).
# The layout under the prefix is the one the executable looks for (app/asset_paths.hpp,
# io/image_codec.hpp): bin/iblab, lib/iblab/libiblab_oiio.so, share/iblab/{shaders,
# environments,models}.
# Installing (and cpack) needs only what is installed, not every test: build the iblab target
# (its image module comes with it) before `cmake --install` or `cpack`.
set(CMAKE_SKIP_INSTALL_ALL_DEPENDENCY ON)
install(TARGETS iblab RUNTIME DESTINATION ${IBLAB_INSTALL_BIN_DIR})
install(TARGETS iblab_oiio LIBRARY DESTINATION ${IBLAB_INSTALL_MODULE_DIR})
install(DIRECTORY ${IBLAB_ASSET_DIR}/shaders ${IBLAB_ASSET_DIR}/environments ${IBLAB_ASSET_DIR}/models
        DESTINATION ${IBLAB_INSTALL_DATA_DIR})
install(FILES ${PROJECT_SOURCE_DIR}/README.md DESTINATION share/doc/iblab)

set(CPACK_PACKAGE_NAME iblab)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_CONTACT "iblab maintainers <iblab@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "lab for image-based lighting: bake, shade and measure HDR environments")
set(CPACK_PACKAGE_DESCRIPTION "iblab loads an HDR environment, bakes it into the inputs of real-time image-based lighting
(cubemap, SH9, GGX-prefiltered mips, BRDF LUT) checked against exact integrals, and shades
spheres, grids and glTF models with the split sum, a fitted lobe or N importance samples per
pixel, in a window or headless through EGL.")
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
# Without the build's debug information: 10 MB instead of 100.
set(CPACK_STRIP_FILES ON)
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
# The libraries the executable and its image module link, from dpkg-shlibdeps (dpkg-dev).
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# What no binary links but rendering needs, so shlibdeps cannot find it: libepoxy opens
# libEGL and libGL (libglvnd) at run time, they dispatch to Mesa's vendor libraries, and
# llvmpipe's driver renders where there is no GPU; headless commands go through EGL, the GUI
# through GLX.
set(CPACK_DEBIAN_PACKAGE_DEPENDS "libegl1, libgl1, libegl-mesa0, libglx-mesa0, libgl1-mesa-dri")
set(CPACK_GENERATOR DEB)
include(CPack)
