#!/usr/bin/env bash
# Installs every build, test and run dependency of iblab from Debian 12 packages.
# Idempotent; runs apt as root (directly, or through sudo when not root).
set -euo pipefail
packages=(
  cmake g++ make pkg-config git
  libimgui-dev libstb-dev libglfw3-dev libglm-dev libepoxy-dev
  libopenimageio-dev libimath-dev libtinygltf-dev libcli11-dev nlohmann-json3-dev libgtest-dev libx11-dev zlib1g-dev
  # scripts/fuzz.sh (run by CI): libFuzzer and the sanitizer runtimes of clang 14.
  clang-14 libclang-rt-14-dev
  # OpenGL through Mesa: EGL (headless) and GLX (windows), llvmpipe as the software driver.
  libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri libglx-mesa0
)
as_root=()
[ "$(id -u)" -eq 0 ] || as_root=(sudo)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "install-deps: installing ${missing[*]}"
  "${as_root[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${as_root[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
