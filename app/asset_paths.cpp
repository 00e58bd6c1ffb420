#include "asset_paths.hpp"

#include <cstdlib>

namespace iblab::app {
std::filesystem::path assetDirectory()
{
    if (const char* overridden = std::getenv("IBLAB_ASSET_DIR"); overridden && *overridden) return overridden;
    return IBLAB_ASSET_DIR;
}
}
