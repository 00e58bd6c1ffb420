#!/usr/bin/env bash
# Installs every Debian 12 package that iblab's build, tests, fuzzers and GUI need, and
# nothing else; scripts/fresh-check.sh proves the list on a freshly bootstrapped root.
# Idempotent; runs apt as root (directly, or through sudo when not root).
set -euo pipefail
packages=(
  # The build: CMake drives make and g++; pkg-config finds epoxy, EGL, imgui, OpenImageIO.
  cmake make g++ pkg-config
  # Libraries the code includes (ImGui ships its GLFW/OpenGL3 backends as sources we compile).
  libimgui-dev libglfw3-dev libepoxy-dev libglm-dev libcli11-dev nlohmann-json3-dev
  # Images: OpenImageIO reads/writes EXR, HDR, PNG; its headers include Imath's.
  libopenimageio-dev libimath-dev
  # OpenEXR's own library, linked by the io layer: the bake's EXRs are read and written
  # without loading OpenImageIO (renderer/io/image_codec_direct.hpp).
  libopenexr-dev
  # glTF: tiny_gltf.h includes stb_image.h and stb_image_write.h from libstb-dev.
  libtinygltf-dev libstb-dev
  # XXH3: the content hash that keys the bake and reference caches (a map's 6 MB of texels
  # at memory speed, where the byte-wise FNV-1a before it was a multiply per byte).
  libxxhash-dev
  # Tests: GoogleTest; zlib for the CRCs of the malformed-PNG corpus the tests write.
  libgtest-dev zlib1g-dev
  # Tests: universal-ctags gives each function's first and last line, members defined in
  # their class and lambdas included, to the function-length check (layers.functions_*).
  universal-ctags
  # Tests: the Khronos glTF samples that model_framing_gltest draws (models from millimetres
  # to hundreds of units across; the tests skip with a message without them).
  assimp-testmodels
  # OpenGL through Mesa: EGL headers (headless), the EGL and GLX vendors, llvmpipe's driver.
  libegl-dev libegl-mesa0 libglx-mesa0 libgl1-mesa-dri
  # The GUI tests drive a real GLFW window on a private X server (tests/gui/with-xvfb.sh).
  xvfb
  # The export tests' readers that iblab did not write (tests/gl/engine_export_gltest.cpp):
  # Filament's KTX 1 reader (KtxBundle in libfilament_image, headers in libfilament-dev), its
  # cmgen (libfilament-tools) for the SH comparison, and node + npm to run npm's ktx-parse on
  # the KTX 2.0 files (scripts/install-ktx-parse.sh installs it from tests/ktx2's lockfile).
  # cmgen's own bakes are also what the import is tested on (imported_bake_test runs it on a
  # map it writes) and what scripts/compare-cmgen.sh measures against iblab's.
  # ca-certificates: npm reaches its registry over HTTPS.
  libfilament-dev libfilament-tools nodejs npm ca-certificates
  # The Debian package (cpack -G DEB, scripts/package-check.sh): CPack's DEB generator finds
  # the runtime dependencies with dpkg-shlibdeps (dpkg-dev) and tells binaries by file(1).
  dpkg-dev file
  # scripts/fuzz.sh (run by CI): libFuzzer and the sanitizer runtimes of clang 14, and its
  # llvm-symbolizer (llvm-14): tests/sanitizer/lsan.supp matches function names, which a
  # leak report only has when its stack is symbolized.
  clang-14 libclang-rt-14-dev llvm-14
)
as_root=()
[ "$(id -u)" -eq 0 ] || as_root=(sudo)
missing=()
for p in "${packages[@]}"; do
  # A Node.js from outside Debian (NodeSource's nodejs bundles npm and Conflicts: npm) already
  # gives the npm command; asking apt for Debian's npm beside it fails the whole install.
  [ "$p" = npm ] && command -v npm >/dev/null && continue
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "install-deps: installing ${missing[*]}"
  "${as_root[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${as_root[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
# The npm package of the export tests, at its locked version (as the invoking user, not root,
# when run through sudo, so that the checkout stays theirs).
# Best effort: the lab builds and runs without it, and the KTX 2.0 checks skip, saying so,
# where the npm registry cannot be reached.
ktx_parse=("$(dirname "$0")/install-ktx-parse.sh")
[ -n "${SUDO_USER:-}" ] && ktx_parse=(sudo -u "$SUDO_USER" "${ktx_parse[@]}")
"${ktx_parse[@]}" || echo "install-deps: could not install npm's ktx-parse (tests/ktx2); the KTX 2.0 reader checks will be skipped" >&2
