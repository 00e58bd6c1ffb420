#pragma once
#include <filesystem>

namespace iblab::app {
// Where the shaders, bundled environments and models are (the first that exists):
// $IBLAB_ASSET_DIR; ../share/iblab beside the executable (an installed iblab: cmake --install
// or the Debian package); the source tree's assets/ (set at build time, so that a build runs
// from its checkout and shader edits hot-reload); iblab/ under each of $XDG_DATA_DIRS.
std::filesystem::path assetDirectory();
inline std::filesystem::path shaderDirectory() { return assetDirectory() / "shaders"; }
}
