#pragma once
#include <filesystem>

namespace iblab::app {
// assets/ of the source tree (set at build time), or $IBLAB_ASSET_DIR when set.
std::filesystem::path assetDirectory();
inline std::filesystem::path shaderDirectory() { return assetDirectory() / "shaders"; }
}
